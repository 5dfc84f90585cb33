"""The launcher of repeated runs (frontend/, out/bin/run-cached): `./build.sh
run` of a scene run before with the same --set values and nothing rebuilt
since starts the solver without Python.  It is a second implementation of the
Python front end's repeated run (gen/cache.py key, gen/pipeline.py run,
gen/run_summary.py print_summary), so these tests hold the two against each
other: the same cache key, the same files, the same console output, the same
exit status; a run it cannot take goes to Python unchanged.  (Its speed is in
./build.sh bench, not here.)"""
import json
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest

from util import BUILD, ENV, ROOT, ensure_dir, run_cli

LAUNCHER = ROOT / "out" / "bin" / "run-cached"
FRONTEND = ROOT / "frontend"
ONLY = {"BK_RUN_CACHED_ONLY": "1"}          # a run the launcher cannot take exits 3
PYTHON = {"BK_NO_FAST_RUN": "1"}            # the Python front end only


def out_dir():
    return Path(tempfile.mkdtemp(prefix="bk-cached-", dir=ensure_dir(BUILD / "runs")))


def launcher():
    """out/bin/run-cached, built by build.sh's first run when missing or stale."""
    r = run_cli(["run", "cantilever_bend_100N", "--quiet", "--out", str(out_dir())])
    assert r.returncode == 0, r.stderr[-2000:]
    assert LAUNCHER.exists(), "build.sh did not build out/bin/run-cached"
    return LAUNCHER


def print_key(scene, sets):
    args = [str(launcher()), "--print-key", str(scene)]
    for s in sets:
        args += ["--set", s]
    r = subprocess.run(args, capture_output=True, text=True, env=dict(ENV, BK_ROOT=str(ROOT)), cwd=ROOT)
    assert r.returncode == 0, r.stderr
    return r.stdout.strip()


def test_the_launchers_key_is_the_python_front_ends():
    from gen import cache
    d = out_dir()
    odd = d / "a scene with spaces, ünïcode.toml"
    shutil.copy(ROOT / "models" / "cantilever_bend_100N.toml", odd)
    fp = cache.fingerprint()
    cases = [(ROOT / "models" / "cantilever_bend_100N.toml", []),
             (ROOT / "models" / "cantilever_modal.toml", ["beam.arm.elements=7", "material.alu.E=7e10"]),
             (odd, ["load.0.value.2=-1.5e1", "scene.name=ñame"])]
    for path, sets in cases:
        real = os.path.realpath(path)
        want = cache.key(real, Path(real).read_bytes(), sets, fp)
        assert print_key(path, sets) == want, (path, sets)
    # a byte more in the scene is another key
    odd.write_bytes(odd.read_bytes() + b"\n")
    assert print_key(odd, cases[2][1]) != cache.key(os.path.realpath(odd), b"", cases[2][1], fp)


def test_sha256_against_hashlib():
    """The launcher's SHA-256 (constants computed, not listed) on messages of
    every length around the block and padding boundaries."""
    import hashlib
    src = ensure_dir(BUILD / "run_cached") / "sha_check.c"
    src.write_text(
        '#include "sha256.h"\n#include <stdio.h>\n#include <stdlib.h>\n'
        "int main(void) {\n"
        "    unsigned char m[300];\n"
        "    for (int i = 0; i < 300; i++) m[i] = (unsigned char)(i * 7 + 3);\n"
        "    for (int n = 0; n <= 300; n++) {\n"
        "        bk_sha256 h; char hex[65];\n"
        "        bk_sha256_init(&h);\n"
        "        for (int k = 0; k < n; k += 1 + n % 13)\n"
        "            bk_sha256_update(&h, m + k, (size_t)((k + 1 + n % 13 > n) ? n - k : 1 + n % 13));\n"
        "        bk_sha256_hex(&h, hex); puts(hex);\n"
        "    }\n    return 0;\n}\n")
    exe = src.with_suffix("")
    subprocess.run(["gcc", "-O1", "-std=c11", "-Wall", "-Wextra", "-Werror", "-fsanitize=address,undefined",
                    f"-I{FRONTEND}", str(src), str(FRONTEND / "sha256.c"), "-o", str(exe)], check=True)
    got = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout.split()
    m = bytes((i * 7 + 3) & 0xFF for i in range(300))
    assert got == [hashlib.sha256(m[:n]).hexdigest() for n in range(301)]


def without_timings(summary):
    return {k: v for k, v in summary.items() if not k.endswith("_s")}


def console(text, out):
    """The console text with the wall time and the results directory masked."""
    import re
    return re.sub(r"wall \d+\.\d+ s", "wall T s", text).replace(str(out), "OUT")


# (scene, --set values): one of each analysis the summary prints differently
SCENES = [("cantilever_bend_100N", ["beam.arm.elements=6"]),
          ("cantilever_bend_100N_nu03", []),                       # with a scene warning
          ("pendulum_soft_ancf", ["dynamic.t_end=0.02"]),          # scene warnings, dynamic
          ("cantilever_modal", []),
          ("column_buckling", []),
          ("tip_mass_cantilever", ["scene.analysis=dynamic", "dynamic.t_end=0.02"]),
          ("cantilever_euler_arc", [])]


@pytest.mark.parametrize("scene,sets", SCENES, ids=[s for s, _ in SCENES])
def test_a_repeated_run_gives_the_python_front_ends_files_and_output(scene, sets):
    args = []
    for s in sets:
        args += ["--set", s]
    a, b = out_dir(), out_dir()
    run_cli(["run", scene, "--out", str(a)] + args, env=PYTHON)             # records the entry
    ra = run_cli(["run", scene, "--out", str(a)] + args, env=PYTHON)        # Python's repeated run
    rb = run_cli(["run", scene, "--out", str(b)] + args, env=ONLY)          # must be the launcher's
    assert ra.returncode == rb.returncode, (ra.stderr[-2000:], rb.stderr[-2000:])
    assert "run-cached:" not in rb.stderr, rb.stderr
    assert console(rb.stdout, b) == console(ra.stdout, a)
    assert console(rb.stderr, b) == console(ra.stderr, a)
    assert rb.stdout.count("\n") >= 2 and "results in" in rb.stdout
    files_a = sorted(p.relative_to(a) for p in a.rglob("*"))
    assert files_a == sorted(p.relative_to(b) for p in b.rglob("*"))
    for rel in files_a:
        if rel.name == "summary.json":
            sa, sb = (json.loads((d / rel).read_text()) for d in (a, b))
            assert without_timings(sa) == without_timings(sb)
        elif (a / rel).is_file():
            assert (a / rel).read_bytes() == (b / rel).read_bytes(), rel
    # --quiet prints nothing, --verbose says the run was reused, as in Python
    rq = run_cli(["run", scene, "--quiet", "--out", str(b)] + args, env=ONLY)
    assert rq.returncode == ra.returncode and rq.stdout == ""
    rv = run_cli(["run", scene, "--verbose", "--out", str(b)] + args, env=ONLY)
    assert "model and solver of an identical earlier run" in rv.stderr


def test_a_run_it_cannot_take_goes_to_python_unchanged():
    d = out_dir()
    scene = d / "bend.toml"
    shutil.copy(ROOT / "models" / "cantilever_bend_100N.toml", scene)
    out = d / "run"
    r = run_cli(["run", str(scene), "--out", str(out), "--quiet"], env=ONLY)
    assert r.returncode == 3 and "no identical earlier run" in r.stderr
    r = run_cli(["run", str(scene), "--out", str(out), "--quiet"])     # Python, records it
    assert r.returncode == 0, r.stderr
    tip = json.loads((out / "summary.json").read_text())["sensors"]["tip"]["displacement"][2]
    assert run_cli(["run", str(scene), "--out", str(out), "--quiet"], env=ONLY).returncode == 0
    # an edited scene: a miss, and through Python the new result
    scene.write_text(scene.read_text().replace("-100.0", "-50.0"))
    assert run_cli(["run", str(scene), "--out", str(out), "--quiet"], env=ONLY).returncode == 3
    r = run_cli(["run", str(scene), "--out", str(out), "--quiet"])
    assert r.returncode == 0, r.stderr
    tip2 = json.loads((out / "summary.json").read_text())["sensors"]["tip"]["displacement"][2]
    assert abs(tip2) < abs(tip) * 0.9
    # a results directory with foreign files: Python's error, nothing removed
    foreign = d / "foreign"
    foreign.mkdir()
    (foreign / "mine.txt").write_text("keep me")
    r = run_cli(["run", str(scene), "--out", str(foreign), "--quiet"], env=ONLY)
    assert r.returncode == 3 and "results directory" in r.stderr
    r = run_cli(["run", str(scene), "--out", str(foreign), "--quiet"])
    assert r.returncode == 1 and "was not made by ./build.sh run" in r.stderr
    assert (foreign / "mine.txt").read_text() == "keep me" and len(list(foreign.iterdir())) == 1
    # forms it does not take: --sanitize goes to Python
    r = run_cli(["run", str(scene), "--sanitize", "--out", str(out), "--quiet"], env=ONLY)
    assert r.returncode == 3 and "common forms" in r.stderr


def test_launcher_is_clean_under_sanitizers_and_valgrind():
    """The launcher's sources built with -Werror, then with AddressSanitizer and
    UBSan, and for valgrind memcheck, each running a repeated run and its summary."""
    base = ["gcc", "-std=c11", "-Wall", "-Wextra", "-Werror", "-g"] + [str(p) for p in FRONTEND.glob("*.c")]
    d = ensure_dir(BUILD / "run_cached")
    asan, plain = d / "run-cached-asan", d / "run-cached-memcheck"
    subprocess.run(base + ["-O1", "-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-o", str(asan)],
                   check=True)
    subprocess.run(base + ["-O1", "-march=x86-64-v2", "-o", str(plain)], check=True)
    sets = ["--set", "beam.arm.elements=5"]
    out = out_dir()
    assert run_cli(["run", "cantilever_modal", "--out", str(out)] + sets, env=PYTHON).returncode == 0
    env = dict(ENV, BK_ROOT=str(ROOT), BK_RUN_CACHED_ONLY="1", BK_CALLER_CWD=str(ROOT))
    from gen.pipeline import memcheck_command     # (the one valgrind command line; its exit status 99)
    args = ["cantilever_modal", "--out", str(out)] + sets
    for cmd in ([str(asan)] + args, memcheck_command([str(plain)] + args)):
        r = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT, timeout=300)
        assert r.returncode == 0, (cmd[0], r.stderr[-3000:])
        assert "frequency (Hz)" in r.stdout and "ERROR: AddressSanitizer" not in r.stderr


@pytest.mark.parametrize("signo,status", [(2, 130), (15, 143)], ids=["SIGINT", "SIGTERM"])
def test_a_quiet_repeated_run_becomes_the_solver_and_stops_on_a_signal(signo, status):
    """--quiet prints nothing after the solve, so the launcher execs the solver:
    the command's process is the solver itself, started with SIGINT / SIGTERM
    blocked (a signal stays pending until its poll).  Signalled mid-run it stops
    as the Python front end's run does: exit 130 / 143, summary.json
    interrupted, the scene's warnings first in it (from the model file)."""
    import signal
    import time
    sets = ["--set", "dynamic.t_end=4", "--set", "dynamic.output_every=1"]
    out = out_dir()
    r = run_cli(["run", "pendulum_soft_ancf", "--quiet", "--out", str(out)] + sets, env=PYTHON)  # records it
    assert r.returncode == 0, r.stderr[-2000:]
    scene_warnings = [w for w in json.loads((out / "summary.json").read_text())["warnings"] if "locking" in w]
    assert scene_warnings
    out = out_dir()
    p = subprocess.Popen([str(ROOT / "build.sh"), "run", "pendulum_soft_ancf", "--quiet", "--out", str(out)] + sets,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=dict(ENV, **ONLY),
                         start_new_session=True)
    t0 = time.time()
    while not ((out / "sensors.csv").exists() and sum(1 for _ in open(out / "sensors.csv")) > 40):
        assert p.poll() is None and time.time() - t0 < 120, "the run ended before it could be interrupted"
        time.sleep(0.01)
    assert os.path.basename(os.readlink(f"/proc/{p.pid}/exe")).startswith("solver_")
    os.kill(p.pid, signo)
    so, se = p.communicate(timeout=120)
    assert p.returncode == status and so == "" and "run-cached:" not in se, (p.returncode, se[-2000:])
    s = json.loads((out / "summary.json").read_text())
    assert s["interrupted"] is True and s["signal"] == signal.Signals(signo).name and s["steps"] >= 20
    assert s["warnings"][:len(scene_warnings)] == scene_warnings


def _strace_works():
    if shutil.which("strace") is None:
        return False
    r = subprocess.run(["strace", "-f", "-qq", "-e", "trace=execve", "-o", os.devnull, "/bin/true"],
                       capture_output=True, text=True)
    return r.returncode == 0


@pytest.mark.skipif(not _strace_works(), reason="strace is not installed or may not trace here")
def test_a_new_run_starts_python_without_the_shells_once_the_packages_are_stamped():
    """A run the launcher cannot take (a new --set value) starts Python directly, as
    build.sh's `run` does, when build.sh's package stamp is no older than build.sh;
    else through build.sh (which checks the packages).  Both give the same results,
    and a relative --out is the caller's either way."""
    launcher()
    stamp = ROOT / "out" / ".deps-installed"
    assert stamp.exists(), "build.sh's first run writes out/.deps-installed"
    work = out_dir()

    def run(tag, value):
        trace = work / f"{tag}.trace"
        r = subprocess.run(["strace", "-f", "-qq", "-e", "trace=execve", "-o", str(trace), str(ROOT / "build.sh"),
                            "run", "cantilever_bend_100N_nu03", "--quiet", "--out", tag,
                            "--set", f"material.alu.E={value!r}"],
                           capture_output=True, text=True, cwd=work, timeout=600,
                           env={k: v for k, v in ENV.items() if k != "BK_CALLER_CWD"})   # (work is the caller's)
        assert r.returncode == 0, r.stderr[-2000:]
        started = [line.split('execve("', 1)[1].split('"', 1)[0] for line in trace.read_text().splitlines()
                   if 'execve("' in line and "= 0" in line]
        return started, json.loads((work / tag / "summary.json").read_text())

    value = 7.2e10 * (1 + 1e-9 * (os.getpid() % 100000 + 1))     # a value no earlier run used
    direct, s1 = run("direct", value)
    assert "/usr/bin/python3" in direct and "/bin/bash" not in direct, direct
    before = stamp.stat()
    build_sh = (ROOT / "build.sh").stat()
    try:
        # another test's build.sh (the other worker's) renews a stale stamp
        # (ensure_deps): when it does so between the ageing below and the
        # launcher's look at the stamp, the run rightly starts Python directly;
        # then the stamp is aged again (a launcher that ignored the stamp
        # would start Python directly every time)
        for attempt in range(6):
            os.utime(stamp, ns=(before.st_atime_ns, build_sh.st_mtime_ns - 10**9))   # older than build.sh
            shells, s2 = run(f"shells{attempt}", value * (1 + 1e-9 * (attempt + 1)))
            if "/bin/bash" in shells:
                break
    finally:
        os.utime(stamp, ns=(before.st_atime_ns, before.st_mtime_ns))
    assert "/bin/bash" in shells and "/usr/bin/python3" in shells, shells
    assert s1["converged"] and s2["converged"]
    tip1, tip2 = s1["sensors"]["tip"]["displacement"][2], s2["sensors"]["tip"]["displacement"][2]
    assert abs(tip1 - tip2) <= 1e-6 * abs(tip1)          # E differs by 1e-9 relative


def test_the_launcher_starts_python_as_build_sh_does():
    """frontend/python_start.c starts the Python front end itself with
    build.sh run's command line: the interpreter, its flags and the -c code are
    the same strings in both files (a change to one must be made in the other)."""
    import re
    sh = (ROOT / "build.sh").read_text()
    m = re.search(r'exec "\$PY" (-S -X frozen_modules=on) -c \'([^\']*)\' \\\s*\n\s*run "\$@"', sh)
    assert m, "build.sh run's Python command line not found"
    flags, code = m.group(1).split(), m.group(2)
    assert re.search(r'^PY=/usr/bin/python3$', sh, re.M)
    c = (FRONTEND / "python_start.c").read_text()
    args = re.findall(r'cmd\[k\+\+\] = "([^"]*)";', c)
    assert args == flags + ["-c", code, "run"], (args, flags, code)
    assert '#define PYTHON "/usr/bin/python3"' in c


def test_python_takes_the_fingerprint_only_from_its_own_launcher():
    """gen/cache.py launcher_fingerprint: BK_FINGERPRINT ("PID:" and the
    fingerprint with tabs for its NULs, frontend/run_key.c) is taken when PID is
    the process's own -- the launcher execs Python, which keeps its pid -- and
    is then the fingerprint of the run key; with another pid (a value left in a
    user's environment) it is ignored and the folders are walked.  Either way
    it leaves the environment, so that no child inherits it."""
    code = ("import os, sys\n"
            "from gen import cache\n"
            "real = cache.fingerprint()\n"
            "fake = real.replace('runtime/', 'runtime/x', 1)\n"       # a fingerprint unlike the real one
            "pid = os.getpid() + int(sys.argv[1])\n"
            "os.environ['BK_FINGERPRINT'] = f'{pid}:' + fake.replace(chr(0), chr(9))\n"
            "got = cache.fingerprint_once()\n"
            "print(got == fake, got == real, 'BK_FINGERPRINT' in os.environ)\n")
    for offset, expected in ((0, "True False False"), (1, "False True False")):
        r = subprocess.run(["/usr/bin/python3", "-S", "-c", code, str(offset)], capture_output=True, text=True,
                           env=ENV, cwd=ROOT, timeout=120)
        assert r.returncode == 0, r.stderr[-2000:]
        assert r.stdout.split("\n")[0] == expected, (offset, r.stdout)


@pytest.mark.skipif(not _strace_works(), reason="strace is not installed or may not trace here")
def test_a_new_run_keys_its_record_with_the_launchers_fingerprint():
    """A run the launcher hands to Python (a new --set value) records its entry
    under the launcher's own key (so the launcher finds it the next time), and
    Python does not walk gen/ and runtime/ again: after its start no directory
    of runtime/ is opened."""
    launcher()
    work = out_dir()
    value = 7.2e10 * (1 + 1e-9 * (os.getpid() % 100000 + 7))     # a value no earlier run used
    sets = [f"material.alu.E={value!r}"]
    trace = work / "run.trace"
    r = subprocess.run(["strace", "-f", "-qq", "-e", "trace=execve,openat", "-o", str(trace), str(ROOT / "build.sh"),
                        "run", "cantilever_bend_100N_nu03", "--quiet", "--out", str(work / "run"), "--set", sets[0]],
                       capture_output=True, text=True, timeout=600, env=ENV)
    assert r.returncode == 0, r.stderr[-2000:]
    lines = trace.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if 'execve("/usr/bin/python3"' in line)
    walked = [line for line in lines[start:] if f'"{ROOT}/runtime' in line and "O_DIRECTORY" in line]
    assert not walked, walked[:3]
    key = print_key(ROOT / "models" / "cantilever_bend_100N_nu03.toml", sets)
    assert (ROOT / "out" / "cache" / "run" / f"{key}.run").exists()
    r = subprocess.run([str(ROOT / "build.sh"), "run", "cantilever_bend_100N_nu03", "--quiet", "--out",
                        str(work / "again"), "--set", sets[0]], capture_output=True, text=True, timeout=600,
                       env=dict(ENV, **ONLY))
    assert r.returncode == 0, r.stderr[-2000:]            # the launcher took it


def test_a_launcher_older_than_its_sources_goes_back_to_be_rebuilt():
    """build.sh starts out/bin/run-cached without testing its sources' dates
    (19 shell tests cost 0.4 ms of a 10 ms command); the launcher compares
    them with its own date itself and, older than one of them, goes back to
    build.sh's `run` with BK_RUN_CACHED_STALE=1 (which rebuilds it), unless
    build.sh has just checked it (BK_RUN_CACHED_CHECKED=1: no loop with a
    source dated in the future).  Run in a stand-in repository whose build.sh
    prints what it was given."""
    root = out_dir()
    (root / "out" / "bin").mkdir(parents=True)
    (root / "frontend").mkdir()
    exe = root / "out" / "bin" / "run-cached"
    shutil.copy(launcher(), exe)
    src = root / "frontend" / "run_key.c"
    src.write_text("/* a source */\n")
    fake = root / "build.sh"
    fake.write_text('#!/bin/sh\necho "stale=${BK_RUN_CACHED_STALE:-} python=${BK_NO_FAST_RUN:-} $*"\n')
    fake.chmod(0o755)

    def go(extra=None):
        env = dict(ENV, BK_ROOT=str(root), **(extra or {}))
        for k in ("BK_RUN_CACHED_STALE", "BK_NO_FAST_RUN", "BK_RUN_CACHED_CHECKED"):
            if not extra or k not in extra:
                env.pop(k, None)
        r = subprocess.run([str(exe), "no_such_scene", "--quiet"], capture_output=True, text=True, env=env,
                           cwd=root)
        assert r.returncode == 0, r.stderr
        return r.stdout.strip()

    t = exe.stat().st_mtime_ns
    os.utime(src, ns=(t, t - 10**9))                    # older: on to Python (no such scene)
    assert go() == "stale= python=1 run no_such_scene --quiet"
    os.utime(src, ns=(t, t + 10**9))                    # newer: back to be rebuilt
    assert go() == "stale=1 python= run no_such_scene --quiet"
    os.utime(src, ns=(t, t))                            # as old as the launcher: newer is required
    assert go() == "stale=1 python= run no_such_scene --quiet"
    # just checked by build.sh: on, whatever the dates
    assert go({"BK_RUN_CACHED_CHECKED": "1"}) == "stale= python=1 run no_such_scene --quiet"
