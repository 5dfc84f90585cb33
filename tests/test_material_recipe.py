"""The "Adding a material" recipe (docs/howto/add-material.md), followed as written (issue 39 point 3):
its code block becomes gen/materials/gent.py in a scratch copy of the project,
`./build.sh gen` derives the new pairs there, and a scene with law = "gent"
runs: at small load it agrees with the neo-Hookean law of the same small-strain
moduli (Gent tends to it as its strains stay far from the limit) and with beam
theory; a value outside the law's declared range (Jm = -1) is refused with one
line naming the key, the range and the unit; so is a law file without RANGES."""
import re
import shutil
import subprocess

import pytest

from util import ROOT

SCENE = """[scene]
analysis = "static"
[material.rubber]
law = "{law}"
rho = 1100.0
{params}
[section.sq]
shape = "rectangle"
b = 0.01
h = 0.01
[[beam]]
name = "arm"
element = "ancf3363"
material = "rubber"
section = "sq"
start = [0.0, 0.0, 0.0]
end = [0.2, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
elements = 8
integration = "reduced"
[[constraint]]
type = "clamp"
a = "arm:start"
cross_section = "free"
[[load]]
type = "force"
at = "arm:end"
value = [0.0, 0.0, -1e-4]
[[sensor]]
name = "tip"
at = "arm:end"
"""


def _recipe_code():
    sec = (ROOT / "docs" / "howto" / "add-material.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", sec, re.S)
    assert len(blocks) == 1, "the recipe has one code block: the whole law file"
    return blocks[0]


def _scratch(tmp_path):
    """A copy of the project's tracked files (the working tree's content)."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
    dst = tmp_path / "proj"
    for rel in filter(None, files.decode().split("\0")):
        src = ROOT / rel
        if src.is_file():
            (dst / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst / rel)
    return dst


def _sh(proj, *args, timeout=1800):
    return subprocess.run([str(proj / "build.sh"), *args], capture_output=True, text=True, cwd=proj,
                          timeout=timeout)


def _tip_uz(proj, name, law, params):
    scene = proj / f"{name}.toml"
    scene.write_text(SCENE.format(law=law, params=params))
    r = _sh(proj, "run", str(scene), "--quiet", "--out", str(proj / "out" / name))
    assert r.returncode == 0, r.stderr[-2000:]
    import csv
    rows = list(csv.DictReader(open(proj / "out" / name / "sensors.csv", newline="")))
    return float(rows[-1]["uz"])


@pytest.mark.slow
def test_the_recipe_adds_a_law_that_runs(tmp_path):
    proj = _scratch(tmp_path)
    (proj / "gen" / "materials" / "gent.py").write_text(_recipe_code())
    r = _sh(proj, "gen")
    assert r.returncode == 0, r.stderr[-3000:]
    assert (proj / "out" / "kernels" / "ancf3363_gent.c").exists()
    mu, kappa = 4e5, 4e7                     # nearly incompressible silicone-like rubber
    uz_gent = _tip_uz(proj, "gent", "gent", f"mu = {mu}\nJm = 30.0\nkappa = {kappa}")
    lam = kappa - 2 * mu / 3
    uz_nh = _tip_uz(proj, "nh", "neo_hookean", f"lambda = {lam}\nmu = {mu}")
    assert abs(uz_gent / uz_nh - 1) < 1e-4, (uz_gent, uz_nh)
    E = 9 * kappa * mu / (3 * kappa + mu)
    beam = -1e-4 * 0.2**3 / (3 * E * 0.01**4 / 12)
    assert abs(uz_gent / beam - 1) < 0.02, (uz_gent, beam)
    scene = proj / "bad.toml"
    scene.write_text(SCENE.format(law="gent", params=f"mu = {mu}\nJm = -1.0\nkappa = {kappa}"))
    r = _sh(proj, "run", str(scene), "--quiet")
    errs = [x for x in r.stderr.splitlines() if x.startswith("error")]
    assert r.returncode == 1 and len(errs) == 1 and "material.rubber.Jm: expected a positive number" in errs[0], \
        r.stderr[-1000:]
    # a law file without RANGES is refused by the generator, naming the keys
    code = re.sub(r"^RANGES = .*\n", "", _recipe_code(), flags=re.M)
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
    scene.write_text(SCENE.format(law="arruda_boyce", params="mu = 4e5\nlambda_m = 0.5\nkappa = 4e7"))
    r = subprocess.run([str(ROOT / "build.sh"), "run", str(scene), "--quiet"], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 1 and "material.rubber.lambda_m: expected a number in (1, 1e+06), found 0.5" in r.stderr
