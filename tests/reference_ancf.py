"""A second, independent implementation of the ANCF 3243 element: a plain
quadrature loop with dense shape-function matrices, written from the seeds
and not from the generator.

  * shape functions typed in from seed 001 Eq. (3), with hand-derived gradients;
  * S_x, S_y, S_z as dense 3 x 24 matrices at each Gauss point (3 x 2 x 2);
  * St. Venant-Kirchhoff in Voigt notation: Green strain vector, B matrix,
    K = sum w (B^T D B + sum_v S_v d2E_v/dq2);
  * Neo-Hookean through the seed appendix: I1 = q^T (S_x^T S_x + ...) q,
    dI1/dq = 2 (S_x^T S_x + ...) q (Eq. 30), dJ/dq = S_x^T (r_y x r_z) + ... (Eq. 34),
    and the second derivative of J by the product rule on Eq. (34).
"""
import numpy as np


def shape(xi, y, z, l):
    """N (8,) and dN (8, 3) = dN_a/d(x, y, z) of the seed's Eq. (3)."""
    N = np.array([1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), y * (1 - xi), z * (1 - xi),
                  3 * xi**2 - 2 * xi**3, l * (-xi**2 + xi**3), y * xi, z * xi])
    dxi = np.array([-6 * xi + 6 * xi**2, l * (1 - 4 * xi + 3 * xi**2), -y, -z,
                    6 * xi - 6 * xi**2, l * (-2 * xi + 3 * xi**2), y, z]) / l
    dy = np.array([0, 0, 1 - xi, 0, 0, 0, xi, 0])
    dz = np.array([0, 0, 0, 1 - xi, 0, 0, 0, xi])
    return N, np.stack([dxi, dy, dz], axis=1)


def gauss_points(geom, counts=(3, 2, 2)):
    l, b, h = geom[:3]
    pts = []
    gx = np.polynomial.legendre.leggauss(counts[0])
    gy = np.polynomial.legendre.leggauss(counts[1])
    gz = np.polynomial.legendre.leggauss(counts[2])
    for sx, wx in zip(*gx):
        for sy, wy in zip(*gy):
            for sz, wz in zip(*gz):
                pts.append(((sx + 1) / 2, sy * b / 2, sz * h / 2, wx * wy * wz * l * b * h / 8))
    return pts


def smat(v):
    """Dense 3 x 24 matrix v (x) I3."""
    S = np.zeros((3, 24))
    for a in range(8):
        S[:, 3 * a:3 * a + 3] = v[a] * np.eye(3)
    return S


def skew(a):
    return np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def svk(q, geom, lam, mu):
    """Energy, force, tangent of ancf3243 x St. Venant-Kirchhoff."""
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[:3, :3] += 2 * mu * np.eye(3)
    D[3:, 3:] = mu * np.eye(3)
    U, f, K = 0.0, np.zeros(24), np.zeros((24, 24))
    pairs = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]   # Voigt order
    for xi, y, z, w in gauss_points(geom):
        _, dN = shape(xi, y, z, geom[0])
        S = [smat(dN[:, k]) for k in range(3)]
        r = [S[k] @ q for k in range(3)]
        E = np.array([(r[i] @ r[j] - (i == j)) * (0.5 if i == j else 1.0) for i, j in pairs])
        B = np.array([(r[i] @ S[j] + r[j] @ S[i]) * (0.5 if i == j else 1.0) for i, j in pairs])
        sig = D @ E
        U += w * 0.5 * E @ sig
        f += w * B.T @ sig
        K += w * B.T @ D @ B
        for v, (i, j) in enumerate(pairs):
            H = (S[i].T @ S[j] + S[j].T @ S[i]) * (0.5 if i == j else 1.0)
            K += w * sig[v] * H
    return U, f, K


def neo_hookean(q, geom, lam, mu):
    """Energy, force, tangent of ancf3243 x compressible Neo-Hookean
    W = mu/2 (I1 - 3) - mu ln J + lam/2 (ln J)^2, through the seed's Eqs. (29)-(34)."""
    U, f, K = 0.0, np.zeros(24), np.zeros((24, 24))
    for xi, y, z, w in gauss_points(geom):
        _, dN = shape(xi, y, z, geom[0])
        Sx, Sy, Sz = (smat(dN[:, k]) for k in range(3))
        rx, ry, rz = Sx @ q, Sy @ q, Sz @ q
        M = Sx.T @ Sx + Sy.T @ Sy + Sz.T @ Sz
        I1 = q @ M @ q                                              # Eq. (29)
        dI1 = 2 * M @ q                                             # Eq. (30)
        J = rx @ np.cross(ry, rz)                                   # Eq. (31)
        dJ = Sx.T @ np.cross(ry, rz) + Sy.T @ np.cross(rz, rx) + Sz.T @ np.cross(rx, ry)   # Eq. (34)
        d2J = (Sx.T @ (skew(ry) @ Sz - skew(rz) @ Sy) + Sy.T @ (skew(rz) @ Sx - skew(rx) @ Sz)
               + Sz.T @ (skew(rx) @ Sy - skew(ry) @ Sx))
        lnJ = np.log(J)
        W1 = mu / 2
        WJ = -mu / J + lam * lnJ / J
        WJJ = mu / J**2 + lam * (1 - lnJ) / J**2
        U += w * (mu / 2 * (I1 - 3) - mu * lnJ + lam / 2 * lnJ**2)
        f += w * (W1 * dI1 + WJ * dJ)
        K += w * (W1 * 2 * M + WJ * d2J + WJJ * np.outer(dJ, dJ))
    return U, f, K
