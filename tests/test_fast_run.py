"""A repeated `./build.sh run` (same scene file, same --set, nothing rebuilt since)
reuses the model file and the solver of the earlier run without the scene
compiler (gen/pipeline.py with gen/cache.py), with the same results, warnings and messages; any
change to the scene, to a --set, to a source file or to the solver binary takes
the full path again.  (Its start-up time is measured in ./build.sh bench, not here.)"""
import json
import os
import shutil
import signal
import tempfile
import time
from pathlib import Path

from util import BUILD, ROOT, ensure_dir, run_cli

REUSED = "model and solver of an identical earlier run"


def out_dir():
    return Path(tempfile.mkdtemp(prefix="bk-fast-", dir=ensure_dir(BUILD / "runs")))


def run(scene, sets=(), verbose=True):
    out = out_dir()
    args = ["run", str(scene), "--out", str(out)] + (["--verbose"] if verbose else [])
    for s in sets:
        args += ["--set", s]
    r = run_cli(args)
    assert r.returncode == 0, r.stderr[-3000:]
    return r, json.loads((out / "summary.json").read_text()), out


def same_results(a, b):
    assert a["sensors"] == b["sensors"] and a["newton_iterations"] == b["newton_iterations"], (a, b)
    assert a["warnings"] == b["warnings"]


def test_identical_run_reuses_the_model_with_the_same_results():
    sets = ["beam.arm.elements=6", "load.0.value.2=-37.5"]
    r1, s1, o1 = run("cantilever_bend_100N", sets)
    r2, s2, o2 = run("cantilever_bend_100N", sets)
    assert REUSED in r2.stderr, r2.stderr[-2000:]
    same_results(s1, s2)
    assert (o1 / "model.dat").read_bytes() == (o2 / "model.dat").read_bytes()
    assert "results in" in r2.stdout and "Newton iterations" in r2.stdout


def test_another_set_or_an_edited_scene_takes_the_full_path():
    d = out_dir()
    scene = d / "bend.toml"
    shutil.copy(ROOT / "models" / "cantilever_bend_100N.toml", scene)
    _, s1, _ = run(scene, ["beam.arm.elements=5"])
    r, s2, _ = run(scene, ["beam.arm.elements=5"])
    assert REUSED in r.stderr
    r, s3, _ = run(scene, ["beam.arm.elements=6"])
    assert REUSED not in r.stderr
    text = scene.read_text()
    assert "-100.0" in text
    scene.write_text(text.replace("-100.0", "-50.0"))
    r, s4, _ = run(scene, ["beam.arm.elements=5"])
    assert REUSED not in r.stderr
    assert abs(s4["sensors"]["tip"]["displacement"][2]) < abs(s1["sensors"]["tip"]["displacement"][2])


def test_fingerprint_follows_every_source_file():
    from gen.cache import fingerprint
    d = out_dir()
    (d / "gen" / "sub").mkdir(parents=True)
    (d / "runtime").mkdir()
    (d / "gen" / "sub" / "a.py").write_text("x = 1\n")
    (d / "runtime" / "b.c").write_text("int b;\n")
    src = (("gen", True), ("runtime", False))
    f0 = fingerprint(d, src)
    assert "gen/sub/a.py" in f0 and "runtime/b.c" in f0
    (d / "gen" / "sub" / "a.py").write_text("x = 2\n")
    f1 = fingerprint(d, src)
    assert f1 != f0
    os.utime(d / "runtime" / "b.c", ns=(1, 1))
    assert fingerprint(d, src) != f1


def test_another_element_keeps_the_entry_and_a_relinked_solver_is_not_reused():
    """Solvers are kept by pair set (gen/cache.py): a run of the same scene
    with another element gets another solver and leaves the first's, so the
    earlier entry still applies (out/bin/SCENE links to the last run's solver:
    other tests may relink it meanwhile, so it is only read after the first); a
    solver binary changed since the entry was recorded is not reused."""
    sets = ["beam.arm.elements=4", "load.0.value.2=-12.5"]
    link = ROOT / "out" / "bin" / "cantilever_bend_10N"
    _, s1, o1 = run("cantilever_bend_10N", sets)
    first = link.resolve()
    run("cantilever_bend_10N", sets + ["beam.arm.element=ancf3363"])
    assert first.exists() and first.name.startswith("solver_")
    r, s2, o3 = run("cantilever_bend_10N", sets)
    assert REUSED in r.stderr
    same_results(s1, s2)
    assert (o1 / "model.dat").read_bytes() == (o3 / "model.dat").read_bytes()
    st = first.stat()
    os.utime(first, ns=(st.st_atime_ns, st.st_mtime_ns + 1000))     # as a relink would
    r, s3, _ = run("cantilever_bend_10N", sets)
    assert REUSED not in r.stderr
    same_results(s1, s3)


def test_scene_warnings_on_a_reused_run():
    sets = ["dynamic.t_end=0.05"]
    r1, s1, _ = run("pendulum_soft_ancf", sets)
    r2, s2, _ = run("pendulum_soft_ancf", sets)
    assert REUSED in r2.stderr
    assert s2["warnings"] and s2["warnings"] == s1["warnings"]
    assert "warning: pendulum_soft_ancf: " in r2.stderr and "Poisson locking" in r2.stderr


def test_ctrl_c_during_a_reused_run():
    import subprocess
    from util import ENV
    sets = ["dynamic.t_end=4", "dynamic.output_every=1"]
    run("double_pendulum_soft_gef", sets, verbose=False)           # records the entry
    out = out_dir()
    args = [str(ROOT / "build.sh"), "run", "double_pendulum_soft_gef", "--verbose", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV,
                         start_new_session=True)
    t0 = time.time()
    while not ((out / "sensors.csv").exists() and sum(1 for _ in open(out / "sensors.csv")) > 40):
        assert p.poll() is None and time.time() - t0 < 120, "the run ended before it could be interrupted"
        time.sleep(0.02)
    os.killpg(p.pid, signal.SIGINT)
    so, se = p.communicate(timeout=120)
    assert REUSED in se, se[-2000:]
    assert p.returncode == 130 and "Traceback" not in se, (p.returncode, se[-2000:])
    s = json.loads((out / "summary.json").read_text())
    assert s["interrupted"] is True and s["signal"] == "SIGINT" and s["steps"] >= 20


def test_cache_keeps_the_newest_entries_only(monkeypatch):
    import gen.cache as fr
    d = out_dir()
    monkeypatch.setattr(fr, "CACHE", str(d))
    for i in range(5):
        for ext in (".run", ".dat"):
            (d / f"k{i}{ext}").write_text("x")
        os.utime(d / f"k{i}.run", ns=(i + 1, (i + 1) * 10**9))
    fr.prune(limit=2, slack=3)                    # 5 entries: not more than 2 + 3, all kept
    assert len(list(d.iterdir())) == 10
    fr.prune(limit=2, slack=2)                    # more than 2 + 2: down to the newest 2
    assert sorted(p.name for p in d.iterdir()) == ["k3.dat", "k3.run", "k4.dat", "k4.run"]
