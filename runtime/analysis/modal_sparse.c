/* modal_sparse.c -- the lowest modes of a model too large for the dense
 * eigen-solver of modal.c: shift-invert Lanczos (linalg/lanczos.h) with the
 * Newton matrix's pattern and the linear solver object (linalg/linsolve.h).
 *
 * The operator.  With A the Newton matrix of K + sigma M and the scaled
 * constraint rows (assembly/system.h),
 *     [ K + sigma M   s G^T ] [ y   ]   [ M x ]
 *     [ s G           0     ] [ lam ] = [ 0   ],
 * y = OP x is (K + sigma M)^-1 M x restricted to the motions G y = 0: OP is
 * M-symmetric there, and its eigenvalues theta = 1 / (omega^2 + sigma) are
 * largest for the lowest frequencies.  sigma = 1e-12 tr K / tr M keeps A
 * regular for free rigid motions (omega = 0) while it stays below the lowest
 * elastic omega^2 of fine meshes (tr K / tr M grows as the element length to
 * the -2; the dense solver's 1e-6 would crowd the lowest modes together
 * for 10,000 elements, and the iteration would converge slowly); massless
 * directions (a quaternion's scale) have theta = 0 and never come first.  K
 * is the elements' tangent at the state (as the dense solver: no load
 * stiffness), M the mass with the rotary inertia of beams with nodal
 * rotations.  A is factored once (band LU or KLU, whichever the linear solver
 * object picks); each Lanczos step is one solve.
 *
 * Limits (refused with a message): constraints of deficient rank (A is then
 * singular: the dense solver handles them), joints nonlinear in q about a
 * static state (their geometric stiffness needs the multipliers).
 */
#include "analysis/modal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/interaction.h"
#include "linalg/lanczos.h"
#include "linalg/linsolve.h"

/* The Lanczos steps at most: enough for `want` well-separated modes with
 * room, capped (its basis is 2 (steps + 1) n doubles). */
#define BK_MODAL_SPARSE_STEPS(want) ((want) * 4 + 60)
#define BK_MODAL_SPARSE_TOL 1e-10

typedef struct sparse_op {
    const bk_system *s;
    bk_linsolver *ls;
    const double *Mx;      /* [nnz] the mass on the pattern (free rows and columns) */
    double *b;             /* [neq] right-hand side and solution */
} sparse_op;

static void mass_prod(void *ctx, const double *x, double *y)
{
    const sparse_op *o = ctx;
    const bk_system *s = o->s;
    memset(y, 0, (size_t)s->nfree * sizeof *y);
    for (int j = 0; j < s->nfree; ++j)
        for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k)
            if (s->Ai[k] < s->nfree)
                y[s->Ai[k]] += o->Mx[k] * x[j];
}

static int shift_invert(void *ctx, const double *x, double *y)
{
    sparse_op *o = ctx;
    const bk_system *s = o->s;
    mass_prod(ctx, x, o->b);
    memset(o->b + s->nfree, 0, (size_t)(s->neq - s->nfree) * sizeof *o->b);
    if (bk_lin_solve(o->ls, o->b) != BK_LIN_OK)
        return -1;
    memcpy(y, o->b, (size_t)s->nfree * sizeof *y);
    return 0;
}

int bk_modal_interactions(bk_system *s, const double *q, double *fint, double *Ax)
{
    const double x = s->m->modal.about == BK_ABOUT_STATIC ? 1.0 : 0.0;
    const bk_path at = {.factor = x, .x = x};
    memset(fint, 0, (size_t)s->m->ndof * sizeof *fint);
    return bk_assemble_interactions(s, q, &at, fint, Ax);
}

/* K (the elements' and the interactions' tangent) into Ax and M into Mx, both on the pattern; the
 * traces of their free diagonals.  -1 on a non-finite tangent. */
static int matrices(bk_system *s, const double *q, double *Ax, double *Mx, double *fint, double *work,
                    double *trK, double *trM)
{
    const bk_model *m = s->m;
    const int md = s->maxdof;
    if (bk_assemble_internal(s, q, fint, Ax) != 0 || bk_modal_interactions(s, q, fint, Ax) != 0)
        return -1;
    memset(Mx, 0, (size_t)s->nnz * sizeof *Mx);
    double *me = work, *Me = work + (size_t)md * md, *Cq = Me + (size_t)md * md, *Kq = Cq + (size_t)md * md;
    double *qe = Kq + (size_t)md * md, *fe = qe + md, *qd0 = fe + md;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_element *et = m->pairs[el->pair]->element;
        bk_element_mass(m, e, me, Me);
        bk_scatter_matrix(s, e, Me, 1.0, Mx);
        if (et->rotary) {
            double Trot;
            bk_gather(m, e, q, qe);
            memset(qd0, 0, (size_t)md * sizeof *qd0);
            et->rotary(m->geoms[el->geom], qe, qd0, qd0, fe, Me, Cq, Kq, &Trot);
            bk_scatter_matrix(s, e, Me, m->mats[el->mat].rho, Mx);
        }
    }
    *trK = *trM = 0.0;
    for (int i = 0; i < s->nfree; ++i) {
        *trK += Ax[s->diag[i]];
        *trM += Mx[s->diag[i]];
    }
    return 0;
}

int bk_modal_sparse(bk_system *s, const double *q, int want, double *omega, double *X, int *got, int *steps,
                    char *msg, size_t nmsg)
{
    const bk_model *m = s->m;
    const int n = s->nfree;
    const size_t md = (size_t)(s->maxdof > 0 ? s->maxdof : 1);
    *got = *steps = 0;
    if (bk_constraints_nonlinear(s) > 0 && m->modal.about == BK_ABOUT_STATIC) {
        snprintf(msg, nmsg, "the sparse modal solver does not take joints nonlinear in the coordinates about a "
                 "static state (their geometric stiffness needs the multipliers): use modal.solver = \"dense\"");
        return 1;
    }
    double *Ax = malloc((size_t)s->nnz * sizeof *Ax), *Mx = malloc((size_t)s->nnz * sizeof *Mx);
    double *fint = malloc((size_t)m->ndof * sizeof *fint), *work = malloc((4 * md * md + 3 * md) * sizeof *work);
    double *b = malloc((size_t)s->neq * sizeof *b), *nu = calloc((size_t)(s->ncon > 0 ? s->ncon : 1), sizeof *nu);
    double *theta = malloc((size_t)want * sizeof *theta);
    bk_linsolver ls;
    int rc = 1, have_ls = 0;
    if (!Ax || !Mx || !fint || !work || !b || !nu || !theta) {
        snprintf(msg, nmsg, "out of memory for the sparse modal matrices");
        goto done;
    }
    double trK, trM;
    if (matrices(s, q, Ax, Mx, fint, work, &trK, &trM) != 0) {
        snprintf(msg, nmsg, "non-finite tangent at the state of the modal analysis");
        goto done;
    }
    if (!(trM > 0.0)) {
        snprintf(msg, nmsg, "the model has no mass (set rho)");
        goto done;
    }
    const double sigma = 1e-12 * fabs(trK) / trM;
    for (long k = 0; k < s->nnz; ++k)
        Ax[k] += sigma * Mx[k];
    bk_assemble_constraints(s, q, nu, 0.0, NULL, Ax);
    if (bk_lin_init(&ls, s->neq, s->Ap, s->Ai) != 0) {
        snprintf(msg, nmsg, "out of memory for the linear solver");
        goto done;
    }
    have_ls = 1;
    int f = bk_lin_factor(&ls, Ax);
    if (f != BK_LIN_OK) {
        snprintf(msg, nmsg, "%s: K + sigma M with the constraint rows is singular (constraints of deficient rank, "
                 "or a motion with neither stiffness nor mass): use modal.solver = \"dense\"",
                 f == BK_LIN_SINGULAR ? "singular matrix" : "factorization failed");
        goto done;
    }
    sparse_op o = {s, &ls, Mx, b};
    const bk_lanczos_ops ops = {&o, shift_invert, mass_prod};
    int nconv, maxit = BK_MODAL_SPARSE_STEPS(want);
    int lr = bk_lanczos(n, want, maxit, BK_MODAL_SPARSE_TOL, &ops, theta, X, &nconv, steps);
    if (lr < 0) {
        snprintf(msg, nmsg, "out of memory (or a failed solve) in the Lanczos iteration");
        goto done;
    }
    for (int k = 0; k < nconv; ++k) {
        if (!(theta[k] > 1e-14 / (trK / trM + sigma)))
            break;                              /* massless directions: infinite frequency */
        const double w2 = 1.0 / theta[k] - sigma;
        omega[k] = w2 > 0.0 ? sqrt(w2) : 0.0;
        *got = k + 1;
    }
    if (*got == 0) {
        snprintf(msg, nmsg, "no mode converged in %d Lanczos steps", *steps);
        goto done;
    }
    rc = 0;
done:
    if (have_ls)
        bk_lin_free(&ls);
    free(Ax), free(Mx), free(fint), free(work), free(b), free(nu), free(theta);
    return rc;
}
