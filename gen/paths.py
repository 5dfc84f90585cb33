"""Paths given on the command line are the caller's: build.sh changes to the
repository and passes the caller's working directory in BK_CALLER_CWD."""
import os
from pathlib import Path


def user_path(p):
    """p as the user meant it: absolute, or relative to the caller's directory."""
    p = Path(p).expanduser()
    if p.is_absolute():
        return p
    return Path(os.environ.get("BK_CALLER_CWD") or os.getcwd()) / p
