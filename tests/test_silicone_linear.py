"""Nearly incompressible silicone with every continuum element (issue 13): the
clamped strip in the linear regime (models/silicone_strip_linear.toml, free clamp,
10 elements) against Timoshenko beam theory with the law's small-strain moduli --
an independent closed form.  Before: ancf3243 sri 2.24 (bending saw 4 mu / 3),
ancf3273 reduced 0.76, neo-Hookean at nu = 0.3 with ancf3243 sri 1.94."""
import json
import tempfile
from pathlib import Path

import pytest

from references.beam_theory import ab_moduli, cantilever_uniform_load_tip
from util import BUILD, ensure_dir, run_cli

MU = 0.3e6
L, B, H, RHO, G = 0.3, 0.02, 0.005, 1100.0, 0.01


def beam_tip(E, nu):
    return cantilever_uniform_load_tip(E, nu, L, B, H, RHO * B * H * G)


def laws(kappa_mu):
    """(name, --set values replacing the material, small-strain E, nu) with shear modulus MU."""
    k = kappa_mu * MU
    E, nu = 9 * k * MU / (3 * k + MU), (3 * k - 2 * MU) / (2 * (3 * k + MU))
    Eab, nuab = ab_moduli(MU, 3.0, k)
    return [("arruda_boyce", {"law": "arruda_boyce", "mu": MU, "lambda_m": 3.0, "kappa": k}, Eab, nuab),
            ("mooney_rivlin", {"law": "mooney_rivlin", "c10": 0.1e6, "c01": 0.05e6, "kappa": k}, E, nu),
            ("neo_hookean", {"law": "neo_hookean", "E": E, "nu": nu}, E, nu),
            ("svk", {"law": "svk", "E": E, "nu": nu}, E, nu)]


def scene_with(material, tmp):
    text = (Path(__file__).resolve().parent.parent / "models" / "silicone_strip_linear.toml").read_text()
    head, rest = text.split("[material.sil]", 1)
    rest = rest[rest.index("[section.strip]"):]
    mat = "[material.sil]\n" + "\n".join(f"{k} = {v!r}" if not isinstance(v, str) else f'{k} = "{v}"'
                                         for k, v in material.items()) + f"\nrho = {RHO!r}\n\n"
    p = tmp / "strip.toml"
    p.write_text(head + mat + rest)
    return p


def tip(material, element, integration, elements=10):
    tmp = Path(tempfile.mkdtemp(prefix="bk-sil-", dir=ensure_dir(BUILD / "runs")))
    path = scene_with(material, tmp)
    r = run_cli(["run", str(path), "--quiet", "--out", str(tmp / "out"), "--set", f"beam.strip.element={element}",
                 "--set", f"beam.strip.integration={integration}", "--set", f"beam.strip.elements={elements}"])
    assert r.returncode == 0, r.stderr[-2000:]
    s = json.loads((tmp / "out" / "summary.json").read_text())
    return -s["sensors"]["tip"]["displacement"][2]


@pytest.mark.parametrize("law", ["arruda_boyce", "mooney_rivlin", "neo_hookean", "svk"])
def test_nearly_incompressible_strip_every_element(law):
    name, mat, E, nu = [x for x in laws(1000.0) if x[0] == law][0]
    ref = beam_tip(E, nu)
    for element, integration, tol in (("ancf3243", "sri", 0.01), ("ancf3363", "reduced", 0.01),
                                      ("ancf3273", "sri", 0.02)):
        w = tip(mat, element, integration)
        assert abs(w / ref - 1) <= tol, (law, element, integration, w / ref)


def test_compressible_neo_hookean_with_sri():
    """nu = 0.3: before, ancf3243 sri was 1.94 times too soft with neo-Hookean."""
    E, nu = 1.0e6, 0.3
    w = tip({"law": "neo_hookean", "E": E, "nu": nu}, "ancf3243", "sri")
    assert abs(w / beam_tip(E, nu) - 1) <= 0.01, w / beam_tip(E, nu)


def test_moderately_compressible_every_law_sri():
    """kappa = 10 mu (nu = 0.45)."""
    for name, mat, E, nu in laws(10.0):
        w = tip(mat, "ancf3243", "sri")
        assert abs(w / beam_tip(E, nu) - 1) <= 0.01, (name, w / beam_tip(E, nu))
