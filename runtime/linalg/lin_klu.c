/* lin_klu.c -- the KLU backend of the linear solver object: analyse once,
 * factor once, then refactor (see linsolve.h).
 *
 * The first numeric factorization (klu_factor) chooses the pivots and
 * allocates the LU factors.  Later factorizations on the same pattern reuse
 * both through klu_refactor, which allocates nothing; only when the old
 * pivot sequence has become poor for the new values (refactor fails, or the
 * reciprocal pivot growth / condition estimate collapses) is a fresh
 * klu_factor done.
 */
#include "linalg/linsolve.h"

/* A refactorization is kept when its condition estimate is no worse than this
 * fraction of the one of the last full factorization, and that one was not
 * poor (below BK_RCOND_POOR: pivots chosen at a bad state, e.g. a diverging
 * Newton iterate): else the pivots are chosen again for the new values (every
 * time, while the matrix itself stays that ill-conditioned). */
#define BK_REFACTOR_RCOND_DROP 1e-3
#define BK_RCOND_POOR 1e-12

static int full_factor(bk_linsolver *s, double *Ax)
{
    if (s->num)
        klu_free_numeric(&s->num, &s->common);
    s->num = klu_factor((int *)s->Ap, (int *)s->Ai, Ax, s->sym, &s->common);
    s->nfactor++;
    s->nfull++;
    if (!s->num)
        return s->common.status == KLU_SINGULAR ? BK_LIN_SINGULAR : BK_LIN_ERROR;
    if (!klu_rcond(s->sym, s->num, &s->common))
        return BK_LIN_ERROR;
    s->rcond = s->common.rcond;
    s->rcond_factor = s->rcond;
    if (!(s->rcond > 1e-300))
        return BK_LIN_SINGULAR;
    return BK_LIN_OK;
}

static int klu_factor_(bk_linsolver *s, double *Ax)
{
    if (s->num) {
        /* Reuse the pivot order and the factor storage: no allocation. */
        if (klu_refactor((int *)s->Ap, (int *)s->Ai, Ax, s->sym, s->num, &s->common) &&
            klu_rcond(s->sym, s->num, &s->common) && s->common.rcond > 1e-300 &&
            s->common.rcond >= BK_REFACTOR_RCOND_DROP * s->rcond_factor && s->rcond_factor >= BK_RCOND_POOR) {
            s->rcond = s->common.rcond;
            s->nfactor++;
            return BK_LIN_OK;
        }
    }
    return full_factor(s, Ax);
}

static int klu_solve_(bk_linsolver *s, double *b)
{
    if (!s->num)
        return BK_LIN_ERROR;
    return klu_solve(s->sym, s->num, s->n, 1, b, &s->common) ? BK_LIN_OK : BK_LIN_ERROR;
}

static int klu_factor_solve_(bk_linsolver *s, double *Ax, double *b)
{
    int st = klu_factor_(s, Ax);
    return st != BK_LIN_OK ? st : klu_solve_(s, b);
}

static void klu_free_(bk_linsolver *s)
{
    if (s->num)
        klu_free_numeric(&s->num, &s->common);
    if (s->sym)
        klu_free_symbolic(&s->sym, &s->common);
}

const bk_lin_ops bk_lin_klu_ops = {"KLU", klu_factor_, klu_solve_, klu_factor_solve_, klu_free_};

int bk_lin_klu_init(bk_linsolver *s)
{
    s->sym = klu_analyze(s->n, (int *)s->Ap, (int *)s->Ai, &s->common);
    if (!s->sym)
        return BK_LIN_ERROR;
    s->ops = &bk_lin_klu_ops;
    s->nanalyze = 1;
    return BK_LIN_OK;
}
