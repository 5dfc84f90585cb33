"""The scene compiler's one entry: a scene file (and --set overrides) to the
model as plain data, step by step: values and overrides (values.py, files.py),
materials and sections (materials.py), cost (cost.py), meshing and numbering
(mesh.py), joints (joints.py), loads (loads.py), options, initial velocities
and sensors (options.py); the model file (model_file.py)."""
import os

import gen.scene_keys as K
from gen.options_schema import OPTIONS
from gen.scene.amplitude import Amplitudes
from gen.scene.bodies import mesh_bodies
from gen.scene.buckling import buckling_options
from gen.scene import interactions
from gen.scene.cost import cost_check
from gen.scene.files import apply_overrides, blame_set, load_index, read_toml
from gen.scene.frame import rotating_frame
from gen.scene.joints import constraints
from gen.scene.loads import loads
from gen.scene.materials import material_params, sections as parse_sections
from gen.scene.mesh import mesh_beams
from gen.scene.model_file import _f
from gen.scene.options import initial_velocities, options, sensors
from gen.scene.point_masses import point_masses
from gen.scene.rigid_modes import check_static
from gen.scene.values import NAME_RE, Ctx, SceneError, check_keys, get_array_of_tables, get_name, get_str, get_table

ANALYSES = next(o.choices for o in OPTIONS if o.name == "scene.analysis")
PLANNED_ANALYSES = ()


def build(path, sets=(), name=None, log=None, out_dir=None, doc=None, base=None):
    """Validate the scene and return the model as a dict of plain data (see
    _build); a message about a value a --set gave names the --set."""
    touched = []
    try:
        return _build(path, sets, name, log, out_dir, doc, base, touched)
    except SceneError as e:
        if not touched:
            raise
        msg = blame_set(str(e), path, touched)
        if msg == str(e):
            raise
        raise SceneError(msg) from None


def _build(path, sets, name, log, out_dir, doc, base, touched):
    """Validate the scene and return the model as a dict of plain data.  log: a
    function taking a line (cost estimates and meshing progress of large
    models); out_dir: where the results will go (disk space check); doc: the
    scene as parsed TOML (a dict, copied; the Python API), else read from path
    (which names the scene in messages either way); base: the directory of
    relative data paths (gen/scene/values.py Ctx)."""
    ctx = Ctx(path, base)
    if doc is not None:
        import copy                      # (only here: 2 ms of a scene run's imports)
        doc = copy.deepcopy(doc)
    else:
        doc = read_toml(path)
    if sets:
        apply_overrides(doc, sets, path, touched)
    index = load_index()
    check_keys(ctx, doc, set(K.TOP) | interactions.tables(), "(top level)")
    scene = get_table(ctx, doc, "scene")
    check_keys(ctx, scene, set(K.SCENE), "scene")
    analysis = get_str(ctx, scene, "analysis", "scene", default="static",
                       choices=ANALYSES + PLANNED_ANALYSES)
    if analysis not in ANALYSES:
        ctx.fail("scene.analysis", f"{analysis!r} analysis is not implemented yet; expected static")
    if "description" in scene:
        get_str(ctx, scene, "description", "scene")
    sname = name or (get_name(ctx, scene, "name", "scene") if "name" in scene else os.path.splitext(os.path.basename(str(path)))[0])
    if not NAME_RE.match(sname):
        ctx.fail("scene.name", f"scene name {sname!r} must be letters, digits, '_', '.', '-'")

    mats_doc = get_table(ctx, doc, "material")
    materials = {}
    for mname, mt in mats_doc.items():
        if not NAME_RE.match(mname):
            ctx.fail(f"material.{mname}", "material names are letters, digits, '_', '.', '-'")
        check_keys(ctx, mt, set(mt) if isinstance(mt, dict) else set(), f"material.{mname}")
        materials[mname] = material_params(ctx, mname, mt, index)
    sections = parse_sections(ctx, doc)

    beams_doc = get_array_of_tables(ctx, doc, "beam")
    if not beams_doc and not get_array_of_tables(ctx, doc, "body"):
        ctx.fail("beam", "missing; expected at least one [[beam]] or [[body]]")
    cost_check(ctx, doc, index, analysis, beams_doc, out_dir, log)
    mesh = mesh_beams(ctx, doc, beams_doc, index, materials, mats_doc, sections, log)
    mesh_bodies(ctx, doc, mesh, index)
    amps = Amplitudes(ctx, doc)
    rows = constraints(ctx, doc, mesh, amps, analysis)    # none is allowed: the solver reports the singular tangent
    buckling = buckling_options(ctx, doc, analysis)   # (before the loads: gives them their amplitudes)
    forces, moments, gravity, dloads, tendons = loads(ctx, doc, mesh.beams, amps, mesh.bodies)
    stat, dyn, modal, output = options(ctx, doc, analysis)
    modal = buckling or modal               # the model file's modal record carries the buckling options
    qd0 = initial_velocities(ctx, doc, mesh)
    load_types = [lt.get("type") for lt in get_array_of_tables(ctx, doc, "load")]
    follower = [i for i, lt in enumerate(get_array_of_tables(ctx, doc, "load")) if lt.get("follower") is True]
    if follower and analysis == "static" and stat["stability"]:
        mesh.warnings.append(f"load[{follower[0]}]: follower loads are not conservative: the stability check "
                             "counts the eigenvalues of the symmetric part of the tangent (flutter is not detected)")
    stiff = [i for i, t in enumerate(load_types) if t in ("moment", "tendon", "chamber") or i in follower]
    if stiff and analysis == "modal" and modal["about"] == "static":
        mesh.warnings.append(f"load[{stiff[0]}]: the modal analysis about the static state takes the load "
                             "stiffness of moments, follower loads, tendons and chambers symmetrized: their "
                             "non-symmetric part (non-conservative; flutter) is left out")
    length_scale = max([b["length"] for b in mesh.beams.values()] +
                       [max(1e-3, b_["geom_edge"], max(abs(x) for x in b_["X"])) for b_ in mesh.bodies.values()])
    scene_parts = interactions.Scene(mesh.beams, mesh.bodies, length_scale, amps, analysis, stat, rows)
    inter = interactions.records(ctx, doc, scene_parts)
    rotating_frame(ctx, doc, dyn, rows, inter, analysis)
    check_static(ctx, mesh, rows, analysis, any(it.holds for it, _ in inter), stat)
    groups = joined_groups(doc, mesh.beams)
    return {
        "name": sname, "analysis": analysis, "ndof": mesh.ndof, "q0": mesh.q0, "length_scale": length_scale,
        "records": [(it.record, it.lines(data, _f)) for it, data in inter],
        "pairs": mesh.pairs, "mats": mesh.mats_used, "geoms": mesh.geoms, "elements": mesh.elements,
        "fixed": sorted(rows.fixed), "lincons": rows.lincons, "nlcons": rows.nlcons, "forces": forces, "moments": moments,
        "gravity": gravity, "sensors": sensors(ctx, doc, mesh.beams, mesh.bodies), "static": stat, "beams": mesh.beams,
        "dynamic": dyn, "modal": modal, "qd0": qd0, **output, "warnings": mesh.warnings,
        "amplitudes": amps.rows, "dloads": dloads, "tendons": tendons, "reactions": rows.reactions,
        "inputs": list(ctx.inputs), "point_masses": point_masses(ctx, doc, mesh.beams, mesh.bodies),
        "sections": [(b["name"], e, b["elem_start"][k], b["elem_start"][k] + b["elem_lens"][k],
                      b["sections"][k][2] / 2, groups[b["name"]])
                     for b in mesh.beams.values() for k in range(b["nelem"])
                     for e in [b["first_elem"] + k] + b["layer_elems"][k]],
    }


def joined_groups(doc, beams):
    """A number per beam, the same for beams joined by a [[constraint]] (its a and b
    points on two beams, transitively): the links of one mechanism, whose
    overlaps near their joints the output's overlap check does not report
    (runtime/output/overlap.c)."""
    group = {n: k for k, n in enumerate(beams)}
    names = list(beams)
    for ct in doc.get("constraint", []) if isinstance(doc.get("constraint"), list) else []:
        ends = [str(ct.get(k, "")).split(":")[0] for k in ("a", "b") if isinstance(ct, dict)]
        ends = [n for n in ends if n in beams]
        if len(ends) == 2 and group[ends[0]] != group[ends[1]]:
            old, new = group[ends[1]], group[ends[0]]
            for n in names:
                if group[n] == old:
                    group[n] = new
    return group
