"""C emission for rigid bodies (out/kernels/rigid_body.{h,c}: the element and its
one pair) and the joints (out/kernels/joints.{h,c}: one kind per joint type,
runtime/bk_joint.h) and the joint actuators' coordinate kernels (gen/actuator.py), from
gen/body.py."""
from pathlib import Path

from gen import actuator, body
from gen.c_functions import _function, section_frame_function
from gen.descriptor import ElementDesc, Field, PairDesc, element_descriptor, pair_descriptors, version_guard
from gen.program import Program, count_lowered, lower
from gen.provenance import BANNER, CORE_FILES, core_paths, input_hash

GEN_DIR = Path(__file__).resolve().parent
BODY_FILES = ("body.py", "actuator.py", "emit_body.py", "rod.py", "rod_inertia.py", "chain.py", "rod_frame.py",
              "rodmath.py", "loads.py")
UNITS = ("rigid_body", "joints")
NAME = "rigid_body"
MATERIAL = "rigid"
TITLE = "rigid body (centre of mass, quaternion)"
CAPS = ("BK_CAP_SECTION_RECTANGLE", "BK_CAP_MOMENT_ANYWHERE")
_D = "const double *restrict"
_W = "double *restrict"


def paths():
    return [GEN_DIR / f for f in BODY_FILES]


def describe():
    fields = (Field("r", 0, 3, 0), Field("p", 3, 4, 0))
    return ElementDesc(name=NAME, title=TITLE, node_xi=("1/2",), ndof=7, caps=CAPS, fields=fields,
                       shape_dof=(0,), functions={k: k for k in ("reference", "shape", "mass", "volume",
                                                                 "frame", "section_frame", "moment", "rotary")})


def _ops(low):
    pro, bod = count_lowered(low)
    bod += pro
    return bod.total()


def _header_lines(unit, h, doc):
    out = [f"/* {BANNER}", f" * {unit}: {doc}",
           f" * generator inputs: {', '.join('gen/' + f for f in BODY_FILES)} + gen core ({', '.join(CORE_FILES)})",
           f" * input hash: sha256:{h}", " *"]
    out += [" * " + x if x.strip() else " *" for x in (body.__doc__ or "").strip().splitlines()]
    return out + [" */"]


def _const(target_values):
    p = Program()
    for t, v in target_values:
        p.output(t, v, op="=")
    return lower(p, ())


def body_source():
    h = input_hash(paths() + core_paths())
    hdr = _header_lines(NAME, h, TITLE)
    htxt = "\n".join(hdr) + f"""
#ifndef BK_GEN_RIGID_BODY_H
#define BK_GEN_RIGID_BODY_H
#include "bk_kernel.h"

/* geom: BK_GEOM_A = mass M (kg); BK_GEOM_I1, _I2, _IP = principal moments of
 * inertia J1, J2, J3 (kg m^2) about e1, e2, e3; BK_GEOM_L = BK_GEOM_B = BK_GEOM_H =
 * the edge of the cube the body is drawn as.  The material density is 1 and
 * mat[0] = cg, the gauge penalty coefficient (J). */
extern const bk_element bk_element_{NAME};
extern const bk_pair bk_pair_{NAME}_{MATERIAL}_full;

#endif
"""
    fg = lambda s: f"geom[BK_GEOM_{s}]"
    c = [f"/* {BANNER} (see {NAME}.h) */", f'#include "{NAME}.h"'] + version_guard() + [""]
    c += ["static void shape(const double *restrict geom, double xi, double y, double z, double *restrict N)",
          "{", "    (void)geom; (void)xi; (void)y; (void)z;", "    N[0] = 1.0;", "}", "",
          f"static void mass({_D} geom, {_W} m)", "{", f"    m[0] = {fg('A')};", "}", "",
          f"static void volume({_D} geom, {_W} v)", "{", f"    v[0] = {fg('A')};", "}", "",
          f"static void reference({_D} geom, {_W} q0)", "{", "    (void)geom;",
          "    for (int i = 0; i < 7; ++i) q0[i] = i == 3 ? 1.0 : 0.0;", "}", ""]
    c += _function(f"static void frame({_D} geom, double xi, {_D} q, {_W} pos, {_W} d)",
                   lower(body.body_frame_program(), ()))
    c += section_frame_function(*(lower(pr, ()) for pr in body.body_section_frame_programs()))
    from gen.rod_frame import moment_node_program
    c += _function(f"static void moment_node({_D} p, {_D} M, {_W} Q, {_W} dQ)", lower(moment_node_program(), ()))
    c += [f"static void moment({_D} geom, double xi, {_D} q, {_D} M, {_W} Q, {_W} dQ)",
          "{", "    (void)geom; (void)xi;", "    double Qn[4], dQn[16];",
          "    for (int i = 0; i < 7; ++i) Q[i] = 0.0;", "    for (int i = 0; i < 49; ++i) dQ[i] = 0.0;",
          "    moment_node(q + 3, M, Qn, dQn);", "    for (int i = 0; i < 4; ++i) {", "        Q[3 + i] = Qn[i];",
          "        for (int j = 0; j < 4; ++j) dQ[7 * (3 + i) + 3 + j] = dQn[4 * i + j];", "    }", "}", ""]
    c += _function(f"static void rotary_node({_D} Jn, {_D} p, {_D} pd, {_D} pdd, {_W} f, {_W} Mq, "
                   f"{_W} Cq, {_W} Kq, {_W} T)", lower(body.body_rotary_program(), ()))
    c += [f"static void rotary({_D} geom, {_D} q, {_D} qd, {_D} qdd, {_W} f, {_W} Mq, {_W} Cq, {_W} Kq, {_W} T)",
          "{", f"    const double Jn[3] = {{{fg('I1')}, {fg('I2')}, {fg('IP')}}};",
          "    double fn[4], Mn[16], Cn[16], Kn[16];",
          "    for (int i = 0; i < 7; ++i) f[i] = 0.0;",
          "    for (int i = 0; i < 49; ++i) Mq[i] = Cq[i] = Kq[i] = 0.0;",
          "    rotary_node(Jn, q + 3, qd + 3, qdd + 3, fn, Mn, Cn, Kn, T);",
          "    for (int i = 0; i < 4; ++i) {", "        f[3 + i] = fn[i];",
          "        for (int j = 0; j < 4; ++j) {",
          "            Mq[7 * (3 + i) + 3 + j] = Mn[4 * i + j];",
          "            Cq[7 * (3 + i) + 3 + j] = Cn[4 * i + j];",
          "            Kq[7 * (3 + i) + 3 + j] = Kn[4 * i + j];", "        }", "    }", "}", ""]
    c += element_descriptor(describe())
    sym = f"{NAME}_{MATERIAL}_full"
    e_low, f_low, k_low = (lower(body.body_gauge_program(o), ()) for o in (0, 1, 2))
    c += [f"static void {sym}_tabulate({_D} geom, {_D} q0, {_W} tab)", "{", "    (void)geom; (void)q0;",
          "    tab[0] = 0.0;", "}", ""]
    c += _function(f"static double {sym}_energy({_D} q, {_D} tab, {_D} mat)", e_low,
                   ["(void)tab;", "double e;"])[:-2] + ["    return e;", "}", ""]
    c += _function(f"static void {sym}_force({_D} q, {_D} tab, {_D} mat, {_W} f)", f_low, ["(void)tab;"])
    c += _function(f"static void {sym}_force_tangent({_D} q, {_D} tab, {_D} mat, {_W} f, {_W} K)", k_low,
                   ["(void)tab;", f"{sym}_force(q, tab, mat, f);"])
    pd = PairDesc(element=NAME, material=MATERIAL, integration="full", ntab=1, nqp=0,
                  ops_force=_ops(f_low), ops_force_tangent=_ops(f_low) + _ops(k_low),
                  functions={"tabulate": f"{sym}_tabulate", "energy": f"{sym}_energy",
                             "force": f"{sym}_force", "force_tangent": f"{sym}_force_tangent"})
    c += pair_descriptors(("cg",), [pd])
    return htxt, "\n".join(c)


def joints_source():
    h = input_hash(paths() + core_paths())
    hdr = _header_lines("joints", h, "constraint equations, Jacobians and Hessian terms of the joints")
    htxt = "\n".join(hdr) + """
#ifndef BK_GEN_JOINTS_H
#define BK_GEN_JOINTS_H
#include "bk_joint.h"

/* Every joint kind, by constraint.type */
extern const bk_joint_kind *const bk_joint_kinds[];
extern const int bk_njoint_kinds;

/* The joint coordinate of an actuator (gen/actuator.py), x and prm[0..23] as the
 * joints': val[2] (rotation: X, Y, the angle atan2(Y, X); translation: s, 0),
 * grad[14] = ds/dx, H[14 * 14] = d2s/dx2 (full, symmetric). */
void bk_actuator_rotation(const double *restrict x, const double *restrict prm, double *restrict val,
                          double *restrict grad, double *restrict H);
void bk_actuator_translation(const double *restrict x, const double *restrict prm, double *restrict val,
                             double *restrict grad, double *restrict H);

#endif
"""
    c = [f"/* {BANNER} (see joints.h) */", '#include "joints.h"'] + version_guard() + [
         f"#if !defined(BK_JOINT_VERSION) || BK_JOINT_VERSION != 2",
         '#error "generated for runtime/bk_joint.h version 2: regenerate out/kernels with ./build.sh gen"',
         "#endif", ""]
    for name in body.JOINT_TYPES:
        c += _function(f"static void {name}_eval({_D} x, {_D} prm, {_W} g, {_W} G)",
                       lower(body.joint_program(name, 1), ()))
        low = lower(body.joint_program(name, 2), ())
        fn = _function(f"static void {name}_hessian({_D} x, {_D} prm, {_D} nu, {_W} H)", low)
        mirror = ["    for (int i = 0; i < 14; ++i)", "        for (int j = 0; j < i; ++j)",
                  "            H[14 * i + j] = H[14 * j + i];"]
        c += fn[:-2] + mirror + fn[-2:]
        c += [f"static const bk_joint_kind kind_{name} = {{", f'    .name = "{name}",',
              f"    .nrow = {body.joint_nrow(name)},", f"    .eval = {name}_eval,",
              f"    .hessian = {name}_hessian,", f"    .driven = {body.DRIVEN.get(name, 0)},", "};", ""]
    mirror = ["    for (int i = 0; i < 14; ++i)", "        for (int j = 0; j < i; ++j)",
              "            H[14 * i + j] = H[14 * j + i];"]
    for kind in actuator.KINDS:
        fn = _function(f"void bk_actuator_{kind}({_D} x, {_D} prm, {_W} val, {_W} grad, {_W} H)",
                       lower(actuator.actuator_program(kind), ()))
        c += fn[:-2] + mirror + fn[-2:]
    c += ["const bk_joint_kind *const bk_joint_kinds[] = {" +
          ", ".join(f"&kind_{n}" for n in body.JOINT_TYPES) + "};",
          f"const int bk_njoint_kinds = {len(body.JOINT_TYPES)};", ""]
    return htxt, "\n".join(c)


def unit_source(unit):
    return body_source() if unit == "rigid_body" else joints_source()


def index_entries():
    """index.json: the body element's nodes and pair, the joint kinds and their files."""
    d = describe()
    return ({"element": NAME, "material": MATERIAL, "ndof": d.ndof, "title": TITLE,
             "nodes": [{"xi": "1/2", "fields": [[f.name, f.dim] for f in d.fields]}],
             "pair": f"{NAME}_{MATERIAL}_full", "params": ["cg"], "integration": "full",
             "symbol": f"bk_pair_{NAME}_{MATERIAL}_full", "files": [f"{NAME}.c"]},
            {"files": ["joints.c"], "types": {n: {"rows": body.joint_nrow(n)} for n in body.JOINT_TYPES}})
