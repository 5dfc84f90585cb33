"""CalculiX (ccx, C3D20R) as an independent reference: the deck against closed
forms, and one nearly incompressible silicone case against our ancf3363."""
import math
import subprocess
import sys
import tempfile

from util import BUILD, ENV, PY, ROOT, ensure_dir, rel, run_scene, tip

from calculix.data import names, reference_data
from calculix.extrapolate import richardson
from calculix.mesh import Grading, Spacing, parse_grading
from calculix.scene import SceneError, read_scene
from calculix.study import reference

MESHES = [(4, 2, 2), (8, 4, 4), (16, 8, 8)]


def _cache():
    """A fresh cache, so that ccx really runs (out/calculix/ would re-use old runs)."""
    return tempfile.mkdtemp(prefix="ccx-", dir=ensure_dir(BUILD / "calculix"))


def test_calculix_cantilever_matches_timoshenko():
    """St. Venant-Kirchhoff (*ELASTIC + NLGEOM), L = 0.2 m, 10 x 10 mm, nu = 0.3,
    -0.01 N tip force (linear regime), `free` clamp: the extrapolated tip
    deflection is Timoshenko's P L^3/(3 E I) + P L/(k G A) (Cowper's k) within
    0.5 %, and nearer to it than to Euler-Bernoulli (the shear term is 0.19 %)."""
    E, nu, L, b, h, P = 7.2e10, 0.3, 0.2, 0.01, 0.01, 0.01
    st = reference("cantilever_bend_10N", [f"beam.arm.end.0={L}", f"material.alu.nu={nu}",
                                           f"load.0.value.2={-P}", "constraint.0.cross_section=free"],
                   meshes=MESHES, increments=1, cache=_cache())
    I, G, k = b * h**3 / 12, E / (2 * (1 + nu)), 10 * (1 + nu) / (12 + 11 * nu)
    w_eb = P * L**3 / (3 * E * I)
    w_timo = w_eb + P * L / (k * G * b * h)
    ex = st.tip["tip"][2]
    assert ex.order is not None and ex.order > 1.5, ex
    assert rel(-ex.value, w_timo) <= 5e-3, f"ccx {ex.value:.6e}, Timoshenko {-w_timo:.6e}"
    assert abs(-ex.value - w_timo) < abs(-ex.value - w_eb), (ex.value, w_timo, w_eb)
    assert ex.error <= 1e-3 * abs(ex.value), ex


def test_calculix_bar_free_clamp_is_exact_svk_uniaxial_stress():
    """+1 kN on a 10 x 10 mm, 1 m bar, nu = 0.3, `free` clamp (plane root face free
    to contract): the homogeneous uniaxial-stress state is in the FE space, so one
    coarse mesh gives the St. Venant-Kirchhoff closed form u = L (lam - 1),
    lam (lam^2 - 1)/2 = F/(E A), and the lateral contraction lat^2 = 1 - nu (lam^2 - 1),
    to ccx's printed 7 digits."""
    from calculix.deck import write_deck
    from calculix.results import final
    from calculix.run import run_deck
    prob = read_scene("cantilever_axial_1kN_free_section")
    prob.sensors.append(("corner", prob.length))
    text, mesh, sets = write_deck(prob, 2, 2, 2, increments=2)
    d, _ = run_deck(text, cache=_cache())
    _, u = final(d / "job.dat", "S1")
    c = 1000.0 / (7.2e10 * 1e-4)
    lam = 1.0
    for _ in range(50):
        lam -= (lam**3 - lam - 2 * c) / (3 * lam**2 - 1)
    assert rel(u[0], lam - 1) <= 1e-5, f"ux {u[0]:.7e}, exact {lam - 1:.7e}"
    assert abs(u[1]) < 1e-12 and abs(u[2]) < 1e-12, u
    # a corner node of the end face contracts by (lat - 1) b/2 in both section directions
    corner = mesh.nodes[(4, 0, 0)]
    text2 = text.replace("*NSET, NSET=S1\n", f"*NSET, NSET=S1\n{corner}\n")
    d2, _ = run_deck(text2, cache=_cache())
    from calculix.results import read_dat
    uc = read_dat(d2 / "job.dat")["S1"][corner][-1][1]
    lat = math.sqrt(1 - 0.3 * (lam**2 - 1))
    assert rel(uc[1], -(lat - 1) * 0.005) <= 1e-4 and rel(uc[2], -(lat - 1) * 0.005) <= 1e-4, (uc, lat)


def test_calculix_silicone_agrees_with_ancf3363():
    """Nearly incompressible Arruda-Boyce (mu = 0.3 MPa, lambda_m = 3, kappa = 1000 mu),
    the silicone strip 0.25 x 0.02 x 0.01 m, `free` clamp, gravity scaled to 0.01 m/s^2
    (linear regime).  Two independent implementations: ccx (C3D20R, *HYPERELASTIC
    ARRUDA-BOYCE, extrapolated over three meshes) and our ancf3363 (40 elements).
    Measured: ccx -6.67743e-4 m with an error estimate 2e-9 m; ancf3363 -6.66023e-4,
    -6.66897e-4, -6.67002e-4 at 10, 20, 40 elements (observed order 3, extrapolated
    -6.67016e-4, so 40 elements are within 2e-5 of converged).  The converged values
    differ by 0.11 %: the two models, not their meshes (the clamps hold the root section
    in its plane differently, and ancf3363's section field is quadratic).  Tolerance
    0.25 %; beam theory with the small-strain E (6.667e-4) is a third check."""
    sets = ["load.0.value.2=-0.01"]
    st = reference("silicone_cantilever_sag", sets, meshes=MESHES, increments=1, cache=_cache())
    ex = st.tip["tip"][2]
    assert ex.error <= 1e-4 * abs(ex.value), ex
    s, _ = run_scene("silicone_cantilever_sag", sets + ["beam.strip.elements=40"])
    ours = tip(s)[2]
    assert rel(ours, ex.value) <= 2.5e-3, f"ancf3363 {ours:.6e}, ccx {ex.value:.6e} +- {ex.error:.1e}"
    mat = st.problem.material
    E, _ = mat.small_strain()
    q = mat.rho * 0.01 * 0.02 * 0.01
    w_beam = q * 0.25**4 / (8 * E * 0.02 * 0.01**3 / 12)
    assert rel(-ex.value, w_beam) <= 3e-3, (ex.value, w_beam)


def test_calculix_richardson_recovers_order_and_limit():
    """f(h) = 1 + 0.3 h^3 on h = 1, 1/2, 1/4: order 3 and the limit 1 exactly; a
    non-monotone sequence is reported as not asymptotic with the finest value."""
    ex = richardson([1 + 0.3, 1 + 0.3 / 8, 1 + 0.3 / 64], 2.0)
    assert abs(ex.order - 3) < 1e-9 and abs(ex.value - 1) < 1e-12, ex
    bad = richardson([1.0, 1.1, 1.05], 2.0)
    assert bad.order is None and bad.value == 1.05 and abs(bad.error - 0.1) < 1e-12, bad
    two = richardson([1 + 0.3, 1 + 0.3 / 8], 2.0, order=3)
    assert abs(two.value - 1) < 1e-12 and two.assumed_order == 3


def test_calculix_refuses_what_a_solid_deck_cannot_represent():
    """One error line naming the scene file and the key."""
    cases = [("cantilever_torsion_10Nm", [], "load[0].type"),
             ("pendulum_soft_gef", [], "material."),
             ("cantilever_modal", [], "scene.analysis"),
             ("silicone_fall_damped", [], "material.silicone.kelvin_voigt"),
             ("double_pendulum_soft_ancf", [], "beam")]
    for scene, sets, key in cases:
        try:
            read_scene(scene, sets)
        except SceneError as e:
            msg = str(e)
            assert msg.startswith("error: ") and f"{scene}.toml: {key}" in msg and "\n" not in msg, msg
        else:
            raise AssertionError(f"{scene}: accepted")
    r = subprocess.run([PY, "-m", "calculix", "silicone_fall_damped"], capture_output=True, text=True,
                       env=ENV, cwd=ROOT, timeout=60)
    assert r.returncode == 1 and r.stderr.count("\n") == 1 and "kelvin_voigt" in r.stderr, r.stderr
    assert "sympy" not in subprocess.run([PY, "-c", "import sys, calculix, calculix.uniaxial, calculix.__main__; "
                                          "print(' '.join(sys.modules))"], capture_output=True, text=True,
                                         env=ENV, cwd=ROOT, timeout=60).stdout


def test_calculix_graded_mesh_family_is_self_similar():
    """A graded spacing is a fixed mapping sampled at i/n: doubling n keeps every
    corner of the coarser mesh (nested, every element halved in the limit); the
    bias points at the clamp, the section's is symmetric, a uniform traction's
    face weights add up to the face, the centroid stays a node."""
    for sp in (Spacing("geometric", 16.0), Spacing("power", 3.0), Spacing("power", 3.0, zone=0.5),
               Spacing("power", 2.0, two_sided=True), Spacing("geometric", 4.0, mirror=True)):
        for n in (2, 4, 8):
            c, f = sp.fractions(n), sp.fractions(2 * n)
            assert all(abs(c[2 * i] - f[4 * i]) < 1e-15 for i in range(n + 1)), (sp, n)
            assert all(c[k] < c[k + 1] for k in range(2 * n)), (sp, n)
            assert c[0] == 0.0 and c[-1] == 1.0
    g = Spacing("geometric", 16.0).fractions(16)
    assert abs((g[32] - g[30]) / (g[2] - g[0]) - 16 ** (15 / 16)) < 1e-12       # limit ratio R
    two = Spacing("power", 2.0, two_sided=True).fractions(8)
    assert all(abs(two[k] + two[16 - k] - 1) < 1e-15 for k in range(17))          # symmetric
    p = Spacing("power", 3.0, zone=0.5).fractions(8)
    assert all(abs((p[k + 2] - p[k]) - (p[10] - p[8])) < 1e-14 for k in range(8, 16, 2))  # uniform beyond
    gr = parse_grading("x=power:3:0.5,y=power:2,z=power:2")
    assert gr == Grading(Spacing("power", 3.0, zone=0.5), Spacing("power", 2.0, two_sided=True),
                         Spacing("power", 2.0, two_sided=True)) and parse_grading(gr.spec()) == gr
    from calculix.mesh import build_mesh
    prob = read_scene("silicone_cantilever_sag")
    m = build_mesh(prob, 8, 4, 4, gr)
    xs = sorted({round(x[0], 12) for x in m.coords})
    assert xs[1] - xs[0] < (xs[-1] - xs[-2]) / 20, "axial bias toward the clamp at x = 0"
    face = m.face("end")
    assert abs(sum(r[5] for r in face) - 1.0) < 1e-13
    assert m.node_at(1.0) is not None and m.node_at(0.0) is not None
    for bad in ("x=power", "q=power:2", "x=geometric:0.5", "x=power:2,x=power:3", "x=geometric:4:0.5"):
        try:
            parse_grading(bad)
        except ValueError:
            pass
        else:
            raise AssertionError(f"{bad!r} accepted")


def test_calculix_bulk_modulus_continuation_same_equilibrium():
    """The static deck of a nearly incompressible solid loads it with kappa = 3 mu0
    and raises kappa to the material's at full load (calculix.deck.continuation_kappa):
    the same equilibrium as loading with the material's kappa from the start
    (hyperelastic, dead loads: path independent), to ccx's 7 printed digits, in
    far fewer Newton iterations (measured 78 against 300+ on this mesh)."""
    from calculix.deck import final_time, write_deck
    from calculix.results import final
    from calculix.run import run_deck
    from calculix.study import _iterations
    prob = read_scene("silicone_cantilever_sag", ["constraint.0.cross_section=rigid"])
    cache = _cache()
    out = {}
    for cont in (True, False):
        text, _, sets = write_deck(prob, 4, 2, 2, continuation=cont)
        assert ("*TEMPERATURE" in text) == cont
        d, _ = run_deck(text, cache=cache)
        t, u = final(d / "job.dat", sets[0][1])
        assert abs(t - final_time(prob, cont)) < 1e-9, t
        out[cont] = (u, _iterations(d / "job.sta"))
    (u1, it1), (u0, it0) = out[True], out[False]
    assert all(abs(a - b) <= 2e-6 * abs(u0[2]) for a, b in zip(u1, u0)), (u1, u0)
    assert it1 < it0 / 2, (it1, it0)


def test_calculix_reference_data_is_complete_and_consistent():
    """The committed references (references/data/calculix_silicone.json) load
    without ccx; each has meshes, per-mesh values, the ccx version and the command
    that reproduces it; error estimates are at most 0.2 % (1.5 % for the damped fall; of the final value for
    statics, of the largest |u| of the history for dynamics); a static entry's
    value and error follow from its per-mesh values by Richardson (calculix.extrapolate)."""
    have = names()
    for n in ("silicone_cantilever_sag_rigid", "silicone_cantilever_sag_free", "silicone_fall",
              "silicone_fall_rayleigh"):
        assert n in have, (n, have)
    for n in have:
        r = reference_data(n)
        assert r.ccx.startswith("This is Version") or "2." in r.ccx, r.ccx
        assert r.command.startswith("python3 -m calculix ") and f"--record {n}" in r.command, r.command
        assert len(r.per_mesh) == len(r.meshes) >= 2
        # the damped fall: ccx's time-step error with Rayleigh damping (dt halving
        # moves u_x by up to 2e-3 m) makes it a 1 % reference (0.8 % in u_x, 1.0 % in u_z)
        bound = 1.5e-2 if n == "silicone_fall_rayleigh" else 2e-3
        for k in (0, 2):
            assert r.relative_error(k) <= bound, (n, k, r.relative_error(k))
        if r.analysis == "static":
            for k in (0, 2):
                ex = richardson([m["u"][k] for m in r.per_mesh], r.ratio)
                extra = sum(c["factor"] * abs(c["final_diff"][k]) for c in r.checks)
                assert abs(ex.value - r.value[k]) <= 1e-6 * abs(r.value[k]), (n, k, ex, r.value)
                assert abs(ex.error + extra - r.error[k]) <= 0.01 * r.error[k] + 1e-12, (n, k, ex, r.error)
        else:
            assert len(r.history) > 100 and r.history[0][0] <= 1e-3
            u_end, e_end = r.at(r.history[-1][0])
            assert u_end == r.value and e_end == r.error
    try:
        reference_data("no_such_reference")
    except KeyError as e:
        assert "silicone_fall" in str(e)
    else:
        raise AssertionError("unknown name accepted")


def test_calculix_reference_data_regression_guard():
    """Regression guard (not an independent check): the coarsest mesh of the rigid
    clamp reference, re-run live in a fresh cache from today's deck, reproduces the
    value stored for that mesh (ccx prints 7 digits), so the committed data still
    describe what calculix/ writes."""
    from calculix.study import parse_mesh, run_mesh
    r = reference_data("silicone_cantilever_sag_rigid")
    prob = read_scene(r.scene, r.sets)
    first = r.per_mesh[0]
    run = run_mesh(prob, parse_mesh(first["mesh"]), parse_grading(r.grading), cache=_cache())
    u = run.histories[r.sensor][-1][1]
    assert all(abs(a - b) <= 2e-6 * abs(first["u"][2]) for a, b in zip(u, first["u"])), (u, first)
