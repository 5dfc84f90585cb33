"""out/report/incompressible.md: the nearly incompressible silicone cantilever
(Arruda-Boyce, kappa = 1000 mu) sagging under its own weight, every ANCF element
with mesh refinement, against a converged ancf3363 solution; the heavy elastica
(inextensible, E I with the small-strain modulus) for context.

usage: python3 -m report.incompressible [--quick]
"""
import json
import sys
import time
from pathlib import Path

from gen.cli import execute
from gen.scene import ROOT

from references.elastica import heavy_cantilever  # noqa: E402

OUT = ROOT / "out" / "report"
VARIANTS = [("ancf3243", "full"), ("ancf3243", "sri"), ("ancf3333", "full"), ("ancf3273", "full"),
            ("ancf3273", "reduced"), ("ancf3363", "full"), ("ancf3363", "reduced")]
REF = ("ancf3363", "reduced", 64)


def tip_w(element, integ, n):
    out = OUT / "runs" / f"sag-{element}-{integ}-{n}"
    t0 = time.time()
    rc, out = execute("silicone_cantilever_sag", [f"beam.strip.element={element}",
                                                  f"beam.strip.integration={integ}",
                                                  f"beam.strip.elements={n}"], out)
    s = json.loads((out / "summary.json").read_text())
    return (s["sensors"]["tip"]["displacement"][2] if rc == 0 else None), s, time.time() - t0


def main(argv):
    quick = "--quick" in argv
    meshes = (2, 8) if quick else (2, 4, 8, 16)
    OUT.mkdir(parents=True, exist_ok=True)
    ref, _, _ = tip_w(*REF)
    mu, lm, kappa = 3.0e5, 3.0, 3.0e8
    mu0 = mu * (1 + 3 / (5 * lm**2) + 99 / (175 * lm**4) + 513 / (875 * lm**6) + 42039 / (67375 * lm**8))
    E = 9 * kappa * mu0 / (3 * kappa + mu0)
    _, el_w = heavy_cantilever(0.25, 1100 * 9.81 * 0.02 * 0.01, E * 0.02 * 0.01**3 / 12)
    lines = ["# Nearly incompressible silicone cantilever under its own weight", "",
             "models/silicone_cantilever_sag.toml: 0.25 x 0.02 x 0.01 m, rho = 1100 kg/m^3, Arruda-Boyce",
             "mu = 0.3 MPa, lambda_m = 3, kappa = 1000 mu (nu = 0.4995 at small strain), beam-like clamp.",
             f"Reference: ancf3363 with {REF[2]} elements, tip deflection w = {ref:.6e} m.",
             f"Heavy elastica (inextensible, E I with E = {E:.4g} Pa from mu0, kappa): w = {-el_w:.6e} m;",
             "the 3-D solution is stiffer because strains reach ~20 % (Arruda-Boyce stiffens) and the",
             "section is wide (b = 2 h): anticlastic bending adds plate-like stiffness.", "",
             "| element | " + " | ".join(f"{n} el: w (m), error" for n in meshes) + " |",
             "|---" * (1 + len(meshes)) + "|"]
    for element, integ in VARIANTS:
        cells = []
        for n in meshes:
            w, s, dt = tip_w(element, integ, n)
            cells.append("failed" if w is None else f"{w:.5e}, {(w - ref) / abs(ref) * 100:+.2f} % ({dt:.1f} s)")
        lines.append(f"| {element} {integ} | " + " | ".join(cells) + " |")
    lines += ["", "* ancf3243 full and ancf3333 (linear transverse interpolation, full integration) lock",
              "  completely: their linear cross-section fields cannot bend at constant volume.",
              "* ancf3243 sri removes the locking but is too soft and does not converge to the reference:",
              "  its transverse strains are constant over the section, so away from the centreline the",
              "  volume change is unpenalized and bending sees only the deviatoric stiffness.",
              "* ancf3363 full (3 x 3 x 3 points) locks mildly (the volume constraint at 9 points per",
              "  section over-constrains the quadratic section field); ancf3363 reduced (3 x 2 x 2, the",
              "  default) converges fast: the higher-order element cures volumetric locking.",
              "* ancf3273 (linear-in-x section terms) converges slowly, from the stiff side, with either rule."]
    (OUT / "incompressible.md").write_text("\n".join(lines) + "\n")
    print(f"wrote {OUT / 'incompressible.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
