/* linsolve.c -- the linear solver object: backend choice and the calls of the
 * interface (see linsolve.h). */
#include "linalg/linsolve.h"

#include <string.h>

int bk_lin_init_kind(bk_linsolver *s, int n, const int *Ap, const int *Ai, bk_lin_kind kind)
{
    memset(s, 0, sizeof *s);
    s->n = n;
    s->Ap = Ap;
    s->Ai = Ai;
    klu_defaults(&s->common);
    switch (kind) {
    case BK_LIN_BAND:
        return bk_lin_band_init(s, 1);
    case BK_LIN_KLU:
        return bk_lin_klu_init(s);
    case BK_LIN_DENSE:
        return bk_lin_dense_init(s);
    default: {
        int rc = bk_lin_band_init(s, 0);        /* -1: not a narrow band */
        return rc < 0 ? bk_lin_klu_init(s) : rc;
    }
    }
}

int bk_lin_init(bk_linsolver *s, int n, const int *Ap, const int *Ai)
{
    return bk_lin_init_kind(s, n, Ap, Ai, BK_LIN_AUTO);
}

int bk_lin_factor(bk_linsolver *s, double *Ax)
{
    return s->ops ? s->ops->factor(s, Ax) : BK_LIN_ERROR;
}

int bk_lin_solve(bk_linsolver *s, double *b)
{
    return s->ops ? s->ops->solve(s, b) : BK_LIN_ERROR;
}

int bk_lin_factor_solve(bk_linsolver *s, double *Ax, double *b)
{
    return s->ops ? s->ops->factor_solve(s, Ax, b) : BK_LIN_ERROR;
}

void bk_lin_free(bk_linsolver *s)
{
    if (s->ops)
        s->ops->free(s);
    s->ops = NULL;
}

const char *bk_lin_name(const bk_linsolver *s)
{
    return s->ops ? s->ops->name : "none";
}

bk_band *bk_lin_band(bk_linsolver *s)
{
    return s->ops == &bk_lin_band_ops ? &s->band : NULL;
}

bk_bandsplit *bk_lin_split(bk_linsolver *s)
{
    return s->ops == &bk_lin_bandsplit_ops ? &s->split : NULL;
}
