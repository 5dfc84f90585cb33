/* linsolve.c -- the linear solver of the Newton systems: a band LU (bandlu.c) for narrow bands, else KLU: analyse once, factor once, then refactor.
 *
 * The first numeric factorization (klu_factor) chooses the pivots and
 * allocates the LU factors.  Later factorizations on the same pattern reuse
 * both through klu_refactor, which allocates nothing; only when the old
 * pivot sequence has become poor for the new values (refactor fails, or the
 * reciprocal pivot growth / condition estimate collapses) is a fresh
 * klu_factor done.
 */
#include "linalg/linsolve.h"

#include <string.h>

/* A refactorization is kept when its condition estimate is no worse than this
 * fraction of the one of the last full factorization, and that one was not
 * poor (below BK_RCOND_POOR: pivots chosen at a bad state, e.g. a diverging
 * Newton iterate): else the pivots are chosen again for the new values (every
 * time, while the matrix itself stays that ill-conditioned). */
#define BK_REFACTOR_RCOND_DROP 1e-3
#define BK_RCOND_POOR 1e-12

int bk_lin_init(bk_linsolver *s, int n, const int *Ap, const int *Ai)
{
    memset(s, 0, sizeof *s);
    s->n = n;
    s->Ap = Ap;
    s->Ai = Ai;
    klu_defaults(&s->common);
    int bp = bk_band_plan(&s->band, n, Ap, Ai, BK_BAND_MAX_STORAGE);
    if (bp < 0)
        return BK_LIN_ERROR;
    if (bp == 0 && s->band.kl + s->band.ku <= BK_BAND_MAX_WIDTH) {
        s->use_band = 1;
        s->nanalyze = 1;
        return BK_LIN_OK;
    }
    if (bp == 0)
        bk_band_free(&s->band);
    s->sym = klu_analyze(n, (int *)Ap, (int *)Ai, &s->common);
    if (!s->sym)
        return BK_LIN_ERROR;
    s->nanalyze = 1;
    return BK_LIN_OK;
}

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

/* Counters and status after a band factorization that returned rc. */
static int band_status(bk_linsolver *s, int rc)
{
    s->nfactor++;
    if (s->nfactor == 1)
        s->nfull = 1;                    /* the only one that sets up storage (in bk_lin_init) */
    s->rcond = rc == 0 ? s->band.rcond : 0.0;
    s->rcond_factor = s->rcond;
    if (rc == 2)
        return BK_LIN_ERROR;
    return rc == 1 || !(s->rcond > 1e-300) ? BK_LIN_SINGULAR : BK_LIN_OK;
}

int bk_lin_factor(bk_linsolver *s, double *Ax)
{
    if (s->use_band)
        return band_status(s, bk_band_factor(&s->band, Ax));
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

int bk_lin_solve(bk_linsolver *s, double *b)
{
    if (s->use_band) {
        if (!(s->rcond > 1e-300))
            return BK_LIN_ERROR;
        bk_band_solve(&s->band, b);
        return BK_LIN_OK;
    }
    if (!s->num)
        return BK_LIN_ERROR;
    return klu_solve(s->sym, s->num, s->n, 1, b, &s->common) ? BK_LIN_OK : BK_LIN_ERROR;
}

int bk_lin_factor_solve(bk_linsolver *s, double *Ax, double *b)
{
    if (s->use_band)
        return band_status(s, bk_band_factor_solve(&s->band, Ax, b));
    int st = bk_lin_factor(s, Ax);
    return st != BK_LIN_OK ? st : bk_lin_solve(s, b);
}

void bk_lin_free(bk_linsolver *s)
{
    bk_band_free(&s->band);
    if (s->num)
        klu_free_numeric(&s->num, &s->common);
    if (s->sym)
        klu_free_symbolic(&s->sym, &s->common);
}
