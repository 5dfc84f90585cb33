"""The generated kernels against a second implementation written differently
(tests/reference_ancf.py: dense quadrature loop in numpy from the seeds)."""
import numpy as np

import reference_ancf as ref
from util import Kernel


def reference_q(geom, R, x0):
    l = geom[0]
    t, d1, d2 = R[:, 0], R[:, 1], R[:, 2]
    return np.concatenate([x0, t, d1, d2, x0 + l * t, t, d1, d2])


def random_rotation(rng):
    A = rng.normal(size=(3, 3))
    Q, Rr = np.linalg.qr(A)
    Q = Q @ np.diag(np.sign(np.diag(Rr)))
    if np.linalg.det(Q) < 0:
        Q[:, 0] *= -1
    return Q


def compare(material, fn):
    rng = np.random.default_rng(20261123)
    k = Kernel("ancf3243", material)
    E, nu = 7.2e10, 0.3
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    worst = 0.0
    for geom in ([0.1, 0.01, 0.01], [0.5, 0.2, 0.1]):
        tab = k.tabulate(geom)
        scale = np.array([geom[0]] * 3 + [1.0] * 9 + [geom[0]] * 3 + [1.0] * 9)
        for _ in range(12):
            q0 = reference_q(geom, random_rotation(rng), rng.normal(size=3))
            q = q0 + 0.1 * scale * rng.uniform(-1, 1, size=24)
            U, f, K = k.eval(q, tab, [lam, mu])
            Ur, fr, Kr = fn(q, geom, lam, mu)
            errs = (abs(U - Ur) / abs(Ur), np.abs(f - fr).max() / np.abs(fr).max(),
                    np.abs(K - Kr).max() / np.abs(Kr).max())
            worst = max(worst, *errs)
            assert max(errs) <= 1e-10, f"{material} geom {geom}: energy/force/tangent rel. errors {errs}"
    return worst


def test_svk_matches_dense_voigt_implementation():
    compare("svk", ref.svk)


def test_neo_hookean_matches_seed_invariant_formulas():
    compare("neo_hookean", ref.neo_hookean)


def test_mass_matrix_and_volume_integrals_match_quadrature():
    """ancf3243_mass / _volume (exact symbolic integrals) against a 4 x 3 x 3 Gauss
    quadrature of the hand-written shape functions, and against rigid-body
    kinematics: q^T M q = rho V |v|^2 for a translation."""
    import ctypes
    k = Kernel("ancf3243", "svk")
    from gen import contract
    geom = np.zeros(contract.ngeom())        # every slot of bk_kernel.h (the band slots 0: the whole section)
    geom[:3] = (0.3, 0.04, 0.02)
    m = np.zeros(64)
    v = np.zeros(8)
    D = ctypes.POINTER(ctypes.c_double)

    class Element(ctypes.Structure):      # the leading fields of bk_element (runtime/bk_kernel.h)
        _fields_ = [("name", ctypes.c_char_p), ("title", ctypes.c_char_p), ("nnode", ctypes.c_int),
                    ("ndof", ctypes.c_int), ("node_xi", D), ("caps", ctypes.c_uint), ("nfield", ctypes.c_int),
                    ("field_role", ctypes.c_void_p), ("field_name", ctypes.c_void_p), ("field_dof", ctypes.c_void_p),
                    ("field_dim", ctypes.c_void_p), ("reference", ctypes.c_void_p),
                    ("nshape", ctypes.c_int), ("shape_dof", ctypes.c_void_p), ("shape", ctypes.c_void_p),
                    ("mass", ctypes.CFUNCTYPE(None, D, D)), ("volume", ctypes.CFUNCTYPE(None, D, D))]
    el = Element.in_dll(k.lib, "bk_element_ancf3243")
    el.mass(geom.ctypes.data_as(D), m.ctypes.data_as(D))
    el.volume(geom.ctypes.data_as(D), v.ctypes.data_as(D))
    m = m.reshape(8, 8)
    mref, vref = np.zeros((8, 8)), np.zeros(8)
    for xi, y, z, w in ref.gauss_points(geom, (4, 3, 3)):
        N, _ = ref.shape(xi, y, z, geom[0])
        mref += w * np.outer(N, N)
        vref += w * N
    assert np.abs(m - mref).max() <= 1e-14 * np.abs(mref).max(), np.abs(m - mref).max()
    assert np.abs(v - vref).max() <= 1e-14 * np.abs(vref).max()
    V = geom[:3].prod()
    vel = np.array([0.3, -1.2, 0.7])
    qdot = np.concatenate([vel, [0] * 9, vel, [0] * 9])
    M = np.kron(m, np.eye(3))
    assert abs(qdot @ M @ qdot - V * vel @ vel) <= 1e-14 * V
    assert abs(v[0] + v[4] - V) <= 1e-15 * V     # position shape functions carry the volume
