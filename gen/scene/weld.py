"""Welds of an ANCF node to a frame: `fixed`, or `clamp` with `b`, between a node
of a continuum ANCF or cable beam and a node of a rod (gef, euler_bernoulli,
kirchhoff) or a rigid body, as joints nonlinear in q (the joint kernels of
gen/body.py, runtime/bk_joint.h).

What the weld imposes, with R_b the frame's rotation, R_b0 its reference:
  * position: r = x_b + R_b c, c = R_b0^T (X - X_b) (the body's centre may be
    anywhere; a rod node must coincide with the ANCF node);
  * the section rigid at the weld, as a rigid clamp holds it: every nodal
    section vector v of r_y, r_z, r_yy, r_yz, r_zz the node has follows b,
    v = R_b R_b0^T v_0.  The axial slope r_x (ancf3243, ancf3273) stays free:
    its stretch and shear are the ANCF element's own (there is no rod strain
    to match at a node);
  * a cable (r, r_x): r_x along b's rotated reference tangent (two rows), its
    stretch free; the cable has no torsion, b's twist about the tangent is
    b's own.
One [[constraint]] is several joints (a spherical joint for the position and
weld_vectors / weld_vector / weld_tangent for the section, each at most
BK_JOINT_MAXROW rows); its reaction sums them on side a's DOFs.
"""
from gen.scene.held_section import graded_clamp_warning
from gen.scene.joint_frames import endpoint as _endpoint, mtv as _mtv
from gen.scene.values import _cross, _norm, _sub

SECTION_FIELDS = ("r_y", "r_z", "r_yy", "r_yz", "r_zz")


def _is_ancf(spec, mesh):
    """Whether spec names a point of an ANCF (continuum or cable) beam."""
    if not isinstance(spec, str) or ":" not in spec:
        return False
    beam = mesh.beams.get(spec.rsplit(":", 1)[0])
    return beam is not None and beam["element"].startswith("ancf")


def _is_frame(spec, mesh):
    """Whether spec names a body or a point of a beam whose nodes turn (rods)."""
    if isinstance(spec, str) and ":" not in spec:
        return spec in mesh.bodies
    return isinstance(spec, str) and not _is_ancf(spec, mesh) and spec.rsplit(":", 1)[0] in mesh.beams


def is_weld(ct, mesh, ctype):
    """A `fixed` joint or a `clamp` with b between an ANCF point and a rod point or
    a body (either side), built by weld() rather than the other joints."""
    if ctype not in ("fixed", "clamp") or "b" not in ct:
        return False
    a, b = ct.get("a"), ct.get("b")
    return (_is_ancf(a, mesh) and _is_frame(b, mesh)) or (_is_ancf(b, mesh) and _is_frame(a, mesh))


def _across(t):
    """Two unit vectors across the unit vector t, and across each other."""
    n1 = _cross(t, [1.0, 0.0, 0.0])
    if _norm(n1) < 0.5:
        n1 = _cross(t, [0.0, 1.0, 0.0])
    n1 = [c / _norm(n1) for c in n1]
    return n1, _cross(t, n1)


def weld(ctx, ct, where, mesh, rows, ctype, ci, name):
    """The joints of an ANCF-to-frame weld appended to rows.nlcons and its
    reaction (on side a, about the ANCF node) to rows.reactions."""
    from gen.scene.mesh import locate
    if "cross_section" in ct:
        ctx.fail(f"{where}.cross_section", "expected no cross_section with b (a weld holds the section rigid)")
    ka, kf = ("a", "b") if _is_ancf(ct["a"], mesh) else ("b", "a")
    beam, s, gid = mesh.node_of(ctx, f"{where}.{ka}", ct[ka], f"{ctype} joint")
    fd, q0, X = mesh.field_dofs(gid), mesh.q0, mesh.nodes[gid][0]
    fr = _endpoint(ctx, f"{where}.{kf}", ct[kf], mesh, ctype)
    if not fr["rot"]:
        ctx.fail(f"{where}.{kf}", f"a weld of an ANCF point needs a rotation on its other side; {fr['what']} "
                 "has none")
    tol = 1e-9 * max(1.0, _norm(X))
    if "at" in ct:
        from gen.scene.values import get_vec3
        at = get_vec3(ctx, ct, "at", where, bound=1e9)
        if _norm(_sub(at, X)) > tol:
            ctx.fail(f"{where}.at", f"the joint point of a weld must be the ANCF node {ct[ka]} at {X}, "
                     f"found {at}")
    if ":" in ct[kf] and _norm(_sub(X, fr["X"])) > tol:
        ctx.fail(f"{where}.{kf}", f"the points a and b must coincide in the reference configuration "
                 f"({ct[ka]} at {X}, {ct[kf]} at {fr['X']}; a weld at an offset joins a body)")
    R0 = fr["R"]
    c_b = _mtv(R0, _sub(X, fr["X"]))
    eye = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    axes_b = [c for k in range(3) for c in _mtv(R0, eye[3 * k: 3 * k + 3])]
    pb = fr["dofs"][3:7]
    pb0 = [q0[d] for d in pb]
    none = (0.0, 0.0, 0.0, 0.0, -1)
    first = len(rows.nlcons)
    rows.nlcons.append(("spherical", fd["r"] + [-1] * 4 + fr["dofs"],
                        [q0[d] for d in fd["r"]] + [1.0, 0.0, 0.0, 0.0] + [q0[d] for d in fr["dofs"]],
                        [0.0] * 3 + c_b + eye + axes_b, none))

    def ref(f):
        return _mtv(R0, [q0[d] for d in fd[f]])
    if set(fd) == {"r", "r_x"}:                                     # ancf_cable
        t0 = [q0[d] for d in fd["r_x"]]
        n1, n2 = _across([c / _norm(t0) for c in t0])
        vecs = [("weld_tangent", ["r_x"], [_mtv(R0, n1), _mtv(R0, n2)])]
    else:
        fs = [f for f in SECTION_FIELDS if f in fd]
        vecs = [("weld_vectors" if len(fs[i:i + 2]) == 2 else "weld_vector", fs[i:i + 2],
                 [ref(f) for f in fs[i:i + 2]]) for i in range(0, len(fs), 2)]
        unknown = sorted(set(fd) - set(fs) - {"r", "r_x"})
        if unknown or not fs:
            ctx.fail(f"{where}.{ka}", f"a weld needs the section vectors of an ANCF node; {ct[ka]} has fields "
                     f"{sorted(fd)}")
    for kind, fields, ws in vecs:
        dofs = [d for f in fields for d in fd[f]]
        dofs += [-1] * (10 - len(dofs)) + pb
        x0 = [q0[d] if d >= 0 else 0.0 for d in dofs[:10]] + pb0
        w = [c for v in ws for c in v]
        rows.nlcons.append((kind, dofs, x0, [0.0] * 6 + w + [0.0] * (18 - len(w)), none))
    side = [d for f in fd.values() for d in f] if ka == "a" else list(fr["dofs"])
    if ka == "a":
        e, xi = locate(beam, s)
    else:
        e, xi = fr["where"]
    rows.reactions.append((ci, ctype, ct["a"], e, xi, [], [], side, first, name, len(rows.nlcons) - first))
    graded_clamp_warning(mesh, where, beam, s, "a weld (the section held rigid, as a clamp holds it)")
