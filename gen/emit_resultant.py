"""What the cable and rod emitters (gen/emit_cable.py, gen/emit_rod.py) share:
each family's generator input files, the geometry symbols, field descriptors,
the line integrals of mass and volume and the descriptor of a family's one pair."""
from pathlib import Path

import sympy as sp

from gen import contract
from gen.descriptor import Field, PairDesc
from gen.element import geom_symbol
from gen.emit_rod_shared import SHARED_FILES
from gen.program import Program, lower

FAMILY_FILES = {"rod": SHARED_FILES + ("emit_resultant.py", "emit_rod.py"),
                "cable": ("cable.py", "emit_resultant.py", "emit_cable.py")}
GEN_DIR = Path(__file__).resolve().parent


def family_paths(elem):
    return [GEN_DIR / f for f in FAMILY_FILES[elem.kind]]


def _geom():
    """{slot name: symbol geom[BK_GEOM_<slot>]}."""
    return {k: geom_symbol(k) for k in contract.geom_slots()}


def _fields(elem, per_node):
    """Field descriptors from elem.fields() [(name, dof, dim)]: the first
    per_node * nnode are nodal, the rest element-internal."""
    return tuple(Field(n, d, k, i // per_node if i < per_node * elem.nnode else -1)
                 for i, (n, d, k) in enumerate(elem.fields()))


def _line_integrals(N, xi, l, A):
    """mass and volume programs for position shape functions N(xi) on a line of
    length l with cross-section area A."""
    n = len(N)
    mass, vol = Program(), Program()
    for a in range(n):
        for b in range(a, n):
            e = sp.factor(A * l * sp.integrate(sp.expand(N[a] * N[b]), (xi, 0, 1)))
            mass.output(f"m[{a * n + b}]", e, op="=")
            if b != a:
                mass.output(f"m[{b * n + a}]", e, op="=")
        vol.output(f"v[{a}]", sp.factor(A * l * sp.integrate(N[a], (xi, 0, 1))), op="=")
    return lower(mass, ()), lower(vol, ())


def _full_pair(elem, mat, ntab, nqp, ops):
    """The one pair ("full" integration) of a cable or rod element file."""
    name = f"{elem.name}_{mat.NAME}"
    return PairDesc(element=elem.name, material=mat.NAME, integration="full", ntab=ntab, nqp=nqp,
                    ops_force=ops["force"].total(), ops_force_tangent=ops["tangent"].total(),
                    functions={"tabulate": f"{elem.name}_full_tabulate", "energy": f"{name}_full_energy",
                               "force": f"{name}_full_force", "force_tangent": f"{name}_full_force_tangent"})
