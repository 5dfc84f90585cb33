"""The "measurements" of the silicone calibration examples of docs/howto/calibrate.md.

    python3 -m beamkit.examples     writes models/data/silicone_fall_calculix.csv,
                                    models/data/silicone_fall_rayleigh_calculix.csv and
                                    models/data/silicone_fall_measured.csv when missing
                                    (delete it to make it again: one fine run, ~35 s)

silicone_fall_measured.csv is made with our own solver, not measured: models/silicone_fall_damped.toml
(Kelvin-Voigt retardation time 5 ms, Arruda-Boyce mu = 0.3 MPa) on a finer mesh
and step than the fit uses (24 elements graded 3 instead of 12, dt = 0.5 ms
instead of 1 ms), over 0 ... 0.3 s; the tip displacement ux, uz every 5 ms with
Gaussian noise of standard deviation 0.5 mm (seed 18), uy left out (the motion
is in the x-z plane).  The fit (docs/howto/calibrate.md) should find mu and the retardation time
near 0.3 MPa and 5 ms; the difference beyond the standard errors is the
discretization error of the coarser model.  (CalculiX has no Kelvin-Voigt law
for hyperelastic solids, and our runs with its Rayleigh damping take about a
minute each: too slow for an example fit.)
"""
import json
from pathlib import Path

import numpy as np

from beamkit.api import ROOT, Scene
from beamkit.fit import write_data

TRUTH = {"material.silicone.mu": 3.0e5, "material.silicone.kelvin_voigt": 0.005}
FINE = {"beam.strip.elements": 24, "dynamic.dt": 5e-4, "dynamic.t_end": 0.3, "output.vtk_every": 0}
EVERY_S, SIGMA_M, SEED = 0.005, 5e-4, 18
DEFAULT = ROOT / "models" / "data" / "silicone_fall_measured.csv"


def silicone_measurement(path=DEFAULT):
    sc = Scene("silicone_fall_damped", sets=FINE)
    r = sc.run(TRUTH, out=ROOT / "out" / "examples" / "silicone_fall_fine")
    if not r.converged:
        raise RuntimeError(f"the fine run did not converge: {r.error}")
    s = r.sensor("tip")
    k = np.rint(s.time / EVERY_S)
    pick = np.abs(s.time - k * EVERY_S) < 1e-9
    t = s.time[pick]
    rng = np.random.default_rng(SEED)
    vals = {c: s.displacement[pick, i] + SIGMA_M * rng.standard_normal(t.size) for c, i in (("ux", 0), ("uz", 2))}
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    note = ("silicone_fall_damped tip displacement (m) made by beamkit itself, NOT measured: 24 elements graded 3,\n"
            "dt = 0.5 ms, mu = 0.3 MPa, kelvin_voigt = 5 ms, every 5 ms, Gaussian noise sd 0.5 mm (seed 18);\n"
            "written by python3 -m beamkit.examples (see beamkit/examples.py)")
    return write_data(path, t, vals, note)


def calculix_measurement(path=ROOT / "models" / "data" / "silicone_fall_calculix.csv", every=5,
                         name="silicone_fall"):
    """The CalculiX tip history of silicone_fall (C3D20R solid, extrapolated from its
    meshes: references/data/calculix_silicone.json, entry `name`: silicone_fall
    undamped, silicone_fall_rayleigh with Rayleigh beta = 5 ms) every `every` ms:
    an independent solver's "measurement"."""
    ref = json.loads((ROOT / "references" / "data" / "calculix_silicone.json").read_text())
    entry = ref["references"][name]
    h = entry["history"]
    col = {c: i for i, c in enumerate(h["columns"])}
    rows = h["rows"][::every]
    t = np.array([r[col["t"]] for r in rows])
    vals = {c: np.array([r[col[c]] for r in rows]) for c in ("ux", "uz")}
    note = (f"silicone_fall tip displacement (m) of CalculiX (ccx 2.20, C3D20R, meshes {', '.join(entry['meshes'])},\n"
            f"extrapolated; --set {' '.join(entry['sets']) or '(none)'}) from references/data/calculix_silicone.json\n"
            f"entry {name}, every {every} ms; written by python3 -m beamkit.examples (beamkit/examples.py)")
    return write_data(path, t, vals, note)


if __name__ == "__main__":
    print(calculix_measurement())
    print(calculix_measurement(ROOT / "models" / "data" / "silicone_fall_rayleigh_calculix.csv",
                               name="silicone_fall_rayleigh"))
    if not DEFAULT.exists():
        print(silicone_measurement())
