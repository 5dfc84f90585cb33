/* lin_band.c -- the band LU backend of the linear solver object (see
 * linsolve.h, bandlu.h). */
#include "linalg/linsolve.h"

int bk_lin_band_status(bk_linsolver *s, int rc, double rcond)
{
    s->nfactor++;
    if (s->nfactor == 1)
        s->nfull = 1;                    /* the only one that sets up storage (at init) */
    s->rcond = rc == 0 ? rcond : 0.0;
    s->rcond_factor = s->rcond;
    if (rc == 2)
        return BK_LIN_ERROR;
    return rc == 1 || !(s->rcond > 1e-300) ? BK_LIN_SINGULAR : BK_LIN_OK;
}

static int band_factor(bk_linsolver *s, double *Ax)
{
    const int rc = bk_band_factor(&s->band, Ax);       /* (before its rcond is read) */
    return bk_lin_band_status(s, rc, s->band.rcond);
}

static int band_solve(bk_linsolver *s, double *b)
{
    if (!(s->rcond > 1e-300))
        return BK_LIN_ERROR;
    bk_band_solve(&s->band, b);
    return BK_LIN_OK;
}

static int band_factor_solve(bk_linsolver *s, double *Ax, double *b)
{
    const int rc = bk_band_factor_solve(&s->band, Ax, b);
    return bk_lin_band_status(s, rc, s->band.rcond);
}

static void band_free(bk_linsolver *s)
{
    bk_band_free(&s->band);
}

const bk_lin_ops bk_lin_band_ops = {"band LU", band_factor, band_solve, band_factor_solve, band_free};

int bk_lin_band_init(bk_linsolver *s, int required)
{
    int bp = bk_band_plan(&s->band, s->n, s->Ap, s->Ai, required ? (1L << 40) : BK_BAND_MAX_STORAGE);
    if (bp < 0)
        return BK_LIN_ERROR;
    if (bp == 0 && (required || s->band.kl + s->band.ku <= BK_BAND_MAX_WIDTH)) {
        /* a long band: two halves on two threads (bandsplit.h), whatever the
         * thread count, so that the bits do not depend on it */
        if (s->n >= BK_BANDSPLIT_MIN && bk_lin_bandsplit_init(s) == BK_LIN_OK)
            return BK_LIN_OK;
        s->ops = &bk_lin_band_ops;
        s->nanalyze = 1;
        return BK_LIN_OK;
    }
    if (bp == 0)
        bk_band_free(&s->band);
    return required ? BK_LIN_ERROR : -1;
}
