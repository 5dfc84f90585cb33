"""The "Adding a material" recipe (docs/howto/add-material.md), followed as written (issue 39 point 3):
tests/test_docs_run.py's follow() runs the page in a scratch copy of the project
(its law file becomes gen/materials/gent.py, `./build.sh gen` derives the new
pairs, the kernel test checks them against finite differences, the page's
scene with law = "gent" runs and its deflection is the page's, beam theory).
Then, in the same copy: at small load the law agrees with the neo-Hookean law of
the same small-strain moduli (Gent tends to it as its strains stay far from the
limit); a value outside the law's declared range (Jm = -1) is refused with one
line naming the key, the range and the unit; so is a law file without RANGES."""
import csv
import re
import subprocess

import pytest

from test_docs_run import follow, steps
from util import ENV, ROOT, scratch_copy

PAGE = "docs/howto/add-material.md"


def _page():
    """{file or scene name: text} of the page's blocks."""
    return {s[1]: s[2] for s in steps((ROOT / PAGE).read_text()) if s[0] == "scene"}


def _sh(proj, *args, timeout=1800):
    """The copy's ./build.sh ARGS, relative paths from the copy's top."""
    env = dict(ENV, BK_CALLER_CWD=str(proj), PYTHONPATH=str(proj), PYTHONPYCACHEPREFIX=str(proj / "out" / "pycache"))
    return subprocess.run([str(proj / "build.sh"), *args], capture_output=True, text=True, cwd=proj,
                          timeout=timeout, env=env)


def _tip_uz(proj, out):
    rows = list(csv.DictReader(open(proj / out / "sensors.csv", newline="")))
    return float(rows[-1]["uz"])


def _with_material(scene, params):
    """The page's scene with the rubber's law and keys replaced."""
    return re.sub(r'(\[material\.rubber\]\n)(.*?)(\nrho)', lambda m: m.group(1) + params + m.group(3), scene,
                  count=1, flags=re.S)


@pytest.mark.slow
def test_the_recipe_adds_a_law_that_runs(tmp_path):
    blocks = _page()
    assert set(blocks) == {"gen/materials/gent.py", "rubber.toml"}, set(blocks)
    proj = scratch_copy(tmp_path / "repo")
    follow(PAGE, proj, proj)
    assert (proj / "out" / "kernels" / "ancf3363_gent.c").exists()
    uz_gent = _tip_uz(proj, "out/rubber")
    mu, kappa = 4e5, 4e7                     # the page's nearly incompressible rubber
    assert "mu = 4.0e5\nJm = 30.0\nkappa = 4.0e7" in blocks["rubber.toml"]
    lam = kappa - 2 * mu / 3
    (proj / "nh.toml").write_text(_with_material(blocks["rubber.toml"], f'law = "neo_hookean"\nlambda = {lam}\nmu = {mu}'))
    r = _sh(proj, "run", "nh.toml", "--quiet", "--out", "out/nh")
    assert r.returncode == 0, r.stderr[-2000:]
    uz_nh = _tip_uz(proj, "out/nh")
    assert abs(uz_gent / uz_nh - 1) < 1e-4, (uz_gent, uz_nh)
    (proj / "bad.toml").write_text(_with_material(blocks["rubber.toml"], f'law = "gent"\nmu = {mu}\nJm = -1.0\nkappa = {kappa}'))
    r = _sh(proj, "run", "bad.toml", "--quiet")
    errs = [x for x in r.stderr.splitlines() if x.startswith("error")]
    assert r.returncode == 1 and len(errs) == 1 and "material.rubber.Jm: expected a positive number" in errs[0], \
        r.stderr[-1000:]
    # a law file without RANGES is refused by the generator, naming the keys
    code = re.sub(r"^RANGES = .*\n", "", blocks["gen/materials/gent.py"], flags=re.M)
    (proj / "gen" / "materials" / "gent.py").write_text(code)
    r = _sh(proj, "gen")
    assert r.returncode != 0 and "RANGES gives no (lo, hi, unit) for mu, Jm, kappa" in r.stderr


def test_declared_ranges_are_checked_for_the_shipped_laws(tmp_path):
    """The shipped laws' RANGES reach the scene reader through the kernel index."""
    from gen.scene import load_index
    idx = load_index()
    for law, info in idx["materials"].items():
        keys = {k for i in info["inputs"] for k in i["keys"]}
        assert keys <= set(info["ranges"]), (law, keys - set(info["ranges"]))
    scene = tmp_path / "s.toml"
    scene.write_text(_with_material(_page()["rubber.toml"], 'law = "arruda_boyce"\nmu = 4e5\nlambda_m = 0.5\nkappa = 4e7'))
    r = subprocess.run([str(ROOT / "build.sh"), "run", str(scene), "--quiet"], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 1 and "material.rubber.lambda_m: expected a number in (1, 1e+06), found 0.5" in r.stderr
