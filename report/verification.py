"""out/report/verification.md: every ANCF continuum element x every hyperelastic
law x kappa/mu in {10, 1000}, against references that are not our elements:

  linear  the clamped silicone strip of models/silicone_strip_linear.toml (free
          clamp, gravity scaled to the linear regime) against Timoshenko beam
          theory with the law's small-strain moduli (references/beam_theory.py);
  large   the silicone cantilever of models/silicone_cantilever_sag.toml (rigid
          clamp, g = 9.81, tip rotation > 45 degrees) against CalculiX C3D20R
          (calculix/, extrapolated mesh study; references/data/ holds the values,
          --ccx computes missing ones, which takes minutes per case).

at 4, 10, 20 and 40 elements: error tables (verification.md, verification.csv)
and a convergence plot (verification_convergence.png).  The shear modulus is
mu = 0.3 MPa for every law (Arruda-Boyce: its series parameter).

usage: python3 -m report.verification [--quick] [--ccx]
"""
import csv
import json
import sys
import time
from pathlib import Path

from gen.cli import execute
from gen.scene import ROOT
from references.beam_theory import ab_moduli, cantilever_uniform_load_tip

OUT = ROOT / "out" / "report"
VARIANTS = [("ancf3243", "full"), ("ancf3243", "sri"), ("ancf3333", "full"), ("ancf3363", "reduced"),
            ("ancf3363", "full"), ("ancf3273", "sri"), ("ancf3273", "reduced")]
LAWS = ("arruda_boyce", "mooney_rivlin", "neo_hookean", "svk")
RATIOS = (10.0, 1000.0)
MU = 0.3e6


def material(law, kappa_mu):
    """Scene --set values of the material (table `sil` / `silicone`) and its small-strain E, nu."""
    k = kappa_mu * MU
    E, nu = 9 * k * MU / (3 * k + MU), (3 * k - 2 * MU) / (2 * (3 * k + MU))
    if law == "arruda_boyce":
        return {"law": law, "mu": MU, "lambda_m": 3.0, "kappa": k}, ab_moduli(MU, 3.0, k)
    if law == "mooney_rivlin":
        return {"law": law, "c10": 0.1e6, "c01": 0.05e6, "kappa": k}, (E, nu)
    return {"law": law, "E": E, "nu": nu}, (E, nu)


def scene_text(base, table, mat):
    """The scene file `base` with its [material.TABLE] replaced by mat."""
    text = (ROOT / "models" / f"{base}.toml").read_text()
    head, rest = text.split(f"[material.{table}]", 1)
    rho = [l for l in rest.splitlines() if l.strip().startswith("rho")][0]
    rest = rest[rest.index("[section."):]
    body = "\n".join(f'{k} = "{v}"' if isinstance(v, str) else f"{k} = {v!r}" for k, v in mat.items())
    return head + f"[material.{table}]\n{body}\n{rho}\n\n" + rest


def run(case, element, integ, n, law, kappa_mu):
    base, table, beam, sets = {
        "linear": ("silicone_strip_linear", "sil", "strip", []),
        "large": ("silicone_cantilever_sag", "silicone", "strip", ["constraint.0.cross_section=rigid"]),
    }[case]
    mat, _ = material(law, kappa_mu)
    d = OUT / "runs" / "verification"
    d.mkdir(parents=True, exist_ok=True)
    path = d / f"{case}-{law}-{int(kappa_mu)}.toml"
    path.write_text(scene_text(base, table, mat))
    out = d / f"{case}-{law}-{int(kappa_mu)}-{element}-{integ}-{n}"
    t0 = time.time()
    rc, out = execute(path, sets + [f"beam.{beam}.element={element}", f"beam.{beam}.integration={integ}",
                                    f"beam.{beam}.elements={n}"], out)
    s = json.loads((out / "summary.json").read_text())
    u = s["sensors"]["tip"]["displacement"] if s.get("sensors") else None
    return (u if rc == 0 else None), time.time() - t0


def ccx_name(law, kappa_mu):
    """Name of the CalculiX reference of the large-deflection case in references/data/."""
    if law == "arruda_boyce" and kappa_mu == 1000.0:
        return "silicone_cantilever_sag_rigid"          # the scene's own material
    return f"silicone_cantilever_sag_rigid_{law}_{int(kappa_mu)}"


def ccx_reference(law, kappa_mu, live):
    """(ux, uz, error of ux, error of uz, where from) of the large-deflection case from
    CalculiX, or None.  live: run the mesh study when the data file lacks it (minutes)."""
    from calculix import reference_data
    try:
        r = reference_data(ccx_name(law, kappa_mu))
        return r.value[0], r.value[2], r.error[0], r.error[2], "data"
    except KeyError:
        pass
    if not live:
        return None
    import subprocess
    mat, _ = material(law, kappa_mu)
    d = OUT / "runs" / "verification"
    d.mkdir(parents=True, exist_ok=True)
    path = d / f"ccx-{law}-{int(kappa_mu)}.toml"
    path.write_text(scene_text("silicone_cantilever_sag", "silicone", mat))
    ref = reference_data("silicone_cantilever_sag_rigid")           # the same mesh family
    cmd = ["/usr/bin/python3", "-m", "calculix", str(path.relative_to(ROOT)),
           "--set", "constraint.0.cross_section=rigid",
           "--meshes", ",".join(ref.meshes), "--grading", ref.grading, "--record", ccx_name(law, kappa_mu),
           "--note", f"scene file written by `python3 -m report.verification --ccx`: silicone_cantilever_sag "
                     f"with {law}, kappa = {int(kappa_mu)} mu"]
    subprocess.run(cmd, check=True, cwd=ROOT)
    r = reference_data(ccx_name(law, kappa_mu))
    return r.value[0], r.value[2], r.error[0], r.error[2], "live"


def main(argv):
    quick = "--quick" in argv
    live = "--ccx" in argv
    meshes = (4, 10) if quick else (4, 10, 20, 40)
    OUT.mkdir(parents=True, exist_ok=True)
    rows = []
    t_all = time.time()
    for law in LAWS:
        for kr in RATIOS:
            _, (E, nu) = material(law, kr)
            lin_ref = cantilever_uniform_load_tip(E, nu, L=0.3, b=0.02, h=0.005, q=1100 * 0.02 * 0.005 * 0.01)
            ccx = ccx_reference(law, kr, live)
            for element, integ in VARIANTS:
                for n in meshes:
                    u, dt = run("linear", element, integ, n, law, kr)
                    err = None if u is None else (-u[2] - lin_ref) / lin_ref
                    rows.append(dict(case="linear", law=law, kappa_mu=kr, element=element, integration=integ,
                                     elements=n, w=None if u is None else -u[2], ref=lin_ref, error=err, wall_s=dt))
                    u, dt = run("large", element, integ, n, law, kr)
                    if ccx is not None and u is not None:
                        err = (u[2] - ccx[1]) / abs(ccx[1])
                    else:
                        err = None
                    rows.append(dict(case="large", law=law, kappa_mu=kr, element=element, integration=integ,
                                     elements=n, w=None if u is None else u[2],
                                     ref=None if ccx is None else ccx[1],
                                     ref_err=None if ccx is None else ccx[3], error=err, wall_s=dt))
            print(f"  {law} kappa = {kr:g} mu done ({time.time() - t_all:.0f} s)", file=sys.stderr, flush=True)
    with open(OUT / "verification.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=["case", "law", "kappa_mu", "element", "integration", "elements", "w",
                                           "ref", "ref_err", "error", "wall_s"])
        w.writeheader()
        for r in rows:
            w.writerow(r)
    write_md(rows, meshes)
    plot(rows, meshes)
    print(f"wrote {OUT / 'verification.md'} ({time.time() - t_all:.0f} s)")
    return 0


def _cell(r):
    if r is None:
        return "–"
    if r["w"] is None:
        return "failed"
    if r["error"] is None:
        return f"{r['w']:.4e} (no ref.)"
    return f"{r['error'] * 100:+.2f} %"


def write_md(rows, meshes):
    idx = {(r["case"], r["law"], r["kappa_mu"], r["element"], r["integration"], r["elements"]): r for r in rows}
    L = ["# Verification matrix: continuum elements x laws x compressibility", "",
         "Errors of the tip deflection against references that are not our elements.", "",
         "* **linear**: `models/silicone_strip_linear.toml` (L = 0.3 m, 20 x 5 mm, free clamp, gravity 0.01 m/s²)",
         "  against Timoshenko beam theory with the law's small-strain E, ν (Cowper's shear factor).",
         "* **large**: `models/silicone_cantilever_sag.toml` (L = 0.25 m, 20 x 10 mm, rigid clamp, g = 9.81,",
         "  large deflection) against CalculiX C3D20R, mesh-extrapolated (`calculix/`); the reference's own",
         "  error estimate is given with each table.", "",
         "μ = 0.3 MPa for every law (Arruda–Boyce: its series parameter, λ_m = 3); κ/μ = 10 (ν ≈ 0.45) and",
         "1000 (ν ≈ 0.4995).", ""]
    for case in ("linear", "large"):
        for law in LAWS:
            for kr in RATIOS:
                ref = next((r for r in rows if r["case"] == case and r["law"] == law and r["kappa_mu"] == kr), None)
                head = f"### {case}: {law}, κ = {kr:g} μ"
                if case == "large":
                    head += (f" (CalculiX w = {ref['ref']:.5e} m ± {ref['ref_err']:.1e})" if ref and ref["ref"]
                             else " (no CalculiX reference: run with --ccx)")
                else:
                    head += f" (beam theory w = {ref['ref']:.5e} m)"
                L += [head, "", "| element | " + " | ".join(f"{n} el." for n in meshes) + " |",
                      "|---" * (1 + len(meshes)) + "|"]
                for element, integ in VARIANTS:
                    L.append(f"| {element} {integ} | " + " | ".join(
                        _cell(idx.get((case, law, kr, element, integ, n))) for n in meshes) + " |")
                L.append("")
    (OUT / "verification.md").write_text("\n".join(L) + "\n")


def plot(rows, meshes):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    for ax, (case, kr) in zip(axes.flat, [(c, k) for c in ("linear", "large") for k in RATIOS]):
        for element, integ in VARIANTS:
            pts = [(r["elements"], abs(r["error"])) for r in rows if r["case"] == case and r["kappa_mu"] == kr and
                   r["law"] == "arruda_boyce" and r["element"] == element and r["integration"] == integ and
                   r["error"] is not None]
            if pts:
                ax.loglog(*zip(*pts), marker="o", label=f"{element} {integ}")
        ax.set_title(f"{case}, Arruda-Boyce, kappa = {kr:g} mu")
        ax.set_xlabel("elements")
        ax.set_ylabel("|tip error| (relative)")
        ax.grid(True, which="both", lw=0.3)
    axes.flat[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / "verification_convergence.png", dpi=110)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
