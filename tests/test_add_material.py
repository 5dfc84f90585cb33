"""Adding a material is one file: a Yeoh law written into a temporary copy of the
generator is discovered, derived, compiled and finite-difference checked with no
other edit."""
import shutil
import subprocess
import tempfile
from pathlib import Path

from util import ENV, PY, ROOT

YEOH = '''"""Yeoh: W = c1 (Ibar1 - 3) + c2 (Ibar1 - 3)^2 + c3 (Ibar1 - 3)^3 + kappa/2 (J - 1)^2."""
from sympy import Rational

NAME = "yeoh"
TITLE = "Yeoh"
PARAMS = ("c1", "c2", "c3", "kappa")
INPUTS = ((PARAMS, lambda *v: v),)


def energy(I1, I2, J, p):
    Ib = J**Rational(-2, 3) * I1
    return p["c1"] * (Ib - 3) + p["c2"] * (Ib - 3)**2 + p["c3"] * (Ib - 3)**3 + p["kappa"] / 2 * (J - 1)**2
'''


def test_yeoh_in_one_file():
    tmp = Path(tempfile.mkdtemp(prefix="bk-yeoh-"))
    for d in ("gen", "runtime", "tests"):
        shutil.copytree(ROOT / d, tmp / d, ignore=shutil.ignore_patterns("__pycache__"))
    (tmp / "gen" / "materials" / "yeoh.py").write_text(YEOH)
    out = tmp / "kernels"
    env = dict(ENV, PYTHONPATH=str(tmp))
    r = subprocess.run([PY, "-m", "gen.cli", "gen", "--force", "--only", "loads,ancf3243_yeoh",
                        "--out", str(out)], cwd=tmp, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    r = subprocess.run([PY, "-m", "gen.cli", "gen", "--force", "--only", "ancf3243", "--out", str(out)],
                       cwd=tmp, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert (out / "ancf3243_yeoh.c").exists()
    table = out / "table.c"
    table.write_text('#include "bk_kernel.h"\n'
                     "extern const bk_pair bk_pair_ancf3243_yeoh_full, bk_pair_ancf3243_yeoh_sri;\n"
                     "const bk_pair *const bk_linked_pairs[] = {&bk_pair_ancf3243_yeoh_full, "
                     "&bk_pair_ancf3243_yeoh_sri};\nconst int bk_nlinked_pairs = 2;\n")
    exe = tmp / "kernel_check"
    r = subprocess.run(["cc", "-std=c11", "-O1", "-Wall", "-Wextra", "-fsanitize=address,undefined",
                        f"-I{tmp / 'runtime'}", f"-I{out}", str(tmp / "tests" / "kernel_check.c"),
                        str(out / "ancf3243.c"), str(out / "ancf3243_yeoh.c"), str(table), "-o", str(exe), "-lm"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    r = subprocess.run([str(exe), "20"], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    lines = [dict(kv.split("=", 1) for kv in l.split()) for l in r.stdout.splitlines()]
    assert len(lines) == 4, r.stdout
    for d in lines:
        assert float(d["fd_force"]) <= 1e-6 and float(d["fd_tangent"]) <= 1e-6, d
        assert float(d["rigid_force"]) <= 1e-10 and float(d["rigid_energy"]) <= 1e-10, d
    shutil.rmtree(tmp)
