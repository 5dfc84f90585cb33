"""The writer thread (runtime/base/filewriter.c) asked without waiting: a
buffer taken only when one is free (bk_filewriter_slot with wait 0: a ParaView
frame that finds every one taken is written on the solve thread instead, vtk.c) and
a call's state (bk_filewriter_done: results.h5's states go on filling a set
while the thread still writes the other, h5.c).  The C harness
tests/filewriter_check.c holds the thread in a call and checks each answer,
under AddressSanitizer + UBSan."""
import subprocess
import tempfile
from pathlib import Path

from util import BUILD, build_runtime_program, ensure_dir


def test_buffers_and_calls_asked_without_waiting():
    exe = build_runtime_program(["filewriter_check.c"], "filewriter_check", "sanitize")
    d = Path(tempfile.mkdtemp(prefix="bk-fw-", dir=ensure_dir(BUILD / "runs")))
    r = subprocess.run([str(exe), str(d)], capture_output=True, text=True, timeout=120)
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr, r.stderr[-4000:]
    got = dict(line.split("=") for line in r.stdout.split())
    assert got == {k: "1" for k in ("held_not_done", "all_free", "none_free_without_wait", "held_done",
                                    "free_again", "drained", "files", "unthreaded_done", "unthreaded_free",
                                    "unthreaded_file")}, (got, r.stderr[-2000:])
    assert r.returncode == 0, r.stderr[-2000:]
