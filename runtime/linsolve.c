/* linsolve.c -- KLU wrapper: analyse once, factor per Newton iteration. */
#include "linsolve.h"

#include <string.h>

int bk_lin_init(bk_linsolver *s, int n, const int *Ap, const int *Ai)
{
    memset(s, 0, sizeof *s);
    s->n = n;
    s->Ap = Ap;
    s->Ai = Ai;
    klu_defaults(&s->common);
    s->sym = klu_analyze(n, (int *)Ap, (int *)Ai, &s->common);
    if (!s->sym)
        return BK_LIN_ERROR;
    s->nanalyze = 1;
    return BK_LIN_OK;
}

int bk_lin_factor(bk_linsolver *s, double *Ax)
{
    if (s->num)
        klu_free_numeric(&s->num, &s->common);
    s->num = klu_factor((int *)s->Ap, (int *)s->Ai, Ax, s->sym, &s->common);
    s->nfactor++;
    if (!s->num)
        return s->common.status == KLU_SINGULAR ? BK_LIN_SINGULAR : BK_LIN_ERROR;
    if (!klu_rcond(s->sym, s->num, &s->common))
        return BK_LIN_ERROR;
    s->rcond = s->common.rcond;
    if (!(s->rcond > 1e-300))
        return BK_LIN_SINGULAR;
    return BK_LIN_OK;
}

int bk_lin_solve(bk_linsolver *s, double *b)
{
    if (!s->num)
        return BK_LIN_ERROR;
    return klu_solve(s->sym, s->num, s->n, 1, b, &s->common) ? BK_LIN_OK : BK_LIN_ERROR;
}

void bk_lin_free(bk_linsolver *s)
{
    if (s->num)
        klu_free_numeric(&s->num, &s->common);
    if (s->sym)
        klu_free_symbolic(&s->sym, &s->common);
}
