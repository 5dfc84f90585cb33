"""Linear buckling analysis (scene.analysis = "buckling"): the [buckling]
options and the split of the loads into the loads the critical factors scale
and the preloads (load key `preload = true`), held at their full value.

The C solver (runtime/buckling.c) sees the split through amplitudes: with
preloads, each preload ramps to its value over load factors 0 ... 1 and stays
there, each scaled load is zero up to 1 and reaches its value at 2 (both
linear on [1, 2]); the static solve to load factor 1 gives the preloaded
state, the loads at 1 and 2 the scaled loads.  Without preloads the loads keep
the default (the load factor).  The model file carries the options in the
modal record: modes, and about = static for the preloaded state (the keys:
gen/options_schema.py)."""
import gen.scene_keys as K
from gen import options_schema as S
from gen.scene.values import check_keys, get_array_of_tables, get_bool, get_int, get_table

PRELOAD = {"type": "table", "points": [[0.0, 0.0], [1.0, 1.0]]}
SCALED = {"type": "table", "points": [[1.0, 0.0], [2.0, 1.0]]}


def buckling_options(ctx, doc, analysis):
    """Checks [buckling] and the loads' `preload` keys; for a buckling analysis
    gives the loads their amplitudes (in doc, before the loads are read) and
    returns the modal record {modes, about}, else None."""
    bt = get_table(ctx, doc, "buckling")
    check_keys(ctx, bt, set(K.BUCKLING), "buckling")
    o = next(o for o in S.table_options("buckling") if o.key == "modes")
    modes = get_int(ctx, bt, "modes", "buckling", default=o.default, lo=o.lo, hi=o.hi)
    loads = get_array_of_tables(ctx, doc, "load")
    pre = [get_bool(ctx, lt, "preload", f"load[{i}]", False) if isinstance(lt, dict) else False
           for i, lt in enumerate(loads)]
    if analysis != "buckling":
        if any(pre):
            ctx.fail(f"load[{pre.index(True)}].preload", 'expected only with scene.analysis = "buckling"')
        return None
    if all(pre):
        ctx.fail("scene.analysis", '"buckling" needs a load to scale: at least one [[load]] without '
                                   "preload = true (the critical load factors multiply those loads)")
    for i, lt in enumerate(loads):
        if "amplitude" in lt:
            ctx.fail(f"load[{i}].amplitude", 'expected none with scene.analysis = "buckling" (the load '
                                             "factor scales the loads linearly)")
        if any(pre):
            lt["amplitude"] = dict(PRELOAD if pre[i] else SCALED)
    return {"modes": modes, "about": "static" if any(pre) else "reference"}
