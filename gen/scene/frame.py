"""The rotating frame of a dynamic run (`dynamic.frame`): the named
prescribed_rotation checked, and what the frame cannot carry refused with one
line (the runtime's side, which takes the axis and the angle from the
constraint's own rows: runtime/analysis/dyn_frame.c).

In the frame every coordinate is measured in axes turning with the hub, so a
load fixed in space, a support to the ground or a contact surface would turn
with it; only what is the same in any rotated axes is kept: the beams and
bodies, their joints to each other, tendons and chambers."""
from gen.scene.values import get_array_of_tables

_OBJECTIVE_LOADS = ("tendon", "chamber")


def rotating_frame(ctx, doc, dyn, rows, interactions, analysis):
    """Refuse a frame the runtime cannot turn."""
    name = dyn.get("frame", "none")
    if name == "none" or analysis != "dynamic":
        return
    cts = get_array_of_tables(ctx, doc, "constraint")
    found = [r for r in rows.reactions if r[9] == name]
    if not found:
        names = ", ".join(repr(r[9]) for r in rows.reactions if r[1] == "prescribed_rotation") or "none"
        ctx.fail("dynamic.frame", f"no [[constraint]] named {name!r}; expected the name of a prescribed_rotation "
                                  f"(the scene's: {names})")
    ci, ctype = found[0][0], found[0][1]
    if ctype != "prescribed_rotation" or "b" in cts[ci]:
        ctx.fail("dynamic.frame", f"constraint {name!r} is a {ctype}" + (" between two parts" if "b" in cts[ci]
                                                                          else "")
                 + "; expected a prescribed_rotation to the ground")
    for k, ct in enumerate(cts):
        if k != ci and ("b" not in ct or str(ct.get("type", "")).startswith("prescribed")):
            ctx.fail(f"constraint[{k}]", f"a {ct.get('type')} to the ground or with a drive is not supported with "
                                         f"dynamic.frame = {name!r} (in the rotating frame the ground turns); "
                                         "expected joints between parts only")
    for k, lt in enumerate(get_array_of_tables(ctx, doc, "load")):
        if lt.get("type") not in _OBJECTIVE_LOADS:
            ctx.fail(f"load[{k}]", f"a {lt.get('type')} load is not supported with dynamic.frame = {name!r} (a "
                                   "direction fixed in space turns in the rotating frame); expected only "
                                   + " and ".join(_OBJECTIVE_LOADS) + " loads")
    for it, _ in interactions:
        ctx.fail(f"{it.table}", f"not supported with dynamic.frame = {name!r} (the rotating frame carries only "
                                "the parts, their joints to each other, tendons and chambers)")
