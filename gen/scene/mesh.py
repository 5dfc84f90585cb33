"""Meshing the [[beam]] tables: element lengths (uniform or graded), nodes,
DOF numbering, element tables and points on beams (BEAM:start, BEAM:end,
BEAM:<arc length>)."""
import itertools
import math
import time

import gen.scene_keys as K
from gen.scene.geometry import arc_geometry, eval_fraction, line_geometry, reference_field, section_geometry
from gen.scene.layers import beam_layers, element_bands, layer_eigenstrains, neutral_axis
from gen.scene.path import path_geometry
from gen.scene.materials import locking_warnings, small_strain
from gen.scene.plausible import beam_warnings
from gen.scene.values import _typename, check_keys, get_int, get_name, get_number, get_str, get_vec3

MAX_ELEMENTS = 1000000          # per beam (the model file and the solver use int indices)


class Mesh:
    """Nodes, DOFs and elements of the scene's beams, as they are built."""

    def __init__(self):
        self.beams = {}
        self.bodies = {}        # rigid bodies (gen/scene/bodies.py)
        self.warnings = []      # likely wrong results (printed, and in summary.json "warnings")
        self.nodes = []         # (position, t, d1, d2, fields) per global node
        self.dof_of_node = []
        self.ndof = 0
        self.q0 = []
        self.elements = []
        self.pairs, self.geoms, self.mats_used = [], [], []
        self.geom_index = {}

    def node_of(self, ctx, key, spec, what):
        """(beam, arc length, global node) of a point that must be a node."""
        beam, s_ = parse_point(ctx, spec, key, self.beams)
        gid = beam["node_at"].get(_key(s_, beam["length"]))
        if gid is None:
            near = min(beam["node_at"], key=lambda x: abs(x - s_ / beam["length"])) * beam["length"]
            ctx.fail(key, f"a {what} must be at a node of beam {beam['name']!r} (nearest node at arc "
                     f"length {near:.6g} m), found arc length {s_:.6g}")
        return beam, s_, gid

    def field_dofs(self, gid):
        """{field name: [global DOFs]} of a node."""
        out, base = {}, self.dof_of_node[gid]
        for f, dim in self.nodes[gid][4]:
            out[f] = list(range(base, base + dim))
            base += dim
        return out


def parse_point(ctx, spec, key, beams):
    """'beam:start' | 'beam:end' | 'beam:<arc length in m>' -> (beam, s)."""
    if not isinstance(spec, str):
        ctx.fail(key, f"expected a string like 'arm:end', found {_typename(spec)}")
    if ":" not in spec:
        ctx.fail(key, f"expected BEAM:start, BEAM:end or BEAM:<arc length in m>, found {spec!r}")
    bname, where = spec.rsplit(":", 1)
    if bname not in beams:
        ctx.fail(key, f"no beam named {bname!r} (beams: {', '.join(beams) or 'none'})")
    beam = beams[bname]
    if where == "start":
        return beam, 0.0
    if where == "end":
        return beam, beam["length"]
    try:
        s = float(where)
    except ValueError:
        ctx.fail(key, f"expected start, end or an arc length in m after ':', found {where!r}")
    if not math.isfinite(s) or s < 0 or s > beam["length"] * (1 + 1e-12):
        ctx.fail(key, f"arc length {where} outside beam {bname!r} (0 to {beam['length']:.6g} m)")
    return beam, min(s, beam["length"])


def element_lengths(ctx, bt, where, nel, length):
    """Element lengths of a beam: uniform, or graded by `grading` (ratio of the
    last element's length to the first's, geometric progression) or given by
    `element_lengths` (relative weights, scaled to the beam length)."""
    if "grading" in bt and "element_lengths" in bt:
        ctx.fail(f"{where}.grading", "give either grading or element_lengths, not both")
    if "element_lengths" in bt:
        v = bt["element_lengths"]
        if not isinstance(v, list) or len(v) != nel or any(
                isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(float(x)) or x <= 0
                for x in v):
            ctx.fail(f"{where}.element_lengths", f"expected an array of {nel} positive numbers (one per element, "
                     f"relative lengths), found {_typename(v) if not isinstance(v, list) else repr(v)}")
        w = [float(x) for x in v]
    elif "grading" in bt:
        r = get_number(ctx, bt, "grading", where, positive=True)
        if not 1e-3 <= r <= 1e3:
            ctx.fail(f"{where}.grading", f"expected a ratio last / first element length in [0.001, 1000], found {r!r}")
        w = [r ** (k / (nel - 1)) if nel > 1 else 1.0 for k in range(nel)]
    else:
        w = [1.0] * nel
    tot = sum(w)
    ls = [length * x / tot for x in w]
    if min(ls) < 1e-9 * length:
        ctx.fail(f"{where}.element_lengths", "an element is shorter than 1e-9 of the beam")
    return ls


def _key(s, length):
    """Dictionary key of an arc length on a beam (relative, rounded)."""
    return round(s / length * 1e9) / 1e9


def locate_node(beam, frac):
    """(element, xi) of the node at `frac` of the beam length."""
    return locate(beam, frac * beam["length"])


def locate(beam, s):
    """(global element index, xi) of arc length s on a beam."""
    from gen.scene.path import bisect_right
    starts = beam["elem_start"]
    n = beam["nelem"]
    k = min(max(bisect_right(starts, s + 1e-12 * beam["length"]) - 1, 0), n - 1)
    l = beam["elem_lens"][k]
    xi = min(max((s - starts[k]) / l, 0.0), 1.0)
    return beam["first_elem"] + k, xi


def element_sections(ctx, bt, where, sections, sec, mids):
    """The section of each element: the beam's `section`; a linear taper from it to
    `section_end` (each element takes the section at its middle, mids: fractions of
    the beam length); or one name per element in `sections`."""
    if "section_end" in bt and "sections" in bt:
        ctx.fail(f"{where}.sections", "give either section_end (a linear taper) or sections (one per element)")
    if "section_end" in bt:
        name = get_str(ctx, bt, "section_end", where)
        if name not in sections:
            ctx.fail(f"{where}.section_end", f"no [section.{name}] in the scene (sections: {', '.join(sections)})")
        end = sections[name]
        if end[0] != sec[0]:
            ctx.fail(f"{where}.section_end", f"a taper needs sections of one shape: {sec[0]} at the start, "
                     f"{end[0]} at the end")
        return [(sec[0], sec[1] + f * (end[1] - sec[1]), sec[2] + f * (end[2] - sec[2])) for f in mids]
    if "sections" in bt:
        v = bt["sections"]
        if not isinstance(v, list) or len(v) != len(mids) or not all(isinstance(x, str) for x in v):
            ctx.fail(f"{where}.sections", f"expected an array of {len(mids)} section names (one per element), "
                     f"found {_typename(v) if not isinstance(v, list) else repr(v)}")
        for x in v:
            if x not in sections:
                ctx.fail(f"{where}.sections", f"no [section.{x}] in the scene (sections: {', '.join(sections)})")
        return [sections[x] for x in v]
    return [sec] * len(mids)


def beam_geometry(ctx, bt, where, ename, einfo, index):
    """The centreline and section frame of a beam: straight (start, end), an arc
    (start, arc_center, arc_axis, arc_angle) or a spline through points (path)."""
    arc_keys = [k for k in ("arc_center", "arc_axis", "arc_angle") if k in bt]
    curved = arc_keys + (["path"] if "path" in bt else [])
    if curved and not einfo["curved"]:
        ok = ", ".join(sorted(e for e, v in index["elements"].items() if v["curved"]))
        ctx.fail(f"{where}.{curved[0]}", f"element {ename} supports straight beams only; curved beams need {ok}")
    if "path" in bt:
        for k in ["start", "end"] + arc_keys:
            if k in bt:
                ctx.fail(f"{where}.{k}", "give either path (a centreline through points) or start with end or an arc")
        return path_geometry(ctx, bt, where)
    start = get_vec3(ctx, bt, "start", where, bound=1e9)
    if arc_keys:
        if "end" in bt:
            ctx.fail(f"{where}.end", "give either end (straight beam) or arc_center, arc_axis, arc_angle")
        return arc_geometry(ctx, bt, where, start)
    end = get_vec3(ctx, bt, "end", where, bound=1e9)
    return line_geometry(ctx, bt, where, start, end)


def layer_modulus(index, materials, mname, sec):
    """Small-strain Young's modulus of a layer's material (1 where the law states
    none: the layers then weigh by thickness)."""
    es = small_strain(index, materials[mname][0], materials[mname][2](sec))
    return es[0] if es else 1.0


def layer_pair(ctx, where, index, pairs, ename, integ, materials, mname):
    """The index in pairs of the kernel of a layer of material mname."""
    law = materials[mname][0]
    if index["materials"][law]["kind"] != "continuum":
        ctx.fail(f"{where}.layers", f"layer material {mname!r} has law {law!r}; a layer needs a continuum law")
    pair = f"{ename}_{law}_{integ}"
    if not any(p["element"] == ename and p["material"] == law and p["integration"] == integ for p in index["pairs"]):
        ctx.fail(f"{where}.layers", f"no generated kernel for element {ename!r} x law {law!r} x integration {integ!r}")
    if pair not in pairs:
        pairs.append(pair)
    return pairs.index(pair)


def mesh_beams(ctx, doc, beams_doc, index, materials, mats_doc, sections, log):
    """Every [[beam]]: validated, meshed, numbered.  Returns a Mesh."""
    m = Mesh()
    beams, warnings, nodes, dof_of_node, q0 = m.beams, m.warnings, m.nodes, m.dof_of_node, m.q0
    elements, pairs, geoms, mats_used, geom_index = m.elements, m.pairs, m.geoms, m.mats_used, m.geom_index
    ndof = 0
    n_total = sum(bt["elements"] for bt in beams_doc if isinstance(bt.get("elements"), int))
    t_progress = [time.monotonic(), 0]
    for bi, bt in enumerate(beams_doc):
        where = f"beam[{bi}]"
        bname = get_name(ctx, bt, "name", where) if isinstance(bt.get("name"), str) else None
        if bname is not None:
            where = f"beam.{bname}"
        check_keys(ctx, bt, set(K.BEAM), where)
        bname = get_name(ctx, bt, "name", where)
        if bname in beams:
            ctx.fail(f"{where}.name", f"duplicate beam name {bname!r}")
        ename = get_str(ctx, bt, "element", where, choices=sorted(index["elements"]))
        einfo = index["elements"][ename]
        mname = get_str(ctx, bt, "material", where)
        if mname not in materials:
            ctx.fail(f"{where}.material", f"no [material.{mname}] in the scene (materials: {', '.join(materials) or 'none'})")
        secname = get_str(ctx, bt, "section", where)
        if secname not in sections:
            ctx.fail(f"{where}.section", f"no [section.{secname}] in the scene (sections: {', '.join(sections) or 'none'})")
        integ = get_str(ctx, bt, "integration", where, default=einfo["default_integration"],
                        choices=sorted(einfo["integrations"]))
        law = materials[mname][0]
        mkind = index["materials"][law]["kind"]
        if mkind != einfo["material_kind"]:
            need = ("law = \"resultant\" (E, nu or the six stiffnesses)" if einfo["material_kind"] == "resultant"
                    else "a continuum law (" + ", ".join(k for k, v in sorted(index["materials"].items())
                                                         if v["kind"] == "continuum") + ")")
            ctx.fail(f"{where}.material", f"element {ename} needs {need}; material {mname!r} has law {law!r}")
        pair = f"{ename}_{law}_{integ}"
        if not any(p["element"] == ename and p["material"] == law and p["integration"] == integ
                   for p in index["pairs"]):
            ctx.fail(f"{where}.element", f"no generated kernel for element {ename!r} x law {law!r} "
                     f"x integration {integ!r}")
        sec = sections[secname]
        nel = get_int(ctx, bt, "elements", where, lo=1, hi=MAX_ELEMENTS)
        geo = beam_geometry(ctx, bt, where, ename, einfo, index)
        length = geo.length
        lens = element_lengths(ctx, bt, where, nel, length)
        from gen.scene.joint_nodes import split_at_joints
        lens, added = split_at_joints(ctx, doc, bt, where, bname, lens, length)
        nel = len(lens)
        warnings.extend(added)
        starts = [0.0] + list(itertools.accumulate(lens))[:-1]
        esecs = element_sections(ctx, bt, where, sections, sec, [(s0 + l / 2) / length for s0, l in zip(starts, lens)])
        if pair not in pairs:
            pairs.append(pair)
        pidx = pairs.index(pair)
        tau = float(mats_doc[mname].get("kelvin_voigt", 0.0))
        if tau > 0 and einfo["kind"] != "continuum":
            ctx.fail(f"material.{mname}.kelvin_voigt", f"Kelvin-Voigt damping is offered by the ANCF continuum "
                     f"elements; for element {ename} use [dynamic] rayleigh_alpha / rayleigh_beta")
        layers = beam_layers(ctx, bt, where, materials, einfo, ename, mname)
        eigen = None if layers is None else layer_eigenstrains(ctx, bt, where)
        layer_pidx = [] if layers is None else [layer_pair(ctx, where, index, pairs, ename, integ, materials, ln)
                                                for ln, _ in layers]
        midx_of = {}

        def material_index(sec, mname=mname):
            """The model's material record of material mname (the beam's, or a
            layer's) with section sec (the resultant laws' stiffnesses depend on it)."""
            if (mname, sec) in midx_of:
                return midx_of[(mname, sec)]
            law = materials[mname][0]
            tau = float(mats_doc[mname].get("kelvin_voigt", 0.0))
            first = not any(k[0] == mname for k in midx_of)
            key = "section" if sec == esecs[0] else "sections"
            if einfo["section"] == "rectangle" and sec[0] != "rectangle":
                ctx.fail(f"{where}.{key}", f"element {ename} needs a rectangle section, found {sec[0]}")
            params = materials[mname][2](sec)
            if any(math.isnan(v) for v in params):
                params = partial_stiffnesses(ctx, f"material.{mname}", ename, einfo, law, params, index)
            if first:
                warnings.extend(w for w in beam_warnings(where, mname, law, params, materials[mname][1], sec, length,
                                                         index) if w not in warnings)
            if einfo["kind"] == "continuum" and first:
                warnings.extend(locking_warnings(where, ename, integ, law, params, index))
            if einfo["kind"] == "cable" and abs(params[4] - params[5]) > 1e-9 * max(params[4], params[5]):
                ctx.fail(f"{where}.{key}", f"element ancf_cable has no section orientation and needs equal "
                         f"bending stiffnesses, found EI1 = {params[4]:.6g}, EI2 = {params[5]:.6g}")
            visc = []
            if tau > 0:
                if index["materials"][law]["kind"] == "resultant":
                    visc = [tau * v for v in params]
                else:
                    E_, nu_ = small_strain(index, law, params)
                    visc = [tau * E_ * nu_ / ((1 + nu_) * (1 - 2 * nu_)), tau * E_ / (2 * (1 + nu_))]
            mkey = (tuple(params), materials[mname][1], tuple(visc), tuple(index["materials"][law]["params"]))
            if mkey not in mats_used:
                mats_used.append(mkey)
            midx_of[(mname, sec)] = mats_used.index(mkey)
            return midx_of[(mname, sec)]

        first_elem = len(elements)
        layer_records = []      # the layers above the first: after the beam's elements
        layer_elems = [[] for _ in range(nel)]
        enodes = einfo["nodes"]
        prev_end = None
        prev_p = None           # the last nodal quaternion: its neighbours keep its hemisphere
        node_ids_of_beam = {}
        for k in range(nel):
            if log and n_total > 100000 and k % 4096 == 0 and time.monotonic() - t_progress[0] > 2.0:
                t_progress[0] = time.monotonic()
                log(f"meshing: {t_progress[1] + k} of {n_total} elements")
            edofs = []
            end_node = None
            l = lens[k]
            for ni, nd in enumerate(enodes):
                xi = float(eval_fraction(nd["xi"]))
                fields = tuple((f, d) for f, d in nd["fields"])
                if xi == 0.0 and prev_end is not None:
                    gid = prev_end
                else:
                    X, t, d1, d2 = geo.at(starts[k] + xi * l)
                    gid = len(nodes)
                    nodes.append((X, t, d1, d2, fields))
                    dof_of_node.append(ndof)
                    for f, dim in fields:
                        val = reference_field(f, t, d1, d2, X)
                        if f == "p":    # p and -p are one rotation; interpolation needs one sign
                            if prev_p is not None and sum(u * v for u, v in zip(val, prev_p)) < 0.0:
                                val = [-v for v in val]
                            prev_p = val
                        q0.extend(val)
                    ndof += sum(d for _, d in fields)
                    node_ids_of_beam[_key(starts[k] + xi * l, length)] = gid
                if nodes[gid][4] != fields:
                    ctx.fail(f"{where}.element", "inconsistent node layout between elements")
                base = dof_of_node[gid]
                edofs.extend(range(base, base + sum(d for _, d in fields)))
                if xi == 1.0:
                    end_node = gid
            # element-internal unknowns (multipliers of constrained theories)
            nint = einfo.get("internal", 0)
            edofs.extend(range(ndof, ndof + nint))
            q0.extend([0.0] * nint)
            ndof += nint
            prev_end = end_node
            sec_k = esecs[k]
            shape_key = geo.shape_key if geo.shape_key is not None else geo.element_key(k)
            if layers is None:
                midx = material_index(sec_k)
                gkey = (pidx, l, sec_k, shape_key)
                # congruent elements share a table
                if gkey not in geom_index:
                    geom_index[gkey] = len(geoms)
                    geoms.append((pidx, len(elements), section_geometry(sec_k, l)))
                elements.append((pidx, geom_index[gkey], midx, edofs))
                continue
            bands = element_bands(ctx, where, layers, sec_k[2])
            axis = neutral_axis(bands, [layer_modulus(index, materials, ln, sec_k) for ln, _ in layers])
            for j, (band, (ln, _)) in enumerate(zip(bands, layers)):
                band = band + (axis, eigen[j])
                lp = layer_pidx[j]
                gkey = (lp, l, sec_k, shape_key, band)
                eidx = len(elements) if j == 0 else first_elem + nel + len(layer_records)   # the record's index
                if gkey not in geom_index:
                    geom_index[gkey] = len(geoms)
                    geoms.append((lp, eidx, section_geometry(sec_k, l, band)))
                rec = (lp, geom_index[gkey], material_index(sec_k, ln), edofs)
                if j == 0:
                    elements.append(rec)
                else:
                    layer_elems[k].append(len(layer_records))
                    layer_records.append(rec)
        base = len(elements)
        assert base == first_elem + nel
        layer_elems = [[base + i for i in le] for le in layer_elems]
        elements.extend(layer_records)
        t_progress[1] += nel
        beams[bname] = {"name": bname, "element": ename, "length": length, "nelem": nel,
                        "first_elem": first_elem, "geo": geo, "elem_lens": lens, "elem_start": starts,
                        "node_at": node_ids_of_beam,
                        "kind": einfo["kind"], "moments": einfo["moments"], "section": sec, "sections": esecs,
                        "section_frame": einfo["section_frame"], "section_line": einfo.get("section_line", False),
                        "layer_elems": layer_elems}

    m.ndof = ndof
    return m


# The resultant stiffnesses an element kind reads (by the law's parameter
# names); the others may be left out of its material.  The cable has no
# section orientation, shear or torsion: EA and one bending stiffness.
RESULTANT_USED = {"cable": ("EA", "EI1")}


def partial_stiffnesses(ctx, where, ename, einfo, law, params, index):
    """params of a resultant material given only some stiffnesses (NaN: left
    out), for element ename: refused when the element uses one left out;
    else the ones it does not use are set (EI2 = EI1, the rest 0: never read)."""
    names = index["materials"][law]["params"]
    used = RESULTANT_USED.get(einfo["kind"], tuple(names))
    missing = [n for n, v in zip(names, params) if math.isnan(v) and n in used]
    if missing:
        left = [n for n, v in zip(names, params) if math.isnan(v)]
        ctx.fail(where, f"element {ename} uses {', '.join(missing)} of law {law!r}: give "
                        f"{'it' if len(missing) == 1 else 'them'} (given without {', '.join(left)}; "
                        f"ancf_cable uses only {', '.join(RESULTANT_USED['cable'])})")
    out = [v if not math.isnan(v) else 0.0 for v in params]
    if "EI1" in names and "EI2" in names and math.isnan(params[names.index("EI2")]):
        out[names.index("EI2")] = out[names.index("EI1")]
    return out
