"""--threads N (issue 38 point 2): the solver's element evaluation on N OpenMP
threads from the command line and the API, the same bits whatever N
(sensors, reactions, summary but its timings and thread count), the count in
summary.json; a bad count is a usage error."""
import json
import re
import tempfile
from pathlib import Path

from util import BUILD, ensure_dir, run_cli


def _run(extra):
    out = Path(tempfile.mkdtemp(prefix="bk-thr-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", "cantilever_bend_100N", "--quiet", "--out", str(out), "--set", "beam.arm.elements=3000"]
                + extra)
    assert r.returncode == 0, r.stderr[-2000:]
    return out


def _strip(text):
    return re.sub(r'"(\w+_s|threads)": [0-9.e+-]+,?\n', "", text)


def test_results_are_the_same_bits_for_one_and_two_threads():
    one, two = _run(["--threads", "1"]), _run(["--threads", "2"])
    assert json.loads((one / "summary.json").read_text())["threads"] == 1
    assert json.loads((two / "summary.json").read_text())["threads"] == 2
    for name in ("sensors.csv", "reactions.csv", "newton.csv"):
        if (one / name).exists():
            assert (one / name).read_bytes() == (two / name).read_bytes(), name
    assert _strip((one / "summary.json").read_text()) == _strip((two / "summary.json").read_text())
    from beamkit.api import Scene
    api = Scene("cantilever_bend_100N").run({"beam.arm.elements": 3000}, out=tempfile.mkdtemp(dir=BUILD / "runs"),
                                            threads=2)
    assert json.loads((Path(api.dir) / "summary.json").read_text())["threads"] == 2


def test_a_bad_thread_count_is_a_usage_error():
    r = run_cli(["run", "cantilever_bend_100N", "--threads", "0"])
    assert r.returncode == 64 and "--threads: expected an integer from 1 to 1024, found '0'" in r.stderr


def test_split_solvers_give_the_same_bits_for_one_and_two_threads():
    """Seed Table 3 at 2,000 elements (24,012 unknowns, above BK_BANDSPLIT_MIN
    of runtime/linalg/bandsplit.h): the Newton solves take the band LU in two
    halves and the stability checks (with eigenvalues: inverse iteration through
    the factor) the band L D L^T in two halves (linalg/symsplit.c); the section
    forces and the frames' points are computed on the threads.  Every table,
    both ParaView frames and the summary (but its timings and thread count) are
    the same bytes with 1 and 2 threads.  A determinism check of our own
    results (no reference values)."""
    import subprocess
    from util import ENV, ROOT
    split_min = int(re.search(r"#define BK_BANDSPLIT_MIN (\d+)",
                              (ROOT / "runtime/linalg/bandsplit.h").read_text()).group(1))
    outs = []
    for threads in (1, 2):
        out = Path(tempfile.mkdtemp(prefix=f"bk-split{threads}-", dir=ensure_dir(BUILD / "runs")))
        r = subprocess.run([str(ROOT / "build.sh"), "run", "cantilever_bend_100N_nu03", "--quiet", "--out", str(out),
                            "--set", "beam.arm.elements=2000", "--set", "static.eigenvalues=true"],
                           capture_output=True, text=True, env=dict(ENV, OMP_NUM_THREADS=str(threads)), timeout=600)
        assert r.returncode == 0, r.stderr[-2000:]
        outs.append(out)
    one, two = outs
    s = json.loads((one / "summary.json").read_text())
    assert s["dofs"] >= split_min and s["threads"] == 1
    assert json.loads((two / "summary.json").read_text())["threads"] == 2
    assert s["stability"]["eig_min"] > 0.0, s["stability"]
    names = ("sensors.csv", "reactions.csv", "newton.csv", "sections.csv", "stability.csv", "step_000000.vtu",
             "step_000001.vtu")
    for name in names:
        assert (one / name).exists(), name
        assert (one / name).read_bytes() == (two / name).read_bytes(), name
    assert _strip((one / "summary.json").read_text()) == _strip((two / "summary.json").read_text())
