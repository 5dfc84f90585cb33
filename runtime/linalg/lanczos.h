/* lanczos.h -- the largest eigenvalues of an operator that is symmetric in a
 * semi-definite inner product <x, y>_B = x^T B y, and their eigenvectors, by
 * the Lanczos method with full reorthogonalization (lanczos.c).
 *
 * Meant for shift-invert: OP = (K - sigma M)^-1 M is M-symmetric, and its
 * largest eigenvalues theta are the eigenvalues omega^2 = sigma + 1/theta of
 * K x = omega^2 M x nearest above sigma.  The start vector is OP applied to a
 * fixed pseudo-random vector, so the iteration stays in the range of OP (where
 * <,>_B is definite when B is definite on that range, as a mass matrix is
 * off its massless directions).  Every Lanczos vector is orthogonalized twice
 * against all the earlier ones (classical Gram-Schmidt in <,>_B), so no ghost
 * copies of converged eigenvalues appear; the cost is O(n m^2) for m steps.
 * The Ritz values of the tridiagonal matrix T_m come from cyclic Jacobi
 * rotations (m is at most a few hundred); a Ritz pair (theta, x) counts as
 * converged when |beta_m s_m| <= tol |theta|, s_m the last component of its
 * eigenvector of T_m (the B-norm of OP x - theta x).
 *
 * Repeated eigenvalues.  One Lanczos run finds one copy of a repeated
 * eigenvalue (a beam of square section bends alike in two planes).  So the
 * converged pairs are locked and the method runs again B-orthogonal to them
 * from another start; the best `want` of all pairs found are kept; it stops
 * when a run finds nothing that ranks among them (at most BK_LANCZOS_ROUNDS
 * runs: an eigenvalue of multiplicity k needs k runs and one more).
 *
 * Sizes and directions: n the operator's size; want the number of eigenpairs
 * (largest theta first); maxit (in) the largest number of Lanczos steps (its
 * basis is (maxit + 1) n doubles, twice: the vectors and B times them, per
 * run);
 * theta[want] (out) the eigenvalues, descending; X[want n] (out, may be NULL)
 * their eigenvectors, B-normalized, row k the k-th; *nconv (out) how many of
 * the first `want` converged; *steps (out) the Lanczos steps of every run.  Returns
 * 0, 1 when fewer than `want` converged within maxit steps (or the operator's
 * range is smaller: an invariant subspace was found; *nconv says how many
 * are good), -1 when out of memory or when op returned nonzero.
 */
#ifndef BK_LANCZOS_H
#define BK_LANCZOS_H

typedef struct bk_lanczos_ops {
    void *ctx;
    int (*op)(void *ctx, const double *x, double *y);      /* y[n] = OP x[n]: 0, or nonzero on failure */
    void (*bprod)(void *ctx, const double *x, double *y);  /* y[n] = B x[n] */
} bk_lanczos_ops;

int bk_lanczos(int n, int want, int maxit, double tol, const bk_lanczos_ops *ops, double *theta, double *X,
               int *nconv, int *steps);

/* Eigenvalues and eigenvectors of the symmetric matrix A[m m] (row-major,
 * destroyed) by cyclic Jacobi rotations: w[m] (out) descending, V[m m] (out)
 * column k the k-th eigenvector.  For small m (the Lanczos T). */
void bk_jacobi_eigen(int m, double *A, double *w, double *V);

#endif
