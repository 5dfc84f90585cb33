"""Data derived from a file, kept between runs: the parsed scene TOML, the
kernel index, what gen/contract.py reads from runtime/bk_kernel.h.

A run of a built scene with new `--set` values must not pay for parsing the
same files again (nor for importing tomllib, json and re to do it).  Entries
live in out/cache/derived, are named by the content hash of the file they
come from and stored with marshal; a missing, unreadable or foreign entry is
recomputed, so the cache never changes a result.  Standard library os and
marshal only.
"""
import marshal
import os

try:                                   # hashlib's OpenSSL binding alone costs ~5 ms to import
    from _sha256 import sha256
except ImportError:                    # pragma: no cover
    from hashlib import sha256

DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "out", "cache", "derived")
MAX_ENTRIES = 400
_VERSION = 1


def derived(kind, data, compute):
    """compute(data) for the bytes `data`, through the cache (`kind` names what
    is computed).  A value marshal cannot store (a TOML date, say) is returned
    and not kept; an exception of compute propagates and nothing is kept."""
    h = sha256(data).hexdigest()[:40]
    path = os.path.join(DIR, f"{kind}-{h}.marshal")
    try:
        with open(path, "rb") as fh:
            version, value = marshal.load(fh)
        if version == _VERSION:
            return value
    except (OSError, EOFError, ValueError, TypeError):
        pass
    value = compute(data)
    try:
        blob = marshal.dumps((_VERSION, value))
    except ValueError:
        return value
    try:
        os.makedirs(DIR, exist_ok=True)
        tmp = f"{path}.{os.getpid()}.tmp"
        with open(tmp, "wb") as fh:
            fh.write(blob)
        os.replace(tmp, path)
        _prune()
    except OSError:
        pass                           # no cache: the next run parses again
    return value


def _prune():
    """Keep the MAX_ENTRIES most recently written entries."""
    with os.scandir(DIR) as it:
        entries = sorted((e.stat().st_mtime_ns, e.path) for e in it if e.name.endswith(".marshal"))
    for _, p in entries[:max(0, len(entries) - MAX_ENTRIES)]:
        try:
            os.unlink(p)
        except OSError:
            pass
