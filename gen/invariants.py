"""Invariants of C = F^T F and their first and second derivatives with respect to F.

These are the building blocks of every isotropic hyperelastic kernel.  With the
ANCF interpolation F = sum_a q_a g_a^T (g_a = grad N_a at a quadrature point),
dI/dq_a = (dI/dF) g_a, which are the seed's Eqs. (30) and (34) written per node:

  dI1/dF = 2 F                      -> dI1/dq_a = 2 F g_a          (Eq. 30)
  dJ/dF  = cof F                    -> dJ/dq_a  = cof(F) g_a       (Eq. 34:
           columns of cof F are r_y x r_z, r_z x r_x, r_x x r_y)
  dI2/dF = 2 (I1 F - F C)
  dC_IJ/dF_kL = delta_LI F_kJ + delta_LJ F_kI   (components of C in the element's
                                     material frame: x along the beam axis, y, z across)

Second derivatives, as 4-index arrays D[i][J][k][L] = d^2 I / dF_iJ dF_kL:

  d2 I1 = 2 delta_ik delta_JL
  d2 I2 = 2 (2 F_iJ F_kL + I1 delta_ik delta_JL - delta_ik C_JL - F_iL F_kJ - b_ik delta_JL),  b = F F^T
  d2 J  = eps_ikm eps_JLM F_mM
  d2 C_IJ / dF_iM dF_kL = delta_ik (delta_MI delta_LJ + delta_MJ delta_LI)

Everything is expressed in terms of the symbols passed in (F, C, b, I1, cof), so
the generated code computes each intermediate once.  tests/test_generator.py
checks these formulas against direct sympy differentiation.
"""
import sympy as sp
from sympy import LeviCivita

R3 = range(3)


def cofactor(F):
    """cof F = det(F) F^-T as polynomials in the entries of F."""
    return sp.Matrix(3, 3, lambda i, j: F.cofactor(i, j))


def first_derivatives(F, C, I1, cof):
    """Map invariant name -> 3x3 matrix dI/dF."""
    FC = F * C
    return {
        "I1": 2 * F,
        "I2": sp.Matrix(3, 3, lambda i, J: 2 * (I1 * F[i, J] - FC[i, J])),
        "J": cof,
    }


def second_derivatives(F, C, b, I1):
    """Map invariant name -> function (i, J, k, L) -> d2I / dF_iJ dF_kL."""
    def d(i, j):
        return 1 if i == j else 0

    def d2I1(i, J, k, L):
        return 2 * d(i, k) * d(J, L)

    def d2I2(i, J, k, L):
        return 2 * (2 * F[i, J] * F[k, L] + I1 * d(i, k) * d(J, L) - d(i, k) * C[J, L]
                    - F[i, L] * F[k, J] - b[i, k] * d(J, L))

    def d2J(i, J, k, L):
        return sum(LeviCivita(i, k, m) * LeviCivita(J, L, M) * F[m, M] for m in R3 for M in R3)

    return {"I1": d2I1, "I2": d2I2, "J": d2J}


COMPONENTS = tuple((I, J) for I in range(3) for J in range(I, 3))


def component_first(F, I, J):
    """3x3 matrix dC_IJ/dF."""
    return sp.Matrix(3, 3, lambda k, L: (F[k, J] if L == I else 0) + (F[k, I] if L == J else 0))


def component_second(I, J):
    """(i, M, k, L) -> d2 C_IJ / dF_iM dF_kL."""
    def f(i, M, k, L):
        if i != k:
            return 0
        return (1 if (M == I and L == J) else 0) + (1 if (M == J and L == I) else 0)
    return f
