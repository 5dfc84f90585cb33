"""Frequencies and decay rates of a sum of damped sinusoids sampled at equal
intervals, by the matrix pencil method (Hua and Sarkar, 1990)."""
import numpy as np


def matrix_pencil(y, dt, order, pencil=None):
    """Returns (frequencies in Hz, decay rates in 1/s) of the `order` strongest
    complex exponentials in y, positive frequencies only, sorted by frequency."""
    y = np.asarray(y, dtype=float)
    n = len(y)
    Lp = pencil or n // 3
    Y = np.array([y[i:i + Lp + 1] for i in range(n - Lp)])
    U, s, Vt = np.linalg.svd(Y, full_matrices=False)
    V = Vt[:order].T
    V1, V2 = V[:-1], V[1:]
    z = np.linalg.eigvals(np.linalg.pinv(V1) @ V2)
    lam = np.log(z.astype(complex)) / dt
    keep = [l for l in lam if l.imag > 1e-9]
    keep.sort(key=lambda l: l.imag)
    return np.array([l.imag / (2 * np.pi) for l in keep]), np.array([-l.real for l in keep])
