"""Paths given on the command line are the caller's: build.sh changes to the
repository and passes the caller's working directory in BK_CALLER_CWD.  Also
where a scene name points and how a run directory is prepared.  Standard
library os only (no pathlib at import): the run pipeline (gen/pipeline.py)
uses these on a repeated run too, before any scene compiler is imported."""
import os

MARKER = ".beamkit-run"            # in every directory made by ./build.sh run


def caller_path(p):
    """p (a str) as the user meant it: absolute, or relative to the caller's directory."""
    p = os.path.expanduser(str(p))
    return p if os.path.isabs(p) else os.path.join(os.environ.get("BK_CALLER_CWD") or os.getcwd(), p)


def user_path(p):
    """caller_path as a pathlib.Path."""
    from pathlib import Path
    return Path(caller_path(p))


def scene_location(spec, models):
    """(path, is a name in models/) of a scene argument: a `.toml` file or a path
    with a `/` is the caller's, anything else models/SPEC.toml."""
    spec = str(spec)
    if spec.endswith(".toml") or "/" in spec:
        return caller_path(spec), False
    return os.path.join(str(models), f"{spec}.toml"), True


def prepare_run_dir(out):
    """Create or clear a results directory (never one with foreign files) and mark
    it as made by ./build.sh run.  Returns None, or why it cannot be used."""
    out = str(out)
    if os.path.exists(out):
        if not os.path.isdir(out):
            return f"error: --out {out}: exists and is not a directory"
        entries = os.listdir(out)
        if entries and not os.path.exists(os.path.join(out, MARKER)):
            return (f"error: --out {out}: directory exists, is not empty and was not made by "
                    f"./build.sh run; choose a new or empty directory")
        for e in entries:
            p = os.path.join(out, e)
            if e == MARKER:
                continue
            if os.path.isdir(p) and not os.path.islink(p):
                import shutil
                shutil.rmtree(p)
            else:
                os.unlink(p)
    else:
        os.makedirs(out)
    with open(os.path.join(out, MARKER), "w") as fh:
        fh.write("results of ./build.sh run; cleared on the next run into this directory\n")
    return None
