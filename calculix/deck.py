"""Scene (calculix.scene.Problem) + mesh (calculix.mesh) -> CalculiX input deck.

What the deck represents:
  * C3D20R bricks (20 nodes, 2 x 2 x 2 reduced integration), nodes in the
    beam's global frame.
  * Materials (our law -> ccx card):
      svk            *ELASTIC E, nu (with NLGEOM: St. Venant-Kirchhoff, exact)
      mooney_rivlin  *HYPERELASTIC, MOONEY-RIVLIN  C10, C01, D1 = 2/kappa (exact)
      arruda_boyce   *HYPERELASTIC, ARRUDA-BOYCE  mu, lambda_m, D = 2/kappa: the same
                     five-term deviatoric series; ccx's volumetric term is
                     (1/D)((J^2 - 1)/2 - ln J) instead of kappa/2 (J - 1)^2
                     (same bulk modulus kappa, pressures differ by O((J - 1)^2))
      neo_hookean    *HYPERELASTIC, NEO HOOKE with C10 = mu/2, D1 = 2/K, K = lambda + 2 mu/3:
                     mu/2 (Ibar1 - 3) + K/2 (J - 1)^2 instead of mu/2 (I1 - 3) - mu ln J +
                     lambda/2 (ln J)^2: the same small-strain moduli and the same response
                     to isochoric deformations, a different coupling of volume and
                     distortion at large strain.  (*HYPERFOAM N=1, mu1 = mu, alpha1 = 2,
                     nu1 = nu would differ from ours only in the volumetric function, but
                     ccx 2.20 stops without a message on its first increment here.)
    calculix.uniaxial computes the remaining differences in uniaxial stress.
  * Clamps: `rigid`: every node of the face fixed.  `free`: the face stays plane
    (every node's axial displacement 0) and may deform freely in its plane; the
    three in-plane rigid motions are removed by three equations: the mean
    displacement of the face along d1 and along d2 and its mean rotation about the
    axis, integral (y u.d2 - z u.d1) dA, vanish (consistent quadratic face
    weights).  The transverse reaction is then a uniform traction on the face.
    The free clamp needs the beam's axes (t, d1, d2) along global axes.
  * Loads: a force on an end face is a uniform dead traction (consistent nodal
    forces of the 8-node faces: -A/12 at corners, A/3 at mid-sides); gravity is
    *DLOAD GRAV on every element with the material's density.
  * Mesh: structured bricks, uniform or graded (calculix.mesh.Grading).
  * Analyses: *STATIC with NLGEOM in steps of time 1: (1) the loads ramped 0 -> 1
    (first increment 1/load_steps, grown or cut back by ccx, ccx's default
    tolerances); (2) for nearly incompressible hyperelastic laws only, the bulk
    modulus raised at full load from KAPPA0_RATIO mu0 to the material's (a
    temperature-dependent card, temperature 0 -> 1; continuation_kappa); (3) one
    increment at full load with the tight FIELD_CONTROLS, whose result is printed
    (only the last equilibrium matters: a hyperelastic solid under dead loads is
    path independent).  Or implicit *DYNAMIC
    (HHT-alpha, alpha = (rho_inf - 1)/(rho_inf + 1), steps of at most dt, cut back
    by ccx when Newton fails, output at every dt) with the scene's rigid initial
    velocity and Rayleigh damping
    *DAMPING ALPHA, BETA (C = alpha M + beta K, K ccx's current tangent stiffness).
  * Output: *NODE PRINT U of the sensor nodes (section centroid at the sensor's
    arc length) in the last static step, or at every dt (dynamics).
"""
import math

from calculix.mesh import build_mesh

# Newton tolerances (ccx *CONTROLS, PARAMETERS=FIELD): residual 1e-6 of the mean
# force and correction 1e-6 of the increment (ccx's defaults are 5e-3 and 1e-2);
# the other six entries are ccx's defaults.
FIELD_CONTROLS = (1e-6, 1e-6, 0.0, 0.0, 0.02, 1e-5, 1e-3, 1e-8)


# Static bulk-modulus continuation (continuation_kappa): used when the small-strain
# bulk modulus is at least CONTINUATION_RATIO times the shear modulus; the first
# loading has KAPPA0_RATIO times the shear modulus (Poisson's ratio 0.35).
CONTINUATION_RATIO = 50.0
KAPPA0_RATIO = 3.0


class DeckError(ValueError):
    pass


def _f(x):
    """A number as ccx reads it: ccx takes the first 20 characters of a field
    (Fortran f20.0), so 13 significant digits in exponent form (at most 19)."""
    return f"{float(x):.12e}"


def _axis_index(v):
    """(global index, sign) of a unit vector along a global axis, or None."""
    for k in range(3):
        if abs(abs(v[k]) - 1.0) < 1e-12 and all(abs(v[j]) < 1e-12 for j in range(3) if j != k):
            return k, 1.0 if v[k] > 0 else -1.0
    return None


def _small_strain_moduli(mat):
    E, nu = mat.small_strain()
    return E / (2 * (1 + nu)), E / (3 * (1 - 2 * nu))


def continuation_kappa(prob):
    """Bulk modulus of the first loading of a static bulk-modulus continuation, or None.

    For a nearly incompressible hyperelastic solid (kappa >= CONTINUATION_RATIO mu0)
    ccx's Newton needs hundreds of iterations to ramp the load (a linearized rotation
    changes the volume to second order, and kappa turns that into large residuals).
    The static deck then loads the solid with the bulk modulus KAPPA0_RATIO mu0
    (temperature 0), raises it to the material's (temperature 1: ccx interpolates
    the compressibility D linearly in temperature) at full load, and finishes with
    one tight increment: the same equilibrium (a hyperelastic solid under dead loads
    has no memory of the path), in about a quarter of the iterations."""
    mat = prob.material
    if prob.layers:                 # refused by layer_cards where a layer would need it
        return None
    if prob.analysis != "static" or mat.law not in ("arruda_boyce", "mooney_rivlin", "neo_hookean"):
        return None
    mu0, K = _small_strain_moduli(mat)
    if K < CONTINUATION_RATIO * mu0:
        return None
    return KAPPA0_RATIO * mu0


def material_cards(mat, kappa0=None, name="M"):
    """*MATERIAL ... lines for a calculix.scene.Material; with `kappa0` (a bulk
    modulus) the hyperelastic card has a second data line at temperature 0 with
    that bulk modulus, the material's own at temperature 1."""
    p = mat.p
    out = [f"*MATERIAL, NAME={name}", "*DENSITY", _f(mat.rho)]
    if mat.law == "svk":
        if kappa0 is not None:
            raise DeckError("the bulk-modulus continuation is for the hyperelastic laws")
        return out + ["*ELASTIC", f"{_f(p['E'])}, {_f(p['nu'])}"]
    if mat.law == "mooney_rivlin":
        head, coef, K = "*HYPERELASTIC, MOONEY-RIVLIN", [p["c10"], p["c01"]], p["kappa"]
    elif mat.law == "arruda_boyce":
        head, coef, K = "*HYPERELASTIC, ARRUDA-BOYCE", [p["mu"], p["lambda_m"]], p["kappa"]
    elif mat.law == "neo_hookean":
        head, coef, K = "*HYPERELASTIC, NEO HOOKE", [p["mu"] / 2], p["lambda"] + 2 * p["mu"] / 3
    else:
        raise DeckError(f"law {mat.law!r} has no CalculiX card here")
    if kappa0 is None:
        return out + [head, ", ".join(_f(x) for x in coef + [2 / K])]
    return out + [head] + [", ".join(_f(x) for x in coef + [2 / k, T]) for k, T in ((kappa0, 0.0), (K, 1.0))]


def _free_clamp(prob, mesh, side):
    """*BOUNDARY and *EQUATION lines of a `free` clamp on an end face."""
    ax = [_axis_index(v) for v in (prob.t, prob.d1, prob.d2)]
    if any(a is None for a in ax):
        raise DeckError(f"error: {prob.path}: constraint: the CalculiX `free` clamp needs the beam axis and the "
                        f"section axes along global axes; found t = {prob.t}, d1 = {prob.d1}, d2 = {prob.d2}")
    (ia, _), (ib, sb), (ic, sc) = ax
    face = mesh.face(side)
    by_lattice = {(J, K): (n, y, z, w) for n, J, K, y, z, w in face}
    centre = by_lattice.get((mesh.ny, mesh.nz))
    # P: a node on the line z = 0 at y > 0 (a corner or mid-side node of the face), the farthest out
    cands = sorted((v for (J, K), v in by_lattice.items() if K == mesh.nz and J > mesh.ny and abs(v[3]) > 0),
                   key=lambda v: -v[1])
    if centre is None or not cands:
        raise DeckError(f"mesh {mesh.label}: the free clamp needs a node at the face centroid (ny, nz not both odd)")
    P = cands[0]
    # the section coordinates in metres
    pts = [(n, y * prob.b, z * prob.h, w) for n, y, z, w in by_lattice.values()]
    yP = P[1] * prob.b
    lines = ["** free clamp: every node of the face has zero axial displacement", "*BOUNDARY"]
    lines += [f"{n}, {ia + 1}, {ia + 1}, 0.0" for n, _, _, _ in pts]

    def eq(terms, first):
        terms = [t for t in terms if abs(t[2]) > 1e-14 * max(abs(x[2]) for x in terms)]
        terms.sort(key=lambda t: (t[:2] != first, t[0], t[1]))
        assert terms[0][:2] == first
        out = ["*EQUATION", str(len(terms))]
        for i in range(0, len(terms), 4):          # at most 12 entries per line
            out.append(", ".join(f"{n}, {d}, {_f(c)}" for n, d, c in terms[i:i + 4]))
        return out

    # mean displacement along d1: sum w u_b = 0 (dependent: the centroid's u_b)
    lines += ["** mean displacement of the face along d1 = 0"]
    lines += eq([(n, ib + 1, w) for n, _, _, w in pts], (centre[0], ib + 1))
    # rotation: sum w (y sc u_c - z sb u_b) = 0 (dependent: P's u_c)
    rot = [(n, ic + 1, w * y * sc) for n, y, _, w in pts] + [(n, ib + 1, -w * z * sb) for n, _, z, w in pts]
    lines += ["** mean rotation of the face about the axis = 0"]
    lines += eq(rot, (P[0], ic + 1))
    # mean displacement along d2 minus rotation / (yP sc): P's u_c drops out (dependent: the centroid's u_c)
    comb = {}
    for n, _, _, w in pts:
        comb[(n, ic + 1)] = comb.get((n, ic + 1), 0.0) + w
    for n, d, c in rot:
        comb[(n, d)] = comb.get((n, d), 0.0) - c / (yP * sc)
    comb[(P[0], ic + 1)] = 0.0
    lines += ["** mean displacement of the face along d2 = 0 (combined with the rotation equation)"]
    lines += eq([(n, d, c) for (n, d), c in sorted(comb.items())], (centre[0], ic + 1))
    return lines


def sensor_nodes(prob, mesh):
    """[(sensor name, node id)] at the section centroid; DeckError if no node is there."""
    out = []
    for name, s in prob.sensors:
        n = mesh.node_at(s / prob.length)
        if n is None:
            where = ("graded along the axis: the ends are always nodes" if mesh.grading.x.graded else
                     f"nodes every {prob.length / (2 * mesh.nx):.6g} m along the axis")
            raise DeckError(f"error: {prob.path}: sensor.{name}.at: no node of mesh {mesh.label} at the centroid "
                            f"of the section at {s:.6g} m ({where}; ny and nz not both odd)")
        out.append((name, n))
    return out


def layer_cards(prob, mesh, continuation):
    """A layered section (beam.layers): one element set and material per layer, the
    elements through the height assigned by their middle; refused unless every
    layer interface is an element face, and for layers that would need the
    bulk-modulus continuation (it is made for one material) or Rayleigh damping."""
    import dataclasses
    fz = mesh.fz
    for _, z0, _ in prob.layers[1:]:
        if min(abs(z0 - fz[2 * k]) for k in range(mesh.nz + 1)) > 1e-9:
            raise DeckError(f"mesh {mesh.label}: the layer interface at {z0:.6g} h is not an element face "
                            "(choose nz so that every layer is a whole number of elements high)")
    if prob.analysis == "dynamic" and (prob.rayleigh_alpha or prob.rayleigh_beta):
        raise DeckError("the CalculiX deck of a layered section takes no Rayleigh damping")
    out, sets = [], [[] for _ in prob.layers]
    for e in range(len(mesh.elements)):
        zc = fz[2 * (e % mesh.nz) + 1]
        sets[next(i for i, (_, z0, z1) in enumerate(prob.layers) if z0 <= zc <= z1)].append(e + 1)
    for i, (mat, _, _) in enumerate(prob.layers):
        if continuation and continuation_kappa(dataclasses.replace(prob, material=mat, layers=None)) is not None:
            raise DeckError("the CalculiX deck's bulk-modulus continuation takes one material; "
                            f"layer {i} is nearly incompressible")
        out += material_cards(mat, None, name=f"M{i}")
        out += [f"*ELSET, ELSET=LAYER{i}"] + [", ".join(map(str, sets[i][j:j + 16]))
                                              for j in range(0, len(sets[i]), 16)]
        out += [f"*SOLID SECTION, ELSET=LAYER{i}, MATERIAL=M{i}"]
    return out


def write_deck(prob, nx, ny, nz, increments=None, grading=None, continuation=True):
    """(deck text, mesh, [(sensor name, node set name, node id)]); `grading` a
    calculix.mesh.Grading (default uniform); continuation=False loads with the
    material's own bulk modulus from the start (see continuation_kappa)."""
    mesh = build_mesh(prob, nx, ny, nz, grading)
    sens = sensor_nodes(prob, mesh)
    L = [f"** beamkit -> CalculiX: scene {prob.path}, C3D20R mesh {mesh.label}",
         "*HEADING", f"beamkit scene {prob.name}, C3D20R {mesh.label}",
         "*NODE, NSET=NALL"]
    L += [f"{i + 1}, {_f(x)}, {_f(y)}, {_f(z)}" for i, (x, y, z) in enumerate(mesh.coords)]
    L.append("*ELEMENT, TYPE=C3D20R, ELSET=EALL")
    for e, conn in enumerate(mesh.elements):
        L.append(f"{e + 1}, " + ", ".join(map(str, conn[:15])) + ",")
        L.append(", ".join(map(str, conn[15:])))
    sets = []
    for k, (name, n) in enumerate(sens):
        sets.append((name, f"S{k + 1}", n))
        L += [f"*NSET, NSET=S{k + 1}", str(n)]
    kappa0 = continuation_kappa(prob) if continuation else None
    if prob.layers:
        L += layer_cards(prob, mesh, continuation)
    else:
        L += material_cards(prob.material, kappa0)
        if prob.analysis == "dynamic" and (prob.rayleigh_alpha or prob.rayleigh_beta):
            L += [f"*DAMPING, ALPHA={_f(prob.rayleigh_alpha)}, BETA={_f(prob.rayleigh_beta)}"]
        L += ["*SOLID SECTION, ELSET=EALL, MATERIAL=M"]
    for side, mode in prob.clamps:
        face = mesh.face(side)
        L += [f"*NSET, NSET=CLAMP_{side.upper()}"]
        ids = [str(row[0]) for row in face]
        L += [", ".join(ids[i:i + 16]) for i in range(0, len(ids), 16)]
        if mode == "rigid":
            L += ["** rigid clamp: every node of the face fixed", "*BOUNDARY", f"CLAMP_{side.upper()}, 1, 3, 0.0"]
        else:
            L += _free_clamp(prob, mesh, side)
    if prob.analysis == "dynamic":
        w, c, v = prob.angular_velocity, prob.center, prob.velocity
        vel = []
        for i, X in enumerate(mesh.coords):
            r = [X[k] - c[k] for k in range(3)]
            u = [v[0] + w[1] * r[2] - w[2] * r[1], v[1] + w[2] * r[0] - w[0] * r[2], v[2] + w[0] * r[1] - w[1] * r[0]]
            vel += [f"{i + 1}, {k + 1}, {_f(u[k])}" for k in range(3) if u[k] != 0.0]
        if vel:
            L += ["*INITIAL CONDITIONS, TYPE=VELOCITY"] + vel
    if prob.analysis == "dynamic":        # output at every dt (ccx lands its increments on them)
        L += ["*TIME POINTS, NAME=TOUT, GENERATE", f"{_f(prob.dt)}, {_f(prob.t_end)}, {_f(prob.dt)}"]
    loads = []
    amp = "RAMP" if prob.analysis == "static" else "CONST"
    for side, F in sorted(prob.forces.items()):
        cl = []
        for n, _, _, _, _, wt in mesh.face(side):
            cl += [f"{n}, {k + 1}, {_f(wt * F[k])}" for k in range(3) if F[k] != 0.0]
        if cl:
            loads += [f"** force {F} N on the {side} face as a uniform traction (consistent nodal weights)",
                      f"*CLOAD, AMPLITUDE={amp}"] + cl
    if prob.gravity is not None:
        g = math.sqrt(sum(x * x for x in prob.gravity))
        if g > 0:
            loads += [f"*DLOAD, AMPLITUDE={amp}",
                      "EALL, GRAV, " + _f(g) + ", " + ", ".join(_f(x / g) for x in prob.gravity)]
    tp = ", TIME POINTS=TOUT" if prob.analysis == "dynamic" else ""
    prints = []
    for _, nset, _ in sets:
        prints += [f"*NODE PRINT, NSET={nset}{tp}", "U"]
    tight = ["*CONTROLS, PARAMETERS=FIELD", ", ".join(_f(x) for x in FIELD_CONTROLS)]
    if prob.analysis == "static":
        n = increments or prob.load_steps
        dt = 1.0 / n
        if kappa0 is not None:
            L += ["*INITIAL CONDITIONS, TYPE=TEMPERATURE", "NALL, 0.0"]
        # the load factor follows the total time: 0 -> 1 in the first step, 1 after
        L += ["*AMPLITUDE, NAME=RAMP, TIME=TOTAL TIME", "0.0, 0.0, 1.0, 1.0, 1.0e9, 1.0"]
        L += ["** step 1: the loads ramped 0 -> 1 (ccx's default tolerances, increments cut back and grown by ccx)",
              "*STEP, NLGEOM, INC=10000000", "*STATIC", f"{_f(dt)}, 1.0, {_f(dt * 1e-6)}, 1.0"]
        L += loads + ["*END STEP"]
        if kappa0 is not None:
            L += [f"** step 2: bulk modulus {kappa0:.6g} Pa (temperature 0) -> the material's (temperature 1), "
                  "at full load", "*STEP, NLGEOM, INC=10000000", "*STATIC", f"{_f(0.1)}, 1.0, {_f(1e-7)}, 1.0",
                  "*TEMPERATURE", "NALL, 1.0", "*END STEP"]
        L += ["** last step: one increment at full load with tight tolerances (the result)",
              "*STEP, NLGEOM, INC=10000000", "*STATIC", "1.0, 1.0, 1.0e-6, 1.0"] + tight + prints + ["*END STEP", ""]
    else:
        L += ["*AMPLITUDE, NAME=CONST", "0.0, 1.0, 1.0e9, 1.0"]
        alpha = (prob.rho_inf - 1.0) / (prob.rho_inf + 1.0)
        L += ["*STEP, NLGEOM, INC=10000000", f"*DYNAMIC, ALPHA={_f(alpha)}",
              f"{_f(prob.dt)}, {_f(prob.t_end)}, {_f(prob.dt * 1e-4)}, {_f(prob.dt)}"]
        L += tight + loads + prints + ["*END STEP", ""]
    return "\n".join(L), mesh, sets


def final_time(prob, continuation=True):
    """ccx's total time at the end of the deck's analysis: the number of static
    steps (each of time 1), or t_end."""
    if prob.analysis == "dynamic":
        return prob.t_end
    return 3.0 if continuation and continuation_kappa(prob) is not None else 2.0
