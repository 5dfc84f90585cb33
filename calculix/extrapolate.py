"""Richardson extrapolation of a mesh study with a constant refinement ratio r.

Three meshes (values f1, f2, f3 from coarse to fine): the observed order is
p = ln((f2 - f1)/(f3 - f2)) / ln r, the extrapolated value
f = f3 + (f3 - f2)/(r^p - 1), and the error estimate 1.25 |f - f3| (Roache's grid
convergence index with safety factor 1.25: a band for the finest mesh's value; the
extrapolated value is within it when the order is asymptotic).  When the
differences change sign or grow the study is not in the asymptotic range: the
finest value is returned with the largest difference as its error and no order.
Two meshes need an assumed order p; the error estimate is then 3 |f - f2|
(safety factor 3).
"""
import math
from dataclasses import dataclass


@dataclass
class Extrapolation:
    values: list            # per mesh, coarse to fine
    ratio: float
    value: float            # extrapolated (or the finest value when not possible)
    order: float = None     # observed order (None: not observed)
    assumed_order: float = None
    error: float = 0.0      # estimated error (absolute)
    note: str = ""

    def as_dict(self):
        return {"values": self.values, "ratio": self.ratio, "value": self.value, "order": self.order,
                "assumed_order": self.assumed_order, "error": self.error, "note": self.note}


def richardson(values, ratio=2.0, order=None, tiny=0.0):
    """Extrapolation of 2 or 3 values from meshes refined by `ratio`.  `order` is the
    assumed order for two meshes (required then; ignored for three).  Differences at
    or below `tiny` (absolute) count as converged."""
    v = [float(x) for x in values]
    r = float(ratio)
    if r <= 1:
        raise ValueError(f"refinement ratio {ratio}: expected > 1")
    if len(v) == 2:
        if order is None or order <= 0:
            raise ValueError("two meshes need an assumed order > 0")
        d = v[1] - v[0]
        f = v[1] + d / (r**order - 1)
        return Extrapolation(v, r, f, None, order, 3.0 * abs(f - v[1]), "two meshes, assumed order")
    if len(v) != 3:
        raise ValueError(f"{len(v)} meshes: expected 2 or 3")
    e21, e32 = v[1] - v[0], v[2] - v[1]
    if abs(e32) <= tiny and abs(e21) <= tiny:
        return Extrapolation(v, r, v[2], None, None, max(abs(e21), abs(e32)), "converged to the given tolerance")
    if e21 * e32 <= 0 or abs(e32) >= abs(e21):
        return Extrapolation(v, r, v[2], None, None, max(abs(e21), abs(e32)),
                             "not in the asymptotic range (differences change sign or do not shrink)")
    p = math.log(e21 / e32) / math.log(r)
    f = v[2] + e32 / (r**p - 1)
    return Extrapolation(v, r, f, p, None, 1.25 * abs(f - v[2]), "three meshes, observed order")
