"""The C descriptors of runtime/bk_kernel.h, written by one emitter for every
element family.

An element family (continuum ANCF: gen/emit.py; cable: gen/emit_cable.py; rods: gen/emit_rod.py)
describes an element by an ElementDesc and its element x material pairs by
PairDescs; this module writes their static arrays and designated initializers,
the version guard every generated C file carries, and what out/kernels/index.json
says of an element (so that the index and the C descriptor come from the same
description).  No sympy here: a description is cheap to build.
"""
from dataclasses import dataclass, field
from fractions import Fraction

from gen import contract


@dataclass(frozen=True)
class Field:
    name: str                 # "r", "r_x", ..., "p", "lambda"
    dof: int                  # first element DOF
    dim: int                  # 3, 4 or 1
    node: int                 # node index, -1 for element-internal unknowns


@dataclass(frozen=True)
class ElementDesc:
    name: str
    title: str
    node_xi: tuple            # exact positions along the axis as strings: "0", "1/2", "1"
    ndof: int
    caps: tuple               # capability constants (bk_element_cap), e.g. ("BK_CAP_CURVED",)
    fields: tuple             # Field, in DOF order
    shape_dof: tuple          # first DOF of each position shape function's vector
    functions: dict = field(default_factory=dict)   # member -> C function name (None: NULL)

    @property
    def nnode(self):
        return len(self.node_xi)


@dataclass(frozen=True)
class PairDesc:
    element: str
    material: str
    integration: str
    ntab: int
    nqp: int
    ops_force: int
    ops_force_tangent: int
    functions: dict           # tabulate, energy, force, force_tangent, viscous*, invariants
    nvisc: int = 0
    green_strain_range: tuple = (0.0, 0.0)
    sample_xi: tuple = ()     # points of sections() along the axis (floats), () with no sections()
    sample_source: str = ""   # what the section resultants come from (sections.csv `source`)

    @property
    def symbol(self):
        return f"bk_pair_{self.element}_{self.material}_{self.integration}"


ELEMENT_FUNCTIONS = ("reference", "shape", "mass", "volume", "frame", "section_frame", "section_line", "moment",
                     "rotary")
PAIR_FUNCTIONS = ("tabulate", "energy", "force", "force_tangent", "force_lanes", "force_tangent_lanes",
                  "viscous_force", "viscous", "viscous_force_lanes", "viscous_lanes", "invariants", "sections")


def version_guard():
    """Lines after a generated C file's includes: it compiles only against the
    header version it was generated for."""
    v = contract.version()
    return ['#include "bk_kernel.h"',
            f"#if !defined(BK_KERNEL_VERSION) || BK_KERNEL_VERSION != {v}",
            f'#error "generated for runtime/bk_kernel.h version {v}: regenerate out/kernels with ./build.sh gen"',
            "#endif"]


def _c_str(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _c_double(x):
    return repr(float(x))


def _array(ctype, name, items):
    return f"static const {ctype} {name}[{len(items)}] = {{{', '.join(items)}}};"


def check_element(d):
    """Raises ValueError when a description breaks the contract."""
    caps = contract.capabilities()
    for c in d.caps:
        if c not in caps:
            raise ValueError(f"{d.name}: capability {c} is not in bk_kernel.h (enum bk_element_cap)")
    maxdof, maxshape = contract.max_sizes()
    if d.ndof > maxdof or len(d.shape_dof) > maxshape:
        raise ValueError(f"{d.name}: {d.ndof} DOFs / {len(d.shape_dof)} shape functions exceed "
                         f"BK_MAX_ELEMENT_DOF {maxdof} / BK_MAX_SHAPE {maxshape}")
    covered = sorted(k for f in d.fields for k in range(f.dof, f.dof + f.dim))
    if covered != list(range(d.ndof)):
        raise ValueError(f"{d.name}: the fields do not cover the {d.ndof} DOFs once each")
    for f in d.fields:
        contract.role_of(f.name)
    moments = [c for c in d.caps if c.startswith("BK_CAP_MOMENT_")]
    if bool(d.functions.get("moment")) != bool(moments):
        raise ValueError(f"{d.name}: a moment() function needs a BK_CAP_MOMENT_* capability and back")
    unknown = set(d.functions) - set(ELEMENT_FUNCTIONS)
    if unknown:
        raise ValueError(f"{d.name}: unknown descriptor functions {sorted(unknown)}")


def element_descriptor(d):
    """C lines: the element's static arrays and `const bk_element bk_element_<name>`."""
    check_element(d)
    n = len(d.fields)
    lines = [_array("double", "node_xi", [_c_double(Fraction(x)) for x in d.node_xi]),
             _array("bk_field_role", "field_role", [contract.role_of(f.name) for f in d.fields]),
             _array("char *const", "field_name", [_c_str(f.name) for f in d.fields]),
             _array("int", "field_dof", [str(f.dof) for f in d.fields]),
             _array("int", "field_dim", [str(f.dim) for f in d.fields]),
             _array("int", "shape_dof", [str(k) for k in d.shape_dof]), ""]
    members = [("name", _c_str(d.name)), ("title", _c_str(d.title)), ("nnode", str(d.nnode)),
               ("ndof", str(d.ndof)), ("node_xi", "node_xi"),
               ("caps", " | ".join(d.caps) if d.caps else "0"),
               ("nfield", str(n)), ("field_role", "field_role"), ("field_name", "field_name"),
               ("field_dof", "field_dof"), ("field_dim", "field_dim"),
               ("nshape", str(len(d.shape_dof))), ("shape_dof", "shape_dof")]
    members += [(k, d.functions[k]) for k in ELEMENT_FUNCTIONS if d.functions.get(k)]
    lines.append(f"const bk_element bk_element_{d.name} = {{")
    lines += [f"    .{k} = {v}," for k, v in members]
    lines += ["};", ""]
    return lines


def pair_descriptors(params, pairs):
    """C lines: the material's parameter names and `const bk_pair <symbol>` of each
    pair (one per integration) of an element x material file."""
    lines = [_array("char *const", "param_names", [_c_str(p) for p in params]), ""]
    for p in pairs:
        unknown = set(p.functions) - set(PAIR_FUNCTIONS)
        if unknown:
            raise ValueError(f"{p.symbol}: unknown descriptor functions {sorted(unknown)}")
        if any(bool(p.nvisc) != bool(p.functions.get(k)) for k in ("viscous_force", "viscous")):
            raise ValueError(f"{p.symbol}: nvisc, viscous_force() and viscous() go together")
        if bool(p.functions.get("viscous_force_lanes")) != bool(p.functions.get("viscous_lanes")):
            raise ValueError(f"{p.symbol}: viscous_force_lanes() and viscous_lanes() go together")
        members = [("element", f"&bk_element_{p.element}"), ("material", _c_str(p.material)),
                   ("integration", _c_str(p.integration)), ("nparam", str(len(params))),
                   ("param_names", "param_names"), ("ntab", str(p.ntab)), ("nqp", str(p.nqp)),
                   ("ops_force", f"{p.ops_force}L"), ("ops_force_tangent", f"{p.ops_force_tangent}L")]
        members += [(k, p.functions[k]) for k in ("tabulate", "energy", "force", "force_tangent")]
        members += [(k, p.functions[k]) for k in ("force_lanes", "force_tangent_lanes") if p.functions.get(k)]
        if p.nvisc:
            members += [("nvisc", str(p.nvisc))]
            members += [(k, p.functions[k]) for k in ("viscous_force", "viscous", "viscous_force_lanes",
                                                      "viscous_lanes") if p.functions.get(k)]
        if p.functions.get("invariants"):
            members.append(("invariants", p.functions["invariants"]))
        lo, hi = p.green_strain_range
        if lo or hi:
            members += [("green_strain_min", _c_double(lo)), ("green_strain_max", _c_double(hi))]
        if bool(p.sample_xi) != bool(p.functions.get("sections")):
            raise ValueError(f"{p.symbol}: sample_xi and sections() go together")
        if p.sample_xi:
            if "," in p.sample_source or not p.sample_source:
                raise ValueError(f"{p.symbol}: sample_source must be a label without commas")
            arr = f"sample_xi_{p.integration}"
            lines += [_array("double", arr, [_c_double(x) for x in p.sample_xi]), ""]
            members += [("nsample", str(len(p.sample_xi))), ("sample_xi", arr),
                        ("sample_source", _c_str(p.sample_source)), ("sections", p.functions["sections"])]
        lines.append(f"const bk_pair {p.symbol} = {{")
        lines += [f"    .{k} = {v}," for k, v in members]
        lines += ["};", ""]
    return lines


def index_entry(d):
    """What index.json says of the element's nodes and capabilities (the scene
    compiler reads it): nodes with their fields, section, moments, curved, and
    whether it has a section_frame() (follower loads) and a section_line()
    (tendons and chambers on rods)."""
    nodes = [{"xi": xi, "fields": [[f.name, f.dim] for f in d.fields if f.node == n]}
             for n, xi in enumerate(d.node_xi)]
    caps = set(d.caps)
    if caps >= {"BK_CAP_SECTION_RECTANGLE", "BK_CAP_SECTION_CIRCLE"}:
        section = "any"
    elif "BK_CAP_SECTION_RECTANGLE" in caps:
        section = "rectangle"
    else:
        raise ValueError(f"{d.name}: no section capability index.json can state")
    moments = next((m for c, m in (("BK_CAP_MOMENT_ANYWHERE", "anywhere"), ("BK_CAP_MOMENT_NODES", "nodes"),
                                   ("BK_CAP_MOMENT_NO_TORSION", "no_torsion")) if c in caps), "none")
    return {"nodes": nodes, "section": section, "moments": moments, "curved": "BK_CAP_CURVED" in caps,
            "internal": sum(f.dim for f in d.fields if f.node < 0),
            "section_frame": bool(d.functions.get("section_frame")),
            "section_line": bool(d.functions.get("section_line"))}
