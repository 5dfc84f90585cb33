"""Layered sections of continuum beams (beam.layers): the layers through the
height, checked, and each element's bands of its section.

A layered element is one element record per layer on the same coordinates:
each layer's material and kernel pair, its table integrating the element's own
rule over its band z in [(lo - 1/2) h, (1/2 - hi) h] of the height (geom[]
slots BK_GEOM_BAND_LO, _HI of runtime/bk_kernel.h).  The energies add, so the
coupling of stretching and bending by an off-centre stiff layer, and every
nonlinearity, come from the continuum itself."""
from gen.scene.values import _typename, check_keys, get_number, get_str

LAYER_KEYS = ("material", "thickness", "eigenstrain")


def beam_layers(ctx, bt, where, materials, einfo, ename, default_material):
    """[(material name, thickness in m or None for the rest of the height)] from
    the -d2 face up, or None when the beam has one material."""
    if "layers" not in bt:
        return None
    v = bt["layers"]
    key = f"{where}.layers"
    if not isinstance(v, list) or not v or not all(isinstance(x, dict) for x in v):
        ctx.fail(key, "expected an array of inline tables {material = NAME, thickness = m} from the -d2 face "
                 f"up, found {_typename(v) if not isinstance(v, list) else repr(v)}")
    if einfo["kind"] != "continuum":
        ctx.fail(key, f"layered sections are integrated through the height by the continuum ANCF elements; "
                 f"element {ename} is a {einfo['kind']} element (use ancf3243, ancf3333 or ancf3363)")
    out, rest = [], 0
    for i, lt in enumerate(v):
        w = f"{key}[{i}]"
        check_keys(ctx, lt, set(LAYER_KEYS), w)
        mname = get_str(ctx, lt, "material", w, default=default_material)
        if mname not in materials:
            ctx.fail(f"{w}.material", f"no [material.{mname}] in the scene (materials: {', '.join(materials)})")
        t = get_number(ctx, lt, "thickness", w, positive=True) if "thickness" in lt else None
        rest += t is None
        out.append((mname, t))
    if rest > 1:
        ctx.fail(key, "at most one layer may leave out its thickness (it fills the rest of the height)")
    return out


def layer_eigenstrains(ctx, bt, where):
    """The free isotropic strain of each layer (`eigenstrain`, e.g. a thermal
    expansion alpha dT; 0 where not given): its stress-free state is stretched by
    1 + e in every direction (runtime/bk_kernel.h BK_GEOM_EIGENSTRAIN)."""
    out = []
    for i, lt in enumerate(bt["layers"]):
        w = f"{where}.layers[{i}]"
        e = get_number(ctx, lt, "eigenstrain", w, default=0.0) if "eigenstrain" in lt else 0.0
        if not -0.5 < e < 0.5:
            ctx.fail(f"{w}.eigenstrain", f"expected a strain between -0.5 and 0.5 (e.g. alpha dT), found {e:g}")
        out.append(float(e))
    return out


def neutral_axis(bands, moduli):
    """Height z / h (0: the middle) of the neutral axis of the layered section whose
    layers occupy bands [(lo, hi)] with small-strain Young's moduli moduli (the
    transformed section's centroid): where the centreline part of selective reduced
    integration evaluates every layer (runtime/bk_kernel.h BK_GEOM_BAND_AXIS)."""
    w = [E * (1.0 - lo - hi) for (lo, hi), E in zip(bands, moduli)]
    return sum(wk * ((lo + 1.0 - hi) / 2 - 0.5) for wk, (lo, hi) in zip(w, bands)) / sum(w)


def element_bands(ctx, where, layers, h):
    """[(lo, hi)] per layer of an element of height h: the fractions of h below and
    above its band.  Refuses layers thicker than the section."""
    fixed = sum(t for _, t in layers if t is not None)
    has_rest = any(t is None for _, t in layers)
    if has_rest and fixed >= h * (1.0 - 1e-9):
        ctx.fail(f"{where}.layers", f"the layers' thicknesses add up to {fixed:.6g} m, the section is "
                 f"{h:.6g} m high: nothing is left for the layer without a thickness")
    if not has_rest and abs(fixed - h) > 1e-9 * h:
        ctx.fail(f"{where}.layers", f"the layers' thicknesses add up to {fixed:.6g} m, the section is "
                 f"{h:.6g} m high (leave out one layer's thickness to fill the rest)")
    bands, below = [], 0.0
    for _, t in layers:
        share = (h - fixed) / h if t is None else t / h
        lo = below
        hi = max(0.0, 1.0 - lo - share)
        if lo + share >= 1.0 - 1e-12:     # the top layer: exactly up to the top face
            hi = 0.0
        bands.append((lo, hi))
        below = lo + share
    return bands
