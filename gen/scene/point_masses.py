"""Point masses: [[point_mass]] tables, a mass (no rotary inertia) at a beam point,
between nodes or at one, as model-file records (runtime/model/point_mass_read.c):
its translational inertia m N^T N and its weight m g N^T on the element holding
the point, N the element's position shape functions there (the element's
consistent treatment of a material point)."""
import gen.scene_keys as K
from gen.scene.mesh import locate, parse_point
from gen.scene.values import check_keys, get_array_of_tables, get_number


def point_masses(ctx, doc, beams, bodies):
    """[(element, xi, mass)] of every [[point_mass]]."""
    out = []
    for i, pt in enumerate(get_array_of_tables(ctx, doc, "point_mass")):
        where = f"point_mass[{i}]"
        check_keys(ctx, pt, set(K.POINT_MASS), where)
        if "at" not in pt:
            ctx.fail(f"{where}.at", "missing; expected a beam point like 'arm:end' or 'arm:0.35'")
        if isinstance(pt["at"], str) and pt["at"] in bodies:
            ctx.fail(f"{where}.at", f"{pt['at']!r} is a rigid body: give its mass and inertia in its [[body]] table")
        beam, s = parse_point(ctx, pt["at"], f"{where}.at", beams)
        mass = get_number(ctx, pt, "mass", where, positive=True)
        e, xi = locate(beam, s)
        out.append((e, xi, mass))
    return out


def point_mass_records(pms, fmt):
    out = [f"point_masses {len(pms)}"]
    out += [f"point_mass {e} {fmt(xi)} {fmt(mass)}" for e, xi, mass in pms]
    return out
