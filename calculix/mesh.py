"""Structured C3D20R mesh of a straight rectangular beam, in the beam's global frame.

nx elements along the axis t, ny across along d1 (width b), nz across along d2
(height h).  Nodes live on the quadratic lattice (I, J, K), 0 <= I <= 2 nx,
0 <= J <= 2 ny, 0 <= K <= 2 nz, where at most one index is odd (20-node
serendipity bricks have no face or body centre nodes).  The node of (I, J, K) is
at start + X[I] L t + (Y[J] - 1/2) b d1 + (Z[K] - 1/2) h d2, where X, Y, Z are
the lattice fractions of the three directions (`Spacing.fractions`): even
entries are the element corners phi(i/n) of a fixed mapping phi of [0, 1],
odd entries the midpoints of their neighbours, so every element is a
rectangular box with straight edges and mid-side nodes at the middle.

Grading (`Spacing`) keeps a mesh family self-similar: the mapping phi is fixed
and only the element count n changes, so doubling n puts a node between every
two nodes of the coarser mesh (the coarse nodes are kept) and every element is
halved in every direction in the limit; a graded family refined by 2 is as
suitable for Richardson extrapolation as a uniform one.

  uniform        phi(x) = x
  geometric R    phi(x) = (R^x - 1)/(R - 1): neighbouring elements grow by the
                 constant factor R^(1/n); the largest element is R^((n-1)/n)
                 times the smallest (R in the limit), for every n
  power B        phi(x) = x^B: elements near 0 shrink like n^-B (B >= 1), for
                 singularities
  power B F      phi(x) = c x^B on the first fraction F of the elements and its
                 tangent line beyond (uniform elements, c fixed by phi(1) = 1): the
                 graded zone near 0 without the large elements of x^B at 1

One-sided mappings put the small elements at fraction 0; two-sided ones (the
section directions, and the axis of a beam clamped at both ends) are symmetric,
with the small elements at both faces: phi2(x) = phi(2x)/2 for x <= 1/2.  The
axial mapping is mirrored when the clamp is at the end of the beam.

The section point (y, z) at arc length s is a node when s/L, y/b + 1/2 and
z/h + 1/2 are lattice fractions with at most one odd index: the centroid of a
section is a node when ny and nz are not both odd and the section mappings are
two-sided or uniform.
"""
import math
from dataclasses import dataclass

# C3D20 node order (CalculiX / Abaqus): lattice offsets of the 20 nodes of an element.
# (t, d1, d2) is right-handed, so this order has a positive Jacobian.
C3D20_OFFSETS = (
    (0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2),
    (1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
    (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1),
)
# 8-node face: a uniform traction on a face of area A gives the consistent nodal
# forces -A/12 at the corners and A/3 at the mid-side nodes (they add up to A).
QUAD8_WEIGHTS = (((0, 0), -1 / 12), ((2, 0), -1 / 12), ((2, 2), -1 / 12), ((0, 2), -1 / 12),
                 ((1, 0), 1 / 3), ((2, 1), 1 / 3), ((1, 2), 1 / 3), ((0, 1), 1 / 3))

KINDS = ("uniform", "geometric", "power")


@dataclass(frozen=True)
class Spacing:
    """Element spacing of one direction: a fixed mapping of [0, 1] (see the module text)."""
    kind: str = "uniform"
    value: float = 1.0            # geometric: limit ratio largest/smallest element; power: exponent
    two_sided: bool = False       # small elements at both ends (symmetric) instead of at 0 only
    mirror: bool = False          # one-sided with the small elements at 1
    zone: float = 1.0             # power: fraction of the elements in the graded zone (uniform beyond)

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"spacing {self.kind!r}: expected one of {', '.join(KINDS)}")
        if self.kind == "geometric" and not (math.isfinite(self.value) and self.value >= 1.0):
            raise ValueError(f"geometric spacing: expected a ratio >= 1, found {self.value!r}")
        if self.kind == "power" and not (math.isfinite(self.value) and self.value >= 1.0):
            raise ValueError(f"power spacing: expected an exponent >= 1, found {self.value!r}")
        if not (0.0 < self.zone <= 1.0) or (self.kind != "power" and self.zone != 1.0):
            raise ValueError(f"spacing zone {self.zone!r}: expected a fraction in (0, 1], for power spacing only")

    @property
    def graded(self):
        return not (self.kind == "uniform" or self.value == 1.0)

    def _phi(self, x):
        """One-sided mapping, small elements at 0."""
        if x >= 1.0:
            return 1.0
        if self.kind == "geometric" and self.value != 1.0:
            R = self.value
            return math.expm1(x * math.log(R)) / (R - 1.0)
        if self.kind == "power":
            B, F = self.value, self.zone
            c = 1.0 / (F**B + B * F ** (B - 1) * (1.0 - F))
            return c * x**B if x <= F else c * (F**B + B * F ** (B - 1) * (x - F))
        return x

    def corner(self, i, n):
        """Fraction of element corner i of n (exact 0 and 1 at the ends)."""
        if i <= 0:
            return 0.0
        if i >= n:
            return 1.0
        x = i / n
        if not self.graded:
            return x
        if self.two_sided:
            return 0.5 * self._phi(2 * x) if 2 * i <= n else 1.0 - 0.5 * self._phi(2 * (1 - x))
        if self.mirror:
            return 1.0 - self._phi(1 - x)
        return self._phi(x)

    def fractions(self, n):
        """2n + 1 lattice fractions: corners at even indices, midpoints at odd."""
        c = [self.corner(i, n) for i in range(n + 1)]
        out = []
        for i in range(n):
            out += [c[i], 0.5 * (c[i] + c[i + 1])]
        return out + [1.0]

    def label(self):
        if not self.graded:
            return "uniform"
        return (f"{self.kind}:{self.value:g}" + (f":{self.zone:g}" if self.zone != 1.0 else "")
                + (" both ends" if self.two_sided else " at 1" if self.mirror else ""))

    def as_dict(self):
        return {"kind": self.kind, "value": self.value, "zone": self.zone, "two_sided": self.two_sided,
                "mirror": self.mirror}

    def spec(self):
        return f"{self.kind}:{self.value:g}" + (f":{self.zone:g}" if self.zone != 1.0 else "")


UNIFORM = Spacing()


@dataclass(frozen=True)
class Grading:
    """Spacing of the axis (x, toward the clamped end(s)) and of the two section
    directions (y along b, z along h, toward both faces)."""
    x: Spacing = UNIFORM
    y: Spacing = UNIFORM
    z: Spacing = UNIFORM

    @property
    def graded(self):
        return self.x.graded or self.y.graded or self.z.graded

    def spec(self):
        """The text parse_grading reads back ('' when uniform)."""
        return ",".join(f"{d}={s.spec()}" for d, s in (("x", self.x), ("y", self.y), ("z", self.z)) if s.graded)

    def as_dict(self):
        return {"x": self.x.as_dict(), "y": self.y.as_dict(), "z": self.z.as_dict()}


def parse_grading(text):
    """'x=power:3:0.25,y=geometric:3,z=power:2' (any subset; '' or 'uniform': none)
    -> Grading with one-sided x (oriented toward the clamp later, `oriented`) and
    two-sided y, z."""
    text = (text or "").strip()
    if text in ("", "uniform"):
        return Grading()
    got = {}
    for item in text.split(","):
        d, sep, rest = item.strip().partition("=")
        kind, sep2, val = rest.partition(":")
        val, _, zone = val.partition(":")
        if d not in ("x", "y", "z") or not sep or d in got:
            raise ValueError(f"grading {text!r}: expected DIR=KIND:VALUE items (DIR x, y or z, each once), "
                             f"e.g. x=geometric:8,z=geometric:3")
        if kind == "uniform" and not sep2:
            got[d] = UNIFORM
            continue
        try:
            v, z = float(val), float(zone or 1.0)
        except ValueError:
            raise ValueError(f"grading {text!r}: {d}: expected KIND:VALUE[:ZONE] with KIND one of {', '.join(KINDS)} "
                             f"and numbers, found {rest!r}") from None
        got[d] = Spacing(kind, v, two_sided=(d != "x"), zone=z)
    return Grading(got.get("x", UNIFORM), got.get("y", UNIFORM), got.get("z", UNIFORM))


def oriented(grading, clamp_sides):
    """The grading with the axial spacing biased toward the clamped end(s)."""
    sx = grading.x
    if not sx.graded:
        return grading
    sides = set(clamp_sides)
    if sides == {"start", "end"}:
        sx = Spacing(sx.kind, sx.value, two_sided=True, zone=sx.zone)
    elif sides == {"end"}:
        sx = Spacing(sx.kind, sx.value, mirror=True, zone=sx.zone)
    else:
        sx = Spacing(sx.kind, sx.value, zone=sx.zone)
    return Grading(sx, grading.y, grading.z)


@dataclass
class Mesh:
    nx: int
    ny: int
    nz: int
    nodes: dict          # lattice (I, J, K) -> node id (1-based)
    coords: list         # node id - 1 -> [x, y, z]
    elements: list       # element id - 1 -> 20 node ids
    fx: list = None      # lattice fractions along the axis (2 nx + 1)
    fy: list = None      # ... along b (2 ny + 1)
    fz: list = None      # ... along h (2 nz + 1)
    grading: Grading = Grading()

    def __post_init__(self):
        self.fx = self.fx or UNIFORM.fractions(self.nx)
        self.fy = self.fy or UNIFORM.fractions(self.ny)
        self.fz = self.fz or UNIFORM.fractions(self.nz)

    @property
    def label(self):
        return f"{self.nx}x{self.ny}x{self.nz}" + (f" ({self.grading.spec()})" if self.grading.graded else "")

    def face(self, side):
        """[(node id, J, K, y/b, z/h, weight)] of the start (I = 0) or end (I = 2 nx)
        face: lattice indices, section coordinates as fractions of b and h about the
        centroid, and the consistent weights of a uniform traction (fractions of the
        face area)."""
        I = 0 if side == "start" else 2 * self.nx
        w = {}
        for j in range(self.ny):
            for k in range(self.nz):
                ae = (self.fy[2 * j + 2] - self.fy[2 * j]) * (self.fz[2 * k + 2] - self.fz[2 * k])
                for (dj, dk), f in QUAD8_WEIGHTS:
                    key = (2 * j + dj, 2 * k + dk)
                    w[key] = w.get(key, 0.0) + f * ae
        rows = [(self.nodes[(I, J, K)], J, K, self.fy[J] - 0.5, self.fz[K] - 0.5, wt) for (J, K), wt in w.items()]
        return sorted(rows)

    def node_at(self, s_frac, y_frac=0.0, z_frac=0.0):
        """Node id at the section point (y/b, z/h) of the section at s/L, or None."""
        key = []
        for f, fr in ((s_frac, self.fx), (y_frac + 0.5, self.fy), (z_frac + 0.5, self.fz)):
            i = min(range(len(fr)), key=lambda k: abs(fr[k] - f))
            if abs(fr[i] - f) > 1e-9:
                return None
            key.append(i)
        return self.nodes.get(tuple(key))


def build_mesh(prob, nx, ny, nz, grading=None):
    """C3D20R mesh of the beam of a Problem (calculix.scene); `grading` a Grading
    (its axial spacing is oriented toward the problem's clamps here)."""
    if min(nx, ny, nz) < 1:
        raise ValueError(f"mesh {nx}x{ny}x{nz}: every count must be >= 1")
    g = oriented(grading or Grading(), [side for side, _ in prob.clamps])
    fx, fy, fz = g.x.fractions(nx), g.y.fractions(ny), g.z.fractions(nz)
    nodes, coords = {}, []
    for I in range(2 * nx + 1):
        for J in range(2 * ny + 1):
            for K in range(2 * nz + 1):
                if (I & 1) + (J & 1) + (K & 1) > 1:
                    continue
                nodes[(I, J, K)] = len(coords) + 1
                coords.append(prob.point(fx[I] * prob.length, (fy[J] - 0.5) * prob.b, (fz[K] - 0.5) * prob.h))
    elements = []
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                elements.append([nodes[(2 * i + a, 2 * j + b, 2 * k + c)] for a, b, c in C3D20_OFFSETS])
    return Mesh(nx, ny, nz, nodes, coords, elements, fx, fy, fz, g)
