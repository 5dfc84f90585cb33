"""Geometry of beams: straight lines and circular arcs with their section frames,
reference nodal fields, section constants (the geom[] layout of bk_kernel.h)."""
import math

from gen.scene.values import _cross, _dot, _norm, _scale, _sub, get_number, get_vec3

class LineGeometry:
    """Straight beam: point and section frame (t, d1, d2) at arc length s."""

    def __init__(self, start, t, d1, d2, length):
        self.start, self.t, self.d1, self.d2, self.length = start, t, d1, d2, length
        self.shape_key = ("straight",)      # elements of equal length are congruent

    def at(self, s):
        return [self.start[i] + s * self.t[i] for i in range(3)], self.t, self.d1, self.d2


class ArcGeometry:
    """Circular arc about `axis` through `center`, from `start`, right-handed."""

    def __init__(self, center, axis, start, d1, d2, radius, angle):
        self.center, self.axis, self.start0 = center, axis, start
        self.d10, self.d20, self.radius = d1, d2, radius
        self.length = radius * angle
        self.shape_key = ("arc", round(radius, 12))

    def at(self, s):
        phi = s / self.radius
        rot = lambda v: _rotate(v, self.axis, phi)
        X = [self.center[i] + x for i, x in enumerate(rot(_sub(self.start0, self.center)))]
        d1, d2 = rot(self.d10), rot(self.d20)
        return X, _cross(d1, d2), d1, d2


def _rotate(v, k, phi):
    """Rodrigues rotation of v about the unit axis k by phi."""
    c, s_ = math.cos(phi), math.sin(phi)
    kv = _cross(k, v)
    kd = _dot(k, v)
    return [v[i] * c + kv[i] * s_ + k[i] * kd * (1 - c) for i in range(3)]


def line_geometry(ctx, bt, where, start, end):
    axis = _sub(end, start)
    length = _norm(axis)
    if not length > 0:
        ctx.fail(f"{where}.end", "expected an end point different from start (beam length must be positive)")
    t = _scale(axis, 1 / length)
    d1, d2 = section_axes(ctx, bt, where, t, [0.0, 0.0, 1.0])
    return LineGeometry(start, t, d1, d2, length)


def section_axes(ctx, bt, where, t, default_up):
    up = get_vec3(ctx, bt, "up", where, default=default_up, nonzero=True, bound=1e300)
    upn = _scale(up, 1 / _norm(up))
    d2 = _sub(upn, _scale(t, _dot(upn, t)))
    if _norm(d2) < 1e-6:
        ctx.fail(f"{where}.up", "expected a direction not parallel to the beam axis")
    d2 = _scale(d2, 1 / _norm(d2))
    return _cross(d2, t), d2


def arc_geometry(ctx, bt, where, start):
    for k in ("arc_center", "arc_axis", "arc_angle"):
        if k not in bt:
            ctx.fail(f"{where}.{k}", "missing; a curved beam needs arc_center, arc_axis and arc_angle")
    center = get_vec3(ctx, bt, "arc_center", where, bound=1e9)
    axis = get_vec3(ctx, bt, "arc_axis", where, nonzero=True, bound=1e300)
    axis = _scale(axis, 1 / _norm(axis))
    angle = get_number(ctx, bt, "arc_angle", where)
    if not 0 < angle <= 360:
        ctx.fail(f"{where}.arc_angle", f"expected an angle in (0, 360] degrees, found {angle!r}")
    rvec = _sub(start, center)
    radius = _norm(rvec)
    if radius == 0 or abs(_dot(rvec, axis)) > 1e-9 * radius:
        ctx.fail(f"{where}.arc_center", "expected the start point off the centre, in the plane normal to arc_axis")
    t = _cross(axis, _scale(rvec, 1 / radius))
    d1, d2 = section_axes(ctx, bt, where, t, axis)
    return ArcGeometry(center, axis, start, d1, d2, radius, math.radians(angle))


def eval_fraction(s):
    if "/" in s:
        a, b = s.split("/")
        return int(a) / int(b)
    return float(s)


def reference_field(name, t, d1, d2, x0):
    """Reference value of a nodal field for the section frame (t, d1, d2) at x0."""
    if name == "r":
        return list(x0)
    if name == "r_x":
        return list(t)
    if name == "r_y":
        return list(d1)
    if name == "r_z":
        return list(d2)
    if name == "p":
        return frame_quaternion(t, d1, d2)
    return [0.0, 0.0, 0.0]


def frame_quaternion(t, d1, d2):
    """Unit quaternion (s, x, y, z) of the rotation with columns (t, d1, d2)."""
    R = [[t[i], d1[i], d2[i]] for i in range(3)]
    tr = R[0][0] + R[1][1] + R[2][2]
    if tr > 0:
        w = math.sqrt(1 + tr) * 2
        q = [w / 4, (R[2][1] - R[1][2]) / w, (R[0][2] - R[2][0]) / w, (R[1][0] - R[0][1]) / w]
    elif R[0][0] > R[1][1] and R[0][0] > R[2][2]:
        w = math.sqrt(1 + R[0][0] - R[1][1] - R[2][2]) * 2
        q = [(R[2][1] - R[1][2]) / w, w / 4, (R[0][1] + R[1][0]) / w, (R[0][2] + R[2][0]) / w]
    elif R[1][1] > R[2][2]:
        w = math.sqrt(1 + R[1][1] - R[0][0] - R[2][2]) * 2
        q = [(R[0][2] - R[2][0]) / w, (R[0][1] + R[1][0]) / w, w / 4, (R[1][2] + R[2][1]) / w]
    else:
        w = math.sqrt(1 + R[2][2] - R[0][0] - R[1][1]) * 2
        q = [(R[1][0] - R[0][1]) / w, (R[0][2] + R[2][0]) / w, (R[1][2] + R[2][1]) / w, w / 4]
    n = math.sqrt(sum(x * x for x in q))
    return [x / n for x in q]


def section_geometry(sec, l, band=(0.0, 0.0)):
    """geom[] of an element of length l with section sec, in the slot order of
    runtime/bk_kernel.h (gen/contract.py): l, b, h, A, I1, I2, Ip, shape, and the
    band (lo, hi[, neutral axis[, eigenstrain]]) of the height a layer integrates
    (A, I1, I2 stay the whole section's: loads and tendons spread over it) and the
    layer's free isotropic strain."""
    from gen import contract
    shape, b, h = sec
    if shape == "rectangle":
        A, I1, I2 = b * h, b * h**3 / 12, h * b**3 / 12
    else:
        r = b / 2
        A, I1 = math.pi * r * r, math.pi * r**4 / 4
        I2 = I1
    return contract.geom_vector(L=l, B=b, H=h, A=A, I1=I1, I2=I2, IP=I1 + I2,
                                SHAPE=contract.section_shapes()[shape], BAND_LO=band[0], BAND_HI=band[1],
                                BAND_AXIS=band[2] if len(band) > 2 else 0.0,
                                EIGENSTRAIN=band[3] if len(band) > 3 else 0.0)
