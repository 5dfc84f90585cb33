"""The `beamkit` command (bin/beamkit, issue 39 point 2): every ./build.sh
command as a subcommand, from any directory and through a link, with Debian's
/usr/bin/python3 whatever python3 comes first on PATH."""
import json
import os
import re
import subprocess

from util import ROOT

BEAMKIT = ROOT / "bin" / "beamkit"


def _commands(text):
    """The command names of a usage text (the first word of each entry)."""
    block = text[text.index("Commands:"):text.index("Results of a run")]
    return {m.group(1) for m in re.finditer(r"^  ([a-z]+|\(none\)|--help)\b", block, re.M)}


def _env_with_a_broken_python(tmp_path):
    """PATH with a python3 first that fails loudly (a virtualenv's that lacks sympy)."""
    fake = tmp_path / "fakebin"
    fake.mkdir()
    (fake / "python3").write_text("#!/bin/sh\necho 'the wrong python3' >&2\nexit 3\n")
    (fake / "python3").chmod(0o755)
    env = dict(os.environ)
    env["PATH"] = f"{fake}:{env.get('PATH', '/usr/bin:/bin')}"
    env.pop("PYTHONPATH", None)
    return env


def test_help_lists_every_build_sh_command_under_its_own_name():
    b = subprocess.run([str(BEAMKIT), "--help"], capture_output=True, text=True, timeout=60)
    s = subprocess.run([str(ROOT / "build.sh"), "--help"], capture_output=True, text=True, timeout=60)
    assert b.returncode == 0 and s.returncode == 0
    assert b.stdout.startswith("usage: beamkit COMMAND")
    assert _commands(b.stdout) == (_commands(s.stdout) - {"(none)"}) | {"setup"}, (_commands(b.stdout),
                                                                                   _commands(s.stdout))
    assert "./build.sh" not in b.stdout
    bad = subprocess.run([str(BEAMKIT), "no-such-command"], capture_output=True, text=True, timeout=60)
    assert bad.returncode == 64 and "beamkit --help lists the commands" in bad.stderr


def test_runs_a_scene_from_another_directory_through_a_link_with_another_python_first(tmp_path):
    env = _env_with_a_broken_python(tmp_path)
    link_dir = tmp_path / "mybin"
    link_dir.mkdir()
    (link_dir / "beamkit").symlink_to(BEAMKIT)
    work = tmp_path / "work"
    work.mkdir()
    r = subprocess.run([str(link_dir / "beamkit"), "scenes"], capture_output=True, text=True, env=env, cwd=work,
                       timeout=300)
    assert r.returncode == 0 and "cantilever_bend_10N" in r.stdout, r.stderr[-2000:]
    r = subprocess.run([str(link_dir / "beamkit"), "run", "cantilever_bend_10N", "--quiet", "--out", "res"],
                       capture_output=True, text=True, env=env, cwd=work, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "the wrong python3" not in r.stderr
    s = json.loads((work / "res" / "summary.json").read_text())     # --out relative to the caller
    assert s["converged"] is True
