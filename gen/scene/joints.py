"""Joints: [[constraint]] tables as rows of linear, possibly rheonomic
constraints on the DOFs (the bk_lincon form of runtime/model/model.h), by type.

A joint type is a function (ctx, ct, where, mesh, rows, beam, s, gid) that adds
rows with rows.row(...) or holds DOFs with rows.fixed; JOINTS maps each
`type` (gen/scene_keys.py CONSTRAINT) to its function.  Adding a joint: a
function here, its keys in scene_keys.CONSTRAINT, a test.
"""
import gen.scene_keys as K
from gen.scene.joint_frames import endpoint as _endpoint, mtv as _mtv
from gen.scene.held_section import graded_clamp_warning
from gen.scene.values import (_cross, _dot, _norm, _scale, _skew, _sub, check_keys, get_array_of_tables,
                              get_number, get_str, get_vec3, plain_name)


class Rows:
    """Constraint rows being collected: fixed DOFs and linear constraints."""

    def __init__(self, q0, amps=None):
        self.q0 = q0
        self.amps = amps
        self.fixed = set()
        self.lincons = []
        self.reactions = []     # per [[constraint]]: (index, type, point, element, xi, fixed, lincons, side, joint,
        #                         name, joints: how many joints from `joint` on)
        self.side = None        # DOFs of the side-a body of a joint between bodies (None: all)
        self.keep_rows = False  # the rotating frame's constraint (dynamic.frame): its driven rows stay rows

    def row(self, terms, r0=0.0, rc=0.0, rs=0.0, kappa=0.0, rate=0.0, amp=0.0, freq=0.0, angle=0.0, ampid=-1,
            ru=0.0, uampid=-1):
        """terms: [(dof, c0, cc, cs)]: sum (c0 + cc cos phi + cs sin phi) q = r0 + rc cos phi + rs sin phi
        + ru u(t), phi(t) = kappa (rate t + amp sin(2 pi freq t) + angle a(t)), a the amplitude ampid (-1:
        none), u the amplitude uampid (-1: t itself, the load factor in statics).  A static single-DOF row is
        a fixed DOF."""
        terms = [t_ for t_ in terms if any(abs(c) > 1e-15 for c in t_[1:])]
        if not terms:
            return
        if len(terms) == 1 and terms[0][2] == 0 and terms[0][3] == 0 and rc == 0 and rs == 0 and ru == 0 \
                and not (self.keep_rows and kappa) and abs(r0 - terms[0][1] * self.q0[terms[0][0]]) <= 1e-12 * max(1.0, abs(r0)):
            self.fixed.add(terms[0][0])
            return
        self.lincons.append((terms, (r0, rc, rs), (kappa, rate, amp, freq, angle, float(ampid), ru,
                                                   float(uampid))))


def _axis_frame(ctx, ct, where):
    axis = get_vec3(ctx, ct, "axis", where, nonzero=True)
    axis = _scale(axis, 1 / _norm(axis))
    n1 = _cross(axis, [1.0, 0.0, 0.0])
    if _norm(n1) < 0.5:
        n1 = _cross(axis, [0.0, 1.0, 0.0])
    n1 = _scale(n1, 1 / _norm(n1))
    return axis, n1, _cross(axis, n1)


def clamp(ctx, ct, where, mesh, rows, beam, s, gid):
    """Every nodal coordinate held (rigid section), or position and the
    directions of the slopes held but not their lengths (free section)."""
    fd, fixed, row = mesh.field_dofs(gid), rows.fixed, rows.row
    if "b" in ct:
        _rigid_joint(ctx, ct, where, mesh, rows, beam, gid)
        return
    mode = get_str(ctx, ct, "cross_section", where, default="rigid", choices=("rigid", "free"))
    if mode == "rigid":
        for dl in fd.values():
            fixed.update(dl)
        if any(beam.get("layer_elems", ())) and "cross_section" not in ct:
            mesh.warnings.append(f"{where}: beam {beam['name']} is layered: a rigid clamp holds the centreline's "
                                 "stretch at the root, which bending about the off-centre neutral axis needs "
                                 "(a bilayer 2 % too stiff at 10 elements, 0.5 % at 40); "
                                 "cross_section = \"free\" holds the section without it")
        graded_clamp_warning(mesh, where, beam, s)
        return
    _, t, d1, d2 = beam["geo"].at(s)
    normals = {"r_x": (d1, d2), "r_y": (t, d2), "r_z": (t, d1)}
    for f, dl in fd.items():
        if f == "r" or len(dl) != 3:
            fixed.update(dl)                                  # position, rotations: held
        elif f in normals:
            for nrm in normals[f]:
                row([(dl[i], nrm[i], 0.0, 0.0) for i in range(3)])
        else:                   # r_yy, r_yz, r_zz: the section stays plane, free in its plane
            row([(dl[i], t[i], 0.0, 0.0) for i in range(3)])


def _quat_mul(p, r):
    """Hamilton product p r of quaternions (s, x, y, z)."""
    ps, pv, rs, rv = p[0], p[1:], r[0], r[1:]
    c = _cross(pv, rv)
    return [ps * rs - _dot(pv, rv)] + [ps * rv[i] + rs * pv[i] + c[i] for i in range(3)]


def _rigid_joint(ctx, ct, where, mesh, rows, beam, gid):
    """clamp with b: the sections at a and b (coinciding points of two beams)
    move as one: equal positions and p_b = p_a r with the constant relative
    rotation r = conj(p_a0) p_b0 (rows linear in the quaternions; gef-family
    nodes), or, between continuum ANCF nodes, equal nodal vectors (_ancf_weld)."""
    q0 = mesh.q0
    if "cross_section" in ct:
        ctx.fail(f"{where}.cross_section", "expected no cross_section with b (a rigid beam-to-beam joint)")
    beam_b, s_b, gid_b = mesh.node_of(ctx, f"{where}.b", ct["b"], "rigid joint")
    X, Xb = mesh.nodes[gid][0], mesh.nodes[gid_b][0]
    if _norm(_sub(X, Xb)) > 1e-9 * max(1.0, _norm(X)):
        ctx.fail(f"{where}.b", f"the points a and b must coincide in the reference configuration "
                 f"({ct['a']} at {X}, {ct['b']} at {Xb})")
    if gid_b == gid:
        ctx.fail(f"{where}.b", "a and b are the same node")
    fa, fb = mesh.field_dofs(gid), mesh.field_dofs(gid_b)
    if "p" not in fa and "p" not in fb:
        _ancf_weld(ctx, ct, where, rows, q0, fa, fb)
        return
    for f, name in ((fa, ct["a"]), (fb, ct["b"])):
        if set(f) != {"r", "p"}:
            ctx.fail(f"{where}.b", "a rigid beam-to-beam joint needs gef-family nodes (position and quaternion) "
                     f"at both points; {name} has fields {sorted(f)}")
    rows.side = list(fa["r"]) + list(fa["p"])                 # the reaction on beam a (as `fixed`)
    for i in range(3):
        rows.row([(fa["r"][i], 1.0, 0.0, 0.0), (fb["r"][i], -1.0, 0.0, 0.0)])
    pa0 = [q0[d] for d in fa["p"]]
    pb0 = [q0[d] for d in fb["p"]]
    rel = _quat_mul([pa0[0], -pa0[1], -pa0[2], -pa0[3]], pb0)
    n2 = sum(x * x for x in pa0)
    rel = [x / n2 for x in rel]
    cols = [_quat_mul([1.0 if k == j else 0.0 for k in range(4)], rel) for j in range(4)]   # p -> p r
    for k in range(4):
        rows.row([(fb["p"][k], 1.0, 0.0, 0.0)] + [(fa["p"][j], -cols[j][k], 0.0, 0.0) for j in range(4)])


def _ancf_weld(ctx, ct, where, rows, q0, fa, fb):
    """clamp with b between two nodes of continuum ANCF beams: every nodal vector of
    b equal to a's (the two nodes move as one, as a shared node would), which needs
    the same nodal fields with the same reference values (sections aligned: a beam
    continued by a segment of another section or material)."""
    if sorted(fa) != sorted(fb):
        ctx.fail(f"{where}.b", f"a weld of ANCF nodes needs the same nodal fields at both points; "
                 f"{ct['a']} has {sorted(fa)}, {ct['b']} has {sorted(fb)}")
    for f in fa:
        va, vb = [q0[d] for d in fa[f]], [q0[d] for d in fb[f]]
        if f != "r" and max(abs(x - y) for x, y in zip(va, vb)) > 1e-9:
            ctx.fail(f"{where}.b", f"a weld of ANCF nodes needs aligned sections (equal reference {f}: "
                     f"{va} at {ct['a']}, {vb} at {ct['b']})")
    for f in fa:
        for da, db in zip(fa[f], fb[f]):
            rows.row([(da, 1.0, 0.0, 0.0), (db, -1.0, 0.0, 0.0)])


def spherical(ctx, ct, where, mesh, rows, beam, s, gid):
    """The point held in space (to ground) or at a point of another beam (b)."""
    fd, fixed, row = mesh.field_dofs(gid), rows.fixed, rows.row
    nodes = mesh.nodes
    X = nodes[gid][0]
    if "b" not in ct:
        fixed.update(fd["r"])                                 # to ground
        return
    beam_b, s_b, gid_b = mesh.node_of(ctx, f"{where}.b", ct["b"], "spherical joint")
    if _norm(_sub(X, nodes[gid_b][0])) > 1e-9 * max(1.0, _norm(X)):
        ctx.fail(f"{where}.b", f"the points a and b must coincide in the reference configuration "
                 f"({ct['a']} at {X}, {ct['b']} at {nodes[gid_b][0]})")
    if gid_b == gid:
        ctx.fail(f"{where}.b", "a and b are the same node")
    fb = mesh.field_dofs(gid_b)
    rows.side = list(fd["r"])                                 # the reaction on beam a
    for i in range(3):
        row([(fd["r"][i], 1.0, 0.0, 0.0), (fb["r"][i], -1.0, 0.0, 0.0)])


def prescribed_motion(ctx, ct, where, mesh, rows, beam, s, gid):
    """The point moved by `motion` (m) times the load factor in statics, or
    times `amplitude` (required in dynamics): three rows, one per component;
    with `clamped = true` the node's other coordinates (ANCF gradients, a
    rod's quaternion) are held too: a clamp that translates."""
    fd, q0 = mesh.field_dofs(gid), mesh.q0
    clamped = ct.get("clamped", False)
    if not isinstance(clamped, bool):
        ctx.fail(f"{where}.clamped", f"expected true or false (got {clamped!r})")
    if clamped:
        rows.fixed.update(d for f, ds in fd.items() if f != "r" for d in ds)
    motion = get_vec3(ctx, ct, "motion", where)
    uamp = rows.amps.ref(ct, "amplitude", where) if rows.amps is not None else -1
    if uamp < 0 and getattr(rows, "analysis", "static") == "dynamic":
        ctx.fail(f"{where}.amplitude", "missing; a prescribed motion in dynamics needs an amplitude (a ramp, ...)")
    for i in range(3):
        d = fd["r"][i]
        rows.row([(d, 1.0, 0.0, 0.0)], r0=q0[d], ru=motion[i], uampid=uamp)


def _axis_joint(ctx, ct, where, mesh, rows, beam, s, gid, ctype):
    fd, fixed, row, q0 = mesh.field_dofs(gid), rows.fixed, rows.row, mesh.q0
    axis, n1, n2 = _axis_frame(ctx, ct, where)
    _, t, d1, d2 = beam["geo"].at(s)
    fixed.update(fd["r"])                                     # the axis passes through the point
    if ctype == "revolute":
        if "p" in fd:                   # quaternion: vec(p conj(p0)) parallel to the axis
            p0 = [q0[d] for d in fd["p"]]
            s0, v0 = p0[0], p0[1:]
            A = [[-v0[i]] + [(s0 if i == j else 0.0) + _skew(v0)[i][j] for j in range(3)] for i in range(3)]
            for nrm in (n1, n2):
                row([(fd["p"][k], sum(nrm[i] * A[i][k] for i in range(3)), 0.0, 0.0) for k in range(4)])
        else:                           # ANCF: the material fibre along the axis stays along it
            comps = {"r_x": _dot(axis, t), "r_y": _dot(axis, d1), "r_z": _dot(axis, d2)}
            for f, c in comps.items():
                if abs(c) > 1e-12 and f not in fd:
                    ctx.fail(f"{where}.axis", f"element {beam['element']} has no nodal {f} at this "
                             "point; a revolute axis there must lie in the cross-section plane")
            for nrm in (n1, n2):
                terms = []
                for f, c in comps.items():
                    if abs(c) > 1e-12:
                        terms += [(fd[f][i], c * nrm[i], 0.0, 0.0) for i in range(3)]
                row(terms)
    else:
        rate = get_number(ctx, ct, "rate", where, default=0.0)
        amp = get_number(ctx, ct, "amplitude", where, default=0.0)
        freq = get_number(ctx, ct, "frequency", where, default=0.0, nonneg=True)
        angle = get_number(ctx, ct, "angle", where, default=0.0)
        ampid = rows.amps.ref(ct, "angle_amplitude", where) if rows.amps else -1
        if ampid >= 0 and "angle" not in ct:
            ctx.fail(f"{where}.angle", "missing; `angle_amplitude` scales the angle `angle` (rad)")
        if "angle" in ct and ampid < 0:
            ampid = rows.amps.ref({"a": {"type": "ramp"}}, "a", where) if rows.amps else -1
        tf = (rate, amp, freq, angle, ampid)
        for f, dl in fd.items():
            if f == "r":
                continue
            if f == "p":                # p(t) = (cos th/2, sin th/2 axis) p0
                s0, v0 = q0[dl[0]], [q0[d] for d in dl[1:]]
                av = _dot(axis, v0)
                cr = _cross(axis, v0)
                row([(dl[0], 1.0, 0.0, 0.0)], 0.0, s0, -av, 0.5, *tf)
                for i in range(3):
                    row([(dl[1 + i], 1.0, 0.0, 0.0)], 0.0, v0[i], s0 * axis[i] + cr[i], 0.5, *tf)
            elif len(dl) == 3:          # nodal vectors rotate rigidly
                v0 = [q0[d] for d in dl]
                par = _dot(axis, v0)
                cr = _cross(axis, v0)
                for i in range(3):
                    row([(dl[i], 1.0, 0.0, 0.0)], par * axis[i], v0[i] - par * axis[i], cr[i],
                        1.0, *tf)
            else:
                fixed.update(dl)



def revolute(ctx, ct, where, mesh, rows, beam, s, gid):
    """The point held; the node turns about `axis` only (to ground)."""
    _axis_joint(ctx, ct, where, mesh, rows, beam, s, gid, "revolute")


def prescribed_rotation(ctx, ct, where, mesh, rows, beam, s, gid):
    """The point held; the node turned about `axis` by rate t + amplitude sin(2 pi frequency t)."""
    _axis_joint(ctx, ct, where, mesh, rows, beam, s, gid, "prescribed_rotation")


def point_on_line(ctx, ct, where, mesh, rows, beam, s, gid):
    """The point stays on the line through its reference position along `axis`
    (a roller, a slider): its position across the axis is held, along it free;
    the section turns freely."""
    axis, n1, n2 = _axis_frame(ctx, ct, where)
    r = mesh.field_dofs(gid)["r"]
    X = mesh.nodes[gid][0]
    for nrm in (n1, n2):
        rows.row([(r[i], nrm[i], 0.0, 0.0) for i in range(3)], _dot(nrm, X))


JOINTS = {"clamp": clamp, "spherical": spherical, "revolute": revolute, "prescribed_rotation": prescribed_rotation,
          "prescribed_motion": prescribed_motion,
          "point_on_line": point_on_line}


# ----------------------------------------------------------------------------
# Joints between two frames, nonlinear in q (generated: gen/body.py, out/kernels/joints.c)

NONLINEAR = ("spherical", "revolute", "universal", "fixed", "prismatic", "prescribed_rotation",
             "prescribed_translation")
_ROTATIONAL = ("revolute", "universal", "fixed", "prismatic", "prescribed_rotation", "prescribed_translation")
_DRIVE_KEYS = {"prescribed_rotation": ("angle", "angle_amplitude", "rad"),
               "prescribed_translation": ("distance", "distance_amplitude", "m")}


def _drive(ctx, ct, where, rows, ctype):
    """(rate, amplitude, frequency, scale, amplitude index) of a driven joint's
    th(t) = rate t + amplitude sin(2 pi frequency t) + scale a(t); no drive: zeros."""
    if ctype not in _DRIVE_KEYS:
        return (0.0, 0.0, 0.0, 0.0, -1)
    key, akey, unit = _DRIVE_KEYS[ctype]
    rate = get_number(ctx, ct, "rate", where, default=0.0)
    amp = get_number(ctx, ct, "amplitude", where, default=0.0)
    freq = get_number(ctx, ct, "frequency", where, default=0.0, nonneg=True)
    scale = get_number(ctx, ct, key, where, default=0.0)
    ampid = rows.amps.ref(ct, akey, where) if rows.amps else -1
    if ampid >= 0 and key not in ct:
        ctx.fail(f"{where}.{key}", f"missing; `{akey}` scales the {key} `{key}` ({unit})")
    if key in ct and ampid < 0:
        ampid = rows.amps.ref({"a": {"type": "ramp"}}, "a", where) if rows.amps else -1
    return (rate, amp, freq, scale, ampid)


def _joint_axes(ctx, ct, where, ctype):
    """Columns E1, E2, E3 (global) of the joint frame; the joint axis is E3."""
    if ctype in ("spherical", "fixed"):
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    if ctype == "universal":
        a1 = get_vec3(ctx, ct, "axis", where, nonzero=True)
        a2 = get_vec3(ctx, ct, "axis_b", where, nonzero=True)
        a1, a2 = _scale(a1, 1 / _norm(a1)), _scale(a2, 1 / _norm(a2))
        if abs(_dot(a1, a2)) > 1e-9:
            ctx.fail(f"{where}.axis_b", f"the arms of a universal joint must be perpendicular, found axis {a1!r} "
                     f"and axis_b {a2!r}")
        return [a1, a2, _cross(a1, a2)]
    axis, n1, n2 = _axis_frame(ctx, ct, where)
    return [n1, n2, axis]


def nonlinear_joint(ctx, ct, where, mesh, ctype, rows=None, actuated=False):
    """(type, dofs[14], x0[14], prm[24], drive[5]) of a joint between a and b (b omitted:
    the ground); a driven joint moves a relative to b (_drive).  actuated: an
    [[actuator]] acts on it (said when a side has no rotation)."""
    if "a" not in ct:
        ctx.fail(f"{where}.a", "missing; expected a point like 'arm:start' or a body name")
    a = _endpoint(ctx, f"{where}.a", ct["a"], mesh, ctype)
    b = _endpoint(ctx, f"{where}.b", ct.get("b"), mesh, ctype)
    if a["id"] == "ground":
        ctx.fail(f"{where}.a", "a must be a beam point or a body; omit b for a joint to the ground")
    if a["id"] == b["id"]:
        ctx.fail(f"{where}.b", f"a joint between {a['what']} and itself: a and b must be different bodies or nodes")
    if ctype in _ROTATIONAL:
        for side, e in (("a", a), ("b", b)):
            if not e["rot"]:
                why = " with an actuator" if actuated else ""
                ctx.fail(f"{where}.{side}", f"a {ctype} joint{why} needs a rotation on both sides; {e['what']} "
                         "has none (use gef, euler_bernoulli, kirchhoff beams or a body; an ANCF point takes "
                         "spherical, a clamp, and fixed to a rod point or a body)")
    if "at" in ct:
        X = get_vec3(ctx, ct, "at", where, bound=1e9)
    else:
        nodes = [e for e in (a, b) if e["what"].startswith("beam point")]
        if not nodes:
            ctx.fail(f"{where}.at", f"missing; a joint between {a['what']} and {b['what']} needs the joint "
                     "point `at` = [x, y, z]")
        X = nodes[0]["X"]
    for side, e in (("a", a), ("b", b)):
        if not e["rot"] and _norm(_sub(X, e["X"])) > 1e-9 * max(1.0, _norm(X)):
            ctx.fail(f"{where}.at", f"the joint point must be {e['what']}'s node at {e['X']} (it has no "
                     f"rotation to carry an offset), found {X}")
    E = _joint_axes(ctx, ct, where, ctype)
    dofs, x0, prm_c, prm_A = [], [], [], []
    for e in (a, b):
        if e["dofs"] is None:                       # the ground: constants
            dofs += [-1] * 7
            x0 += list(X) + [1.0, 0.0, 0.0, 0.0]
            prm_c += [0.0, 0.0, 0.0]
            prm_A += [c for col in E for c in col]
        else:
            dofs += e["dofs"]
            x0 += [mesh.q0[d] if d >= 0 else (1.0 if k == 3 else 0.0) for k, d in enumerate(e["dofs"])]
            prm_c += _mtv(e["R"], _sub(X, e["X"]))
            prm_A += [c for col in E for c in _mtv(e["R"], col)]
    return (ctype, dofs, x0, prm_c + prm_A, _drive(ctx, ct, where, rows, ctype)), a["where"]


def _is_linear(ct, mesh, ctype):
    """The joints the linear rows above express exactly: every type at a beam node
    with no body and (but spherical beam-to-beam) no second point."""
    if ctype not in NONLINEAR:
        return True
    names = [ct.get(k) for k in ("a", "b")]
    if any(isinstance(n, str) and ":" not in n and n in mesh.bodies for n in names) or "at" in ct:
        return False
    if ctype == "spherical":
        return True
    if ctype in ("revolute", "prescribed_rotation"):
        return "b" not in ct
    return False


def _name(ctx, ct, where, ci, names):
    """The constraint's `name` (letters, digits, _ . -; unique), default constraintN."""
    name = get_str(ctx, ct, "name", where, default=f"constraint{ci}")
    if not plain_name(name):
        ctx.fail(f"{where}.name", f"expected 1 to 63 letters, digits, '_', '.' or '-', found {name!r}")
    if name in names:
        ctx.fail(f"{where}.name", f"the name {name!r} is given to two constraints")
    names.add(name)
    return name


def constraints(ctx, doc, mesh, amps=None, analysis="static"):
    """Rows of every [[constraint]] table, and which rows each one added (its
    reaction: rows.reactions, the last field the index of its joint nonlinear
    in q in rows.nlcons, -1 for the linear rows)."""
    from gen.scene.mesh import locate
    rows = Rows(mesh.q0, amps)
    rows.analysis = analysis
    rows.nlcons = []
    names = set()
    from gen.scene.actuators import AXIS_KIND, actuated_joints
    from gen.scene.weld import is_weld, weld
    actuated = actuated_joints(doc)       # joints with a motor need their frames: nonlinear rows
    dyn = doc.get("dynamic")
    frame = dyn.get("frame") if isinstance(dyn, dict) and analysis == "dynamic" else None
    for ci, ct in enumerate(get_array_of_tables(ctx, doc, "constraint")):
        where = f"constraint[{ci}]"
        ctype = get_str(ctx, ct, "type", where, choices=tuple(JOINTS) + ("fixed", "universal", "prismatic",
                                                                         "prescribed_translation"))
        check_keys(ctx, ct, set(K.CONSTRAINT[ctype]), where)
        if "a" not in ct:
            ctx.fail(f"{where}.a", "missing; expected a point like 'arm:start'")
        name = _name(ctx, ct, where, ci, names)
        if is_weld(ct, mesh, ctype):
            weld(ctx, ct, where, mesh, rows, ctype, ci, name)
            continue
        linear = _is_linear(ct, mesh, ctype)
        motor = ctype in AXIS_KIND and name in actuated   # (other types refuse it: gen/scene/actuators.py)
        if not linear or motor:
            joint, (e, xi) = nonlinear_joint(ctx, ct, where, mesh, ctype, rows, actuated=motor and linear)
            rows.reactions.append((ci, ctype, ct["a"], e, xi, [], [], None, len(rows.nlcons), name, 1))
            rows.nlcons.append(joint)
            continue
        beam, s, gid = mesh.node_of(ctx, f"{where}.a", ct["a"], ctype)
        fixed0, nlin0 = set(rows.fixed), len(rows.lincons)
        rows.side = None
        # the frame's constraint keeps every driven row (whole quaternions and vectors: runtime/analysis/dyn_frame.c)
        rows.keep_rows = name == frame
        JOINTS[ctype](ctx, ct, where, mesh, rows, beam, s, gid)
        rows.keep_rows = False
        e, xi = locate(beam, s)
        rows.reactions.append((ci, ctype, ct["a"], e, xi, sorted(rows.fixed - fixed0),
                               list(range(nlin0, len(rows.lincons))), rows.side, -1, name, 0))
    return rows
