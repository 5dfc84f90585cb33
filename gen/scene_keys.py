"""Every key a scene file may hold, per table, in one place (sympy-free).

The scene reader (gen/scene/) accepts exactly these keys (plus, in
[material.NAME], the parameter keys of the chosen law: gen/materials/*.py
INPUTS, and the tables of the interaction modules, each with its keys in its
own module: gen/scene/interactions.py); tests/test_docs.py checks that the scene reference (docs/reference/scene.md) lists
the same keys.  The analysis options' keys ([scene] analysis, [static],
[dynamic], [modal], [buckling], [output]) come from the options schema
(gen/options_schema.py).
"""
from gen import options_schema as S

# the top-level tables: the scene's, then the option tables of the schema (an
# analysis's options table comes with its schema rows)
TOP = ("material", "section", "beam", "body", "constraint", "load", "initial_velocity", "sensor", "amplitude",
       "actuator", "point_mass") + tuple(S.TABLES)

SCENE = S.scene_keys("scene")
MATERIAL_COMMON = ("law", "rho", "kelvin_voigt")
SECTION = {"rectangle": ("shape", "b", "h"), "circle": ("shape", "radius")}
BEAM = ("name", "element", "material", "section", "section_end", "sections", "start", "end", "up", "elements", "integration",
        "arc_center", "arc_axis", "arc_angle", "path", "grading", "element_lengths", "layers")
BODY = ("name", "mass", "center", "inertia", "axes")
CONSTRAINT = {"clamp": ("type", "name", "a", "cross_section", "b"),
              "spherical": ("type", "name", "a", "b", "at"),
              "revolute": ("type", "name", "a", "b", "axis", "at"),
              "fixed": ("type", "name", "a", "b", "at"),
              "universal": ("type", "name", "a", "b", "axis", "axis_b", "at"),
              "prismatic": ("type", "name", "a", "b", "axis", "at"),
              "prescribed_rotation": ("type", "name", "a", "b", "at", "axis", "rate", "amplitude", "frequency",
                                      "angle", "angle_amplitude"),
              "prescribed_translation": ("type", "name", "a", "b", "at", "axis", "rate", "amplitude", "frequency",
                                         "distance", "distance_amplitude"),
              "point_on_line": ("type", "name", "a", "axis"),
              "prescribed_motion": ("type", "name", "a", "motion", "amplitude", "clamped")}
LOAD = {"force": ("type", "name", "at", "value", "distribution", "amplitude", "follower", "preload", "point"),
        "moment": ("type", "name", "at", "value", "amplitude", "follower", "preload"),
        "gravity": ("type", "name", "value", "amplitude", "preload"),
        "distributed": ("type", "name", "beam", "from", "to", "value", "amplitude", "follower", "preload"),
        "tendon": ("type", "name", "beam", "from", "to", "offset", "tension", "amplitude", "preload"),
        "chamber": ("type", "name", "beam", "from", "to", "offset", "area", "pressure", "amplitude", "preload")}
AMPLITUDE = {"ramp": ("type", "t0", "t1"),
             "step": ("type", "t0"),
             "sine": ("type", "amplitude", "frequency", "phase", "offset"),
             "table": ("type", "points", "file"),
             "cycloidal": ("type", "t0", "t1"),
             "quintic": ("type", "t0", "t1"),
             "spline": ("type", "points", "file")}
STATIC = S.scene_keys("static")
DYNAMIC = S.scene_keys("dynamic")
MODAL = S.scene_keys("modal")
BUCKLING = S.scene_keys("buckling")
OUTPUT = S.scene_keys("output")
INITIAL_VELOCITY = ("beam", "body", "velocity", "angular_velocity", "center")
SENSOR = ("name", "at", "point")
POINT_MASS = ("at", "mass")
ACTUATOR = ("name", "joint", "effort", "effort_amplitude", "kp", "kd", "setpoint", "setpoint_amplitude")
BEAM_CONTACT = ("name", "beams", "self", "exclude", "distance", "stiffness", "samples", "contact_radius", "friction",
                "slip", "static_friction", "kinetic_friction")


def union(by_type):
    out = []
    for keys in by_type.values():
        out += [k for k in keys if k not in out]
    return tuple(out)


def all_keys():
    """{table: keys} for every table but the law parameters of [material.NAME]."""
    tables = {"scene": SCENE, "material": MATERIAL_COMMON, "section": union(SECTION), "beam": BEAM, "body": BODY,
              "constraint": union(CONSTRAINT), "load": union(LOAD), "initial_velocity": INITIAL_VELOCITY,
              "sensor": SENSOR, "amplitude": union(AMPLITUDE), "actuator": ACTUATOR, "point_mass": POINT_MASS}
    # every options table of the schema (static, dynamic, modal, buckling, output, an analysis' own)
    tables.update({t: S.scene_keys(t) for t in S.TABLES if t != "scene"})
    return tables
