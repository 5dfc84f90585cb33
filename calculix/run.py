"""Run ccx on a deck in a work directory, cached by the hash of the deck text.

out/calculix/<sha256 of the deck>/ holds job.inp, job.dat, ccx.log and
run.json (wall time, ccx version, threads).  A deck seen before is not run
again.  ccx exits 0 even when it stops on an error, so success is its
"Job finished" line without an *ERROR line; a failure raises CcxError with the
first error lines and keeps the work directory (out/calculix/failed-<hash>/)
for inspection.
"""
import hashlib
import json
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

from gen.scene import ROOT

CACHE = ROOT / "out" / "calculix"
CCX = "ccx"


class CcxError(RuntimeError):
    pass


def deck_hash(text):
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def ccx_env(threads=1):
    env = dict(os.environ)
    for k in ("OMP_NUM_THREADS", "CCX_NPROC_STIFFNESS", "CCX_NPROC_EQUATION_SOLVER", "CCX_NPROC_RESULTS",
              "NUMBER_OF_CPUS"):
        env[k] = str(threads)
    return env


def run_deck(text, cache=CACHE, threads=1, timeout=3600, refresh=False):
    """Directory with the results of `text` (run now unless cached) and its run.json dict."""
    if shutil.which(CCX) is None:
        raise CcxError("ccx not found: install Debian's calculix-ccx (./build.sh deps)")
    h = deck_hash(text)
    cache = Path(cache)
    done = cache / h
    if (done / "run.json").exists() and not refresh:
        return done, json.loads((done / "run.json").read_text())
    cache.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=f"tmp-{h[:12]}-", dir=cache))
    (work / "job.inp").write_text(text, encoding="utf-8")
    t0 = time.perf_counter()
    try:
        r = subprocess.run([CCX, "-i", "job"], cwd=work, env=ccx_env(threads), capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        _keep_failed(work, cache, h)
        raise CcxError(f"ccx did not finish within {timeout} s (work directory {cache / ('failed-' + h)})")
    wall = time.perf_counter() - t0
    log = r.stdout + r.stderr
    (work / "ccx.log").write_text(log, encoding="utf-8")
    errors = [ln.strip() for ln in log.splitlines() if "*ERROR" in ln]
    if r.returncode != 0 or errors or "Job finished" not in log:
        where = _keep_failed(work, cache, h)
        detail = "; ".join(errors[:3]) or (log.strip().splitlines() or ["no output"])[-1]
        raise CcxError(f"ccx failed (exit {r.returncode}): {detail} (log: {where / 'ccx.log'})")
    version = next((ln.strip() for ln in log.splitlines() if "CalculiX Version" in ln), "")
    info = {"wall_s": wall, "ccx": version, "threads": threads, "hash": h}
    for junk in ("job.frd", "spooles.out", "job.12d"):       # large or unused outputs
        (work / junk).unlink(missing_ok=True)
    (work / "run.json").write_text(json.dumps(info, indent=1) + "\n")
    if done.exists():                                        # a concurrent run got there first
        shutil.rmtree(work, ignore_errors=True)
    else:
        os.replace(work, done)
    return done, json.loads((done / "run.json").read_text())


def _keep_failed(work, cache, h):
    dest = cache / f"failed-{h}"
    shutil.rmtree(dest, ignore_errors=True)
    os.replace(work, dest)
    return dest
