"""The silicone free fall of the first seed (models/silicone_fall.toml: L = 0.25 m,
20 x 10 mm, Arruda-Boyce, kappa = 1000 mu, clamped, released straight and
horizontal under g = 9.81) against CalculiX implicit dynamics (C3D20R, HHT with
the same rho_inf and dt, mesh-extrapolated point by point; error estimates
<= 0.1 % of the largest displacement, references/data/calculix_silicone.json).

The measure is the largest distance between the two tip histories (u_x, u_z at
every output time of 0 ... 0.5 s) over the largest |u| of the reference.
Measured: the scene's mesh (ancf3363 reduced, 12 elements graded 3 toward the
clamp) 0.34 % undamped; 8 uniform elements 12 % (the tip lags in the swing back,
t ~ 0.49 s), which the test shows too, so the reference can tell a wrong answer.
(The converged beam solution, 32 elements and dt -> 0, is 1.0 % off the solid at the
end of the swing: part of the 0.34 % is a cancellation of time-step and mesh errors.)"""
import csv
import tempfile

import pytest
from pathlib import Path

from calculix import reference_data
from util import BUILD, ensure_dir, run_cli


def tip_history(sets):
    out = Path(tempfile.mkdtemp(prefix="bk-fall-", dir=ensure_dir(BUILD / "runs")))
    r = run_cli(["run", "silicone_fall", "--quiet", "--out", str(out), "--set", "output.vtk_every=0"]
                + [a for s in sets for a in ("--set", s)])
    assert r.returncode == 0, r.stderr[-2000:]
    with open(out / "sensors.csv", newline="") as f:
        return {round(float(row["time"]), 9): (float(row["ux"]), float(row["uz"]))
                for row in csv.DictReader(f) if row["sensor"] == "tip"}


def history_error(ours, name, ref_tol=2e-3):
    """max over the reference's output times of |(ux, uz) ours - ref| / max |u| of the reference."""
    ref = reference_data(name)
    assert ref.relative_error(0) <= ref_tol and ref.relative_error(2) <= ref_tol
    scale = max(max(abs(u[0]), abs(u[2])) for _, u, _ in ref.history)
    worst, n = 0.0, 0
    for t, u, _ in ref.history:
        if round(t, 9) in ours:
            ux, uz = ours[round(t, 9)]
            worst = max(worst, abs(ux - u[0]), abs(uz - u[2]))
            n += 1
    # every output time of 0 ... 0.5 s compared (but those a halved step moved)
    assert n >= 0.9 * len(ref.history), (n, len(ref.history))
    return worst / scale


def test_free_fall_within_two_percent_of_calculix():
    assert history_error(tip_history([]), "silicone_fall") <= 0.02


def test_coarse_uniform_mesh_is_seen_to_be_off():
    """8 uniform elements (the scene's mesh before): 12 % off; the comparison detects it."""
    e = history_error(tip_history(["beam.strip.elements=8", "beam.strip.grading=1"]), "silicone_fall")
    assert e > 0.05, e


@pytest.mark.slow
def test_damped_free_fall_within_two_percent_of_calculix():
    """Stiffness-proportional Rayleigh damping, beta = 5 ms in both codes (C = beta K_t, the
    current tangent, not linearized in the damping force, so both codes need many
    Newton iterations: ours ~30 s here, ccx ~8 iterations a step).  Measured 0.69 %;
    the reference is good to 0.8 % in u_x, 1.0 % in u_z (ccx's own time-step error with damping: halving
    dt moves u_x by up to 2e-3 m).  The damping moves the tip by more than the allowed
    error (the undamped history is 8.7 % off the damped reference), so the test sees
    whether damping is applied."""
    damped = tip_history(["dynamic.rayleigh_beta=0.005"])
    assert history_error(damped, "silicone_fall_rayleigh", ref_tol=1.5e-2) <= 0.02
    assert history_error(tip_history([]), "silicone_fall_rayleigh", ref_tol=1.5e-2) > 0.05
