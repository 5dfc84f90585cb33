/* sym_setup.c -- the symmetric solver object's set-up and release: the band
 * plan of a narrow band (in the band LU's storage when it holds it), else the
 * symmetric pattern, its AMD order and LDL's symbolic analysis (see
 * symsolve.h). */
#include "linalg/symsolve.h"

#include <amd.h>
#include <ldl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/bigalloc.h"

/* The symmetric pattern of (Ap, Ai) with every diagonal (Bp, Bi) and for each
 * entry the positions of (i,j) and (j,i) in the matrix's values.  (j,i) is
 * found with a cursor per column i that only moves down: the columns j are
 * visited in increasing order and the rows of each column are sorted. */
static int sym_pattern(bk_symsolver *f)
{
    const int n = f->n, *Ap = f->Ap, *Ai = f->Ai;
    size_t N = (size_t)(n > 0 ? n : 1);
    long cap = (long)Ap[n] + n;
    f->Bp = malloc((N + 1) * sizeof *f->Bp);
    f->Bi = malloc((size_t)cap * sizeof *f->Bi);
    f->src = malloc((size_t)cap * sizeof *f->src);
    f->srct = malloc((size_t)cap * sizeof *f->srct);
    int *cur = malloc(N * sizeof *cur);
    if (!f->Bp || !f->Bi || !f->src || !f->srct || !cur) {
        free(cur);
        return -1;
    }
    for (int i = 0; i < n; ++i)
        cur[i] = Ap[i];
    long nz = 0;
    for (int j = 0; j < n; ++j) {
        f->Bp[j] = (int)nz;
        int have_diag = 0;
        for (int k = Ap[j]; k < Ap[j + 1]; ++k) {
            int i = Ai[k];
            if (!have_diag && i > j) {
                f->Bi[nz] = j;
                f->src[nz] = f->srct[nz] = -1;
                nz++;
                have_diag = 1;
            }
            have_diag |= i == j;
            while (cur[i] < Ap[i + 1] && Ai[cur[i]] < j)
                cur[i]++;
            f->Bi[nz] = i;
            f->src[nz] = k;
            f->srct[nz] = cur[i] < Ap[i + 1] && Ai[cur[i]] == j ? cur[i] : -1;
            nz++;
        }
        if (!have_diag) {
            f->Bi[nz] = j;
            f->src[nz] = f->srct[nz] = -1;
            nz++;
        }
    }
    f->Bp[n] = (int)nz;
    free(cur);
    return 0;
}

static void free_pattern(bk_symsolver *f)
{
    free(f->Bp);
    free(f->Bi);
    free(f->src);
    free(f->srct);
    f->Bp = f->Bi = f->src = f->srct = NULL;
}

/* A narrow band: the values now and the factor go into the band LU's storage
 * when it holds both (lu: the Newton solver's plan, or NULL), so that a
 * factorization touches no memory of its own (a page touched the first time
 * costs more than the whole band factorization of a small model: 1-10 us).
 * A long band (BK_BANDSPLIT_MIN unknowns and more) in two halves and a
 * separator: the split band LU's cut, and its blocks' storage for the halves'
 * factors (sp: the Newton solver's, or NULL: the cut in the middle, storage of
 * its own). */
static int use_band(bk_symsolver *f, bk_band *lu, bk_bandsplit *sp)
{
    size_t len = (size_t)f->band.ldab * (size_t)(f->n > 0 ? f->n : 1);
    f->use_band = 1;
    f->nval = (long)len;
    if (f->n >= BK_BANDSPLIT_MIN) {
        const int kd = f->band.kd;
        double *store[2] = {sp ? sp->blk[0].ab : NULL, sp ? sp->blk[1].ab : NULL};
        const long lens[2] = {sp ? (long)sp->blk[0].ldab * sp->blk[0].nb : 0,
                              sp ? (long)sp->blk[1].ldab * sp->blk[1].nb : 0};
        const int m = sp && sp->s == kd ? sp->m : (f->n - kd) / 2;
        const int rc = bk_symsplit_plan(&f->split, f->n, kd, f->band.ldab, m, sp && sp->s == kd ? store : NULL,
                                        lens);
        f->use_split = rc == 0;
        if (rc != 0 && f->n >= 2 * kd + 4)
            return -1;                   /* (out of memory; a band too short stays whole) */
        lu = NULL;
    }
    if (lu && lu->ab && (size_t)lu->ldab * (size_t)lu->n >= 2 * len + BK_BAND_LANES) {
        /* whole vectors from a 64-byte boundary, as the plan's own array */
        double *ab = lu->ab + (BK_BAND_LANES - (uintptr_t)lu->ab / sizeof *ab % BK_BAND_LANES) % BK_BAND_LANES;
        free(f->band.ab);
        f->band.ab = ab;
        f->now = ab + len;
        f->lender = lu;
    } else {
        f->now = bk_big_malloc(len * sizeof *f->now);   /* (a 10,000-element band: 23 MB) */
        if (!f->now)
            return -1;
    }
    f->scratch = f->band.ab;
    return 0;
}

/* The band L D L^T of the pattern (Ap, Ai) in `order` (NULL: its reverse
 * Cuthill-McKee order; kd its half bandwidth when known, else -1) when narrow
 * enough: 0 (its buffers made), 1 (not narrow: nothing kept), -1 (out of
 * memory). */
static int band_plan(bk_symsolver *f, const int *Ap, const int *Ai, const int *order, int kd, bk_band *lu,
                     bk_bandsplit *sp)
{
    int bp = bk_bandsym_plan(&f->band, f->n, Ap, Ai, order, kd, BK_BAND_MAX_STORAGE);
    if (bp < 0)
        return -1;
    if (bp == 0 && f->band.kd <= BK_BAND_MAX_WIDTH / 2)
        return use_band(f, lu, sp);
    if (bp == 0)
        bk_bandsym_free(&f->band);
    return 1;
}

/* Sparse: AMD on the symmetric pattern, the unknowns marked first first (each
 * keeps its AMD rank), LDL's symbolic analysis. */
static int sparse_plan(bk_symsolver *f, const char *first)
{
    const int n = f->n;
    size_t N = (size_t)(n > 0 ? n : 1);
    long cap = f->Bp[n];
    f->nval = cap;
    f->now = malloc((size_t)(cap > 0 ? cap : 1) * sizeof *f->now);
    f->scratch = malloc((size_t)(cap > 0 ? cap : 1) * sizeof *f->scratch);
    f->Lp = malloc((N + 1) * sizeof *f->Lp);
    f->Parent = malloc(N * sizeof(int));
    f->Lnz = malloc(N * sizeof(int));
    f->Flag = malloc(N * sizeof(int));
    f->Pattern = malloc(N * sizeof(int));
    f->P = malloc(N * sizeof(int));
    f->Pinv = malloc(N * sizeof(int));
    f->D = malloc(N * sizeof(double));
    f->Y = malloc(N * sizeof(double));
    f->z = malloc(N * sizeof(double));
    if (!f->now || !f->scratch || !f->Lp || !f->Parent || !f->Lnz || !f->Flag || !f->Pattern || !f->P ||
        !f->Pinv || !f->D || !f->Y || !f->z)
        return -1;
    int *perm = f->Pattern; /* scratch */
    double control[AMD_CONTROL], info[AMD_INFO];
    amd_defaults(control);
    if (amd_order(n, f->Bp, f->Bi, perm, control, info) < AMD_OK)
        for (int i = 0; i < n; ++i)
            perm[i] = i;
    int k = 0;
    for (int i = 0; i < n; ++i)
        if (first && first[perm[i]])
            f->P[k++] = perm[i];
    for (int i = 0; i < n; ++i)
        if (!(first && first[perm[i]]))
            f->P[k++] = perm[i];
    ldl_symbolic(n, f->Bp, f->Bi, f->Lp, f->Parent, f->Lnz, f->Flag, f->P, f->Pinv);
    long lnz = f->Lp[n];
    f->Li = malloc((size_t)(lnz > 0 ? lnz : 1) * sizeof(int));
    f->Lx = malloc((size_t)(lnz > 0 ? lnz : 1) * sizeof(double));
    return f->Li && f->Lx ? 0 : -1;
}

int bk_sym_init(bk_symsolver *f, int n, const int *Ap, const int *Ai, const char *first, bk_linsolver *ls)
{
    memset(f, 0, sizeof *f);
    f->n = n;
    f->Ap = Ap;
    f->Ai = Ai;
    /* A narrow band in the band LU's (reverse Cuthill-McKee) order, or in one
     * of the symmetric pattern's own (beams): a band L D L^T, any symmetric
     * order has the same inertia (Sylvester).  Else AMD on the whole pattern. */
    bk_band *lu = ls ? bk_lin_band(ls) : NULL;
    bk_bandsplit *sp = ls ? bk_lin_split(ls) : NULL;
    if (lu && (lu->n != n || lu->Ap != Ap || lu->Ai != Ai))
        lu = NULL;                       /* a plan of another pattern: its widths are not this one's */
    if (sp && (sp->n != n || sp->Ap != Ap || sp->Ai != Ai))
        sp = NULL;
    int bp = lu   ? band_plan(f, Ap, Ai, lu->perm, lu->kl > lu->ku ? lu->kl : lu->ku, lu, NULL)
             : sp ? band_plan(f, Ap, Ai, sp->perm, sp->kl > sp->ku ? sp->kl : sp->ku, NULL, sp)
                  : 1;
    if (bp <= 0)
        return bp;
    if (sym_pattern(f) != 0)
        return -1;
    if (!lu && !sp && (bp = band_plan(f, f->Bp, f->Bi, NULL, -1, NULL, NULL)) <= 0) {
        free_pattern(f);
        return bp;
    }
    return sparse_plan(f, first);
}

void bk_sym_free(bk_symsolver *f)
{
    free_pattern(f);
    free(f->Lp);
    free(f->Parent);
    free(f->Lnz);
    free(f->Flag);
    free(f->Pattern);
    free(f->P);
    free(f->Pinv);
    free(f->D);
    free(f->Y);
    free(f->z);
    free(f->Li);
    free(f->Lx);
    bk_symsplit_free(&f->split);         /* (its borrowed blocks stay the split band LU's) */
    if (f->lender)
        f->band.ab = NULL;               /* the band LU's */
    else if (f->use_band)
        free(f->now);
    if (!f->use_band) {
        free(f->now);
        free(f->scratch);
    }
    bk_bandsym_free(&f->band);
    memset(f, 0, sizeof *f);
}
