"""Joints at beam points between nodes: the arc lengths where a [[constraint]]
names a point of a beam (`a` or `b` = "BEAM:<arc length>") that no element end
reaches get a node, by splitting the element there (the mesh is otherwise as
`elements`, `grading` or `element_lengths` made it)."""
import math

TOL = 1e-9          # a point within TOL x the beam length of a node is that node


def joint_points(doc, bname):
    """Arc lengths (m, as written) of the constraint points on beam bname."""
    out = []
    cons = doc.get("constraint", [])
    if not isinstance(cons, list):
        return out
    for ct in cons:
        if not isinstance(ct, dict):
            continue
        for key in ("a", "b"):
            spec = ct.get(key)
            if not isinstance(spec, str) or ":" not in spec:
                continue
            beam, where = spec.rsplit(":", 1)
            if beam != bname or where in ("start", "end"):
                continue
            try:
                s = float(where)
            except ValueError:
                continue            # (the joint's reader reports it)
            if math.isfinite(s):
                out.append(s)
    return out


def split_at_joints(ctx, doc, bt, where, bname, lens, length):
    """(element lengths with a node at every joint point, warnings)."""
    starts = [0.0]
    for l in lens:
        starts.append(starts[-1] + l)
    cuts = sorted({s for s in joint_points(doc, bname) if 0.0 < s < length * (1 - TOL)
                   and min(abs(s - x) for x in starts) > TOL * length})
    if not cuts:
        return lens, []
    if "sections" in bt:
        ctx.fail(f"{where}.sections", f"a joint at arc length {cuts[0]:.6g} m lies between nodes, and a node is "
                 "added there: give the sections by section_end, or put the joint at a node")
    nodes = sorted(set(starts) | set(cuts))
    new = [b - a for a, b in zip(nodes[:-1], nodes[1:])]
    if min(new) < 1e-6 * length:
        k = min(range(len(new)), key=lambda i: new[i])
        ctx.fail(f"{where}.elements", f"a joint at arc length {nodes[k + 1] if nodes[k + 1] in cuts else nodes[k]:.6g} m "
                 f"is within {new[k]:.3g} m of a node: put it at the node or {1e-6 * length:.3g} m or more away")
    pts = ", ".join(f"{c:.6g}" for c in cuts)
    return new, [f"{where}: node(s) added at arc length {pts} m for joints between nodes ({len(new)} elements "
                 f"instead of {len(lens)})"]
