"""The run's cost before meshing (gen/estimate.py) from the raw scene tables."""
import os

from gen import estimate as est_mod
from gen.scene.files import ROOT_DIR
from gen.scene.mesh import MAX_ELEMENTS
from gen.scene.options import DYNAMIC_FRAMES


def cost_check(ctx, doc, index, analysis, beams_doc, out_dir, log):
    """Memory, disk and time of the run estimated from the raw element counts
    (gen/estimate.py): refuse what cannot fit, say what is large."""
    beams = []
    for bi, bt in enumerate(beams_doc):
        name = bt.get("name") if isinstance(bt.get("name"), str) else f"[{bi}]"
        ename, nel = bt.get("element"), bt.get("elements")
        if isinstance(ename, str) and ename in index["elements"] and isinstance(nel, int) and not isinstance(nel, bool) \
                and 0 < nel <= MAX_ELEMENTS:        # beyond the limit the reader says so
            beams.append((f"beam.{name}", ename, nel))
    if not beams:
        return
    out = doc.get("output", {}) if isinstance(doc.get("output"), dict) else {}
    st = doc.get("static", {}) if isinstance(doc.get("static"), dict) else {}
    every = out.get("vtk_every", 1)
    every = every if isinstance(every, int) and not isinstance(every, bool) and every >= 0 else 1
    if every == 0:
        frames = 0
    elif analysis == "dynamic":
        frames = DYNAMIC_FRAMES + 1
    elif analysis == "modal":
        md = doc.get("modal", {}) if isinstance(doc.get("modal"), dict) else {}
        frames = (md.get("modes", 10) if isinstance(md.get("modes", 10), int) else 10) + 2
    else:
        ls = st.get("load_steps", 10)
        ls = ls if isinstance(ls, int) and not isinstance(ls, bool) and ls > 0 else 10
        frames = ls // every + 2
    e = est_mod.estimate(beams, index, frames)
    est_mod.check(e, beams, str(out_dir) if out_dir else os.path.join(ROOT_DIR, "out"), ctx.fail, log)
