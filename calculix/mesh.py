"""Structured C3D20R mesh of a straight rectangular beam, in the beam's global frame.

nx elements along the axis t, ny across along d1 (width b), nz across along d2
(height h).  Nodes live on the quadratic lattice (I, J, K), 0 <= I <= 2 nx,
0 <= J <= 2 ny, 0 <= K <= 2 nz, where at most one index is odd (20-node
serendipity bricks have no face or body centre nodes); the node of (I, J, K) is
at start + (I/2nx) L t + (J/2ny - 1/2) b d1 + (K/2nz - 1/2) h d2.  The section
point (y, z) at arc length s is a node when s/L 2nx, (y/b + 1/2) 2ny and
(z/h + 1/2) 2nz are integers with at most one odd: the centroid of a section is
a node unless ny and nz are both odd.
"""
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


@dataclass
class Mesh:
    nx: int
    ny: int
    nz: int
    nodes: dict          # lattice (I, J, K) -> node id (1-based)
    coords: list         # node id - 1 -> [x, y, z]
    elements: list       # element id - 1 -> 20 node ids

    @property
    def label(self):
        return f"{self.nx}x{self.ny}x{self.nz}"

    def face(self, side):
        """Node ids of the start (I = 0) or end (I = 2 nx) face with their section
        coordinates (y, z) and consistent weights (fractions of the face area)."""
        I = 0 if side == "start" else 2 * self.nx
        w = {}
        ae = 1.0 / (self.ny * self.nz)
        for j in range(self.ny):
            for k in range(self.nz):
                for (dj, dk), f in QUAD8_WEIGHTS:
                    key = (I, 2 * j + dj, 2 * k + dk)
                    w[key] = w.get(key, 0.0) + f * ae
        return [(self.nodes[key], key[1] / (2 * self.ny) - 0.5, key[2] / (2 * self.nz) - 0.5, wt)
                for key, wt in sorted(w.items(), key=lambda kv: self.nodes[kv[0]])]

    def node_at(self, s_frac, y_frac=0.0, z_frac=0.0):
        """Node id at the section point (y/b, z/h) of the section at s/L, or None."""
        I, J, K = (f * n for f, n in ((s_frac, 2 * self.nx), (y_frac + 0.5, 2 * self.ny), (z_frac + 0.5, 2 * self.nz)))
        key = tuple(round(v) for v in (I, J, K))
        if any(abs(v - r) > 1e-9 for v, r in zip((I, J, K), key)):
            return None
        return self.nodes.get(key)


def build_mesh(prob, nx, ny, nz):
    """C3D20R mesh of the beam of a Problem (calculix.scene)."""
    if min(nx, ny, nz) < 1:
        raise ValueError(f"mesh {nx}x{ny}x{nz}: every count must be >= 1")
    nodes, coords = {}, []
    for I in range(2 * nx + 1):
        for J in range(2 * ny + 1):
            for K in range(2 * nz + 1):
                if (I & 1) + (J & 1) + (K & 1) > 1:
                    continue
                nodes[(I, J, K)] = len(coords) + 1
                coords.append(prob.point(I / (2 * nx) * prob.length, (J / (2 * ny) - 0.5) * prob.b,
                                         (K / (2 * nz) - 0.5) * prob.h))
    elements = []
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                elements.append([nodes[(2 * i + a, 2 * j + b, 2 * k + c)] for a, b, c in C3D20_OFFSETS])
    return Mesh(nx, ny, nz, nodes, coords, elements)
