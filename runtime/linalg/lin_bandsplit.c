/* lin_bandsplit.c -- the split band LU backend of the linear solver object
 * (see linsolve.h, bandsplit.h): a long band factored as two halves on two
 * threads and a separator. */
#include "linalg/linsolve.h"

static int split_factor(bk_linsolver *s, double *Ax)
{
    const int rc = bk_bandsplit_factor(&s->split, Ax);  /* (before its rcond is read) */
    return bk_lin_band_status(s, rc, s->split.rcond);
}

static int split_solve(bk_linsolver *s, double *b)
{
    if (!(s->rcond > 1e-300))
        return BK_LIN_ERROR;
    bk_bandsplit_solve(&s->split, b);
    return BK_LIN_OK;
}

static int split_factor_solve(bk_linsolver *s, double *Ax, double *b)
{
    int rc = split_factor(s, Ax);
    return rc == BK_LIN_OK ? split_solve(s, b) : rc;
}

static void split_free(bk_linsolver *s)
{
    bk_bandsplit_free(&s->split);
}

const bk_lin_ops bk_lin_bandsplit_ops = {"band LU in two halves", split_factor, split_solve, split_factor_solve,
                                         split_free};

int bk_lin_bandsplit_init(bk_linsolver *s)
{
    if (bk_bandsplit_plan(&s->split, s->n, s->Ap, s->Ai, s->band.perm, s->band.kl, s->band.ku) != 0)
        return -1;
    bk_band_free(&s->band);              /* (its order is copied; its storage is not needed) */
    s->ops = &bk_lin_bandsplit_ops;
    s->nanalyze = 1;
    return BK_LIN_OK;
}
