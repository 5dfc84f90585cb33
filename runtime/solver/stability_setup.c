/* stability_setup.c -- the stability checker's set-up: the symmetric
 * pattern of the Newton matrix (or the band plan of a narrow band, in the
 * Newton solver's band LU storage when it holds it) and every buffer of the
 * checks (see stability.h). */
#include "solver/stability.h"

#include <amd.h>
#include <ldl.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"

/* The symmetric pattern of the Newton matrix with every diagonal (Bp, Bi) and
 * for each entry the positions of (i,j) and (j,i) in the system's values.
 * (j,i) is found with a cursor per column i that only moves down: the columns
 * j are visited in increasing order and the rows of each column are sorted. */
static int sym_pattern(bk_stability *st)
{
    const bk_system *s = st->s;
    int n = st->n;
    size_t N = (size_t)(n > 0 ? n : 1);
    long cap = s->nnz + n;
    st->Bp = malloc((N + 1) * sizeof *st->Bp);
    st->Bi = malloc((size_t)cap * sizeof *st->Bi);
    st->src = malloc((size_t)cap * sizeof *st->src);
    st->srct = malloc((size_t)cap * sizeof *st->srct);
    int *cur = malloc(N * sizeof *cur);
    if (!st->Bp || !st->Bi || !st->src || !st->srct || !cur) {
        free(cur);
        return -1;
    }
    for (int i = 0; i < n; ++i)
        cur[i] = s->Ap[i];
    long nz = 0;
    for (int j = 0; j < n; ++j) {
        st->Bp[j] = (int)nz;
        int have_diag = 0;
        for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k) {
            int i = s->Ai[k];
            if (!have_diag && i > j) {
                st->Bi[nz] = j;
                st->src[nz] = st->srct[nz] = -1;
                nz++;
                have_diag = 1;
            }
            have_diag |= i == j;
            while (cur[i] < s->Ap[i + 1] && s->Ai[cur[i]] < j)
                cur[i]++;
            st->Bi[nz] = i;
            st->src[nz] = k;
            st->srct[nz] = cur[i] < s->Ap[i + 1] && s->Ai[cur[i]] == j ? cur[i] : -1;
            nz++;
        }
        if (!have_diag) {
            st->Bi[nz] = j;
            st->src[nz] = st->srct[nz] = -1;
            nz++;
        }
    }
    st->Bp[n] = (int)nz;
    free(cur);
    return 0;
}

static void free_pattern(bk_stability *st)
{
    free(st->Bp);
    free(st->Bi);
    free(st->src);
    free(st->srct);
    st->Bp = st->Bi = st->src = st->srct = NULL;
}

/* A narrow band: the band LDL^T's buffers.  The matrix now and the factor are scratch of
 * one check: they go into the band LU's storage when it holds both (lu: the
 * Newton solver's plan, or NULL), so that a check touches no memory of its
 * own but the accepted matrix (a page touched the first time costs more than
 * the whole band factorization of a small model: 1-10 us). */
static int use_band(bk_stability *st, bk_band *lu)
{
    size_t len = (size_t)st->band.ldab * (size_t)(st->n > 0 ? st->n : 1);
    st->use_band = 1;
    st->bprev = malloc(len * sizeof *st->bprev);
    if (!st->bprev)
        return -1;
    if (lu && lu->ab && (size_t)lu->ldab * (size_t)lu->n >= 2 * len + BK_BAND_LANES) {
        /* whole vectors from a 64-byte boundary, as the plan's own array */
        double *ab = lu->ab + (BK_BAND_LANES - (uintptr_t)lu->ab / sizeof *ab % BK_BAND_LANES) % BK_BAND_LANES;
        free(st->band.ab);
        st->band.ab = ab;
        st->bnow = ab + len;
        st->lender = lu;
    } else {
        st->bnow = malloc(len * sizeof *st->bnow);
        if (!st->bnow)
            return -1;
    }
    return 0;
}

/* The band LDL^T of the pattern (Ap, Ai) in `order` (NULL: its reverse
 * Cuthill-McKee order; kd its half bandwidth when known, else -1) when narrow
 * enough: 0 (its buffers made), 1 (not narrow: nothing kept), -1 (out of
 * memory). */
static int band_plan(bk_stability *st, const int *Ap, const int *Ai, const int *order, int kd, bk_band *lu)
{
    int bp = bk_bandsym_plan(&st->band, st->n, Ap, Ai, order, kd, BK_BAND_MAX_STORAGE);
    if (bp < 0)
        return -1;
    if (bp == 0 && st->band.kd <= BK_BAND_MAX_WIDTH / 2)
        return use_band(st, lu);
    if (bp == 0)
        bk_bandsym_free(&st->band);
    return 1;
}

static int stability_init(bk_stability *st, const bk_system *s, bk_band *lu)
{
    memset(st, 0, sizeof *st);
    st->s = s;
    int n = st->n = s->neq;
    const bk_model *m = s->m;
    size_t N = (size_t)(n > 0 ? n : 1);
    st->ismult = calloc(N, 1);
    if (!st->ismult)
        return -1;

    /* Multiplier unknowns: the constraint rows and the element-internal
     * multipliers. */
    for (int i = s->nfree; i < n; ++i)
        st->ismult[i] = 1;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_element *et = m->pairs[el->pair]->element;
        for (int f = 0; f < et->nfield; ++f)
            if (et->field_role[f] == BK_FIELD_MULTIPLIER)
                for (int k = 0; k < et->field_dim[f]; ++k) {
                    int qe = s->eq[el->dofs[et->field_dof[f] + k]];
                    if (qe >= 0)
                        st->ismult[qe] = 1;
                }
    }
    for (int i = 0; i < n; ++i)
        st->nmult += st->ismult[i];
    st->dcross = malloc(4 * N * sizeof *st->dcross);
    if (!st->dcross)
        return -1;
    st->dchk = st->dcross + 2 * N;
    st->dacc = st->dchk + N;
    if (m->stat.eigenvalues) {
        st->x = malloc(N * sizeof(double));
        st->y = malloc(N * sizeof(double));
        st->z = malloc(N * sizeof(double));
        st->xmax = malloc(N * sizeof(double));
        if (!st->x || !st->y || !st->z || !st->xmax)
            return -1;
    }

    /* A narrow band in the band LU's (reverse Cuthill-McKee) order, or in
     * one of the symmetric pattern's own (beams): a band LDL^T, any symmetric
     * order has the same inertia (Sylvester).  Else AMD on the whole pattern,
     * then the multipliers first (each keeps its AMD rank). */
    if (lu && (lu->n != n || lu->Ap != s->Ap || lu->Ai != s->Ai))
        lu = NULL;                       /* a plan of another pattern: its widths are not this one's */
    int bp = lu ? band_plan(st, s->Ap, s->Ai, lu->perm, lu->kl > lu->ku ? lu->kl : lu->ku, lu) : 1;
    if (bp <= 0)
        return bp;
    if (sym_pattern(st) != 0)
        return -1;
    if (!lu && (bp = band_plan(st, st->Bp, st->Bi, NULL, -1, NULL)) <= 0) {
        free_pattern(st);
        return bp;
    }
    long cap = st->Bp[n];
    st->Bx = malloc((size_t)cap * sizeof *st->Bx);
    st->Bprev = malloc((size_t)cap * sizeof *st->Bprev);
    st->Bnow = malloc((size_t)cap * sizeof *st->Bnow);
    st->Lp = malloc((N + 1) * sizeof *st->Lp);
    st->Parent = malloc(N * sizeof(int));
    st->Lnz = malloc(N * sizeof(int));
    st->Flag = malloc(N * sizeof(int));
    st->Pattern = malloc(N * sizeof(int));
    st->P = malloc(N * sizeof(int));
    st->Pinv = malloc(N * sizeof(int));
    st->D = malloc(N * sizeof(double));
    st->Y = malloc(N * sizeof(double));
    if (!st->Bx || !st->Bprev || !st->Bnow || !st->Lp || !st->Parent || !st->Lnz || !st->Flag || !st->Pattern ||
        !st->P || !st->Pinv || !st->D || !st->Y)
        return -1;
    int *perm = st->Pattern; /* scratch */
    double control[AMD_CONTROL], info[AMD_INFO];
    amd_defaults(control);
    if (amd_order(n, st->Bp, st->Bi, perm, control, info) < AMD_OK)
        for (int i = 0; i < n; ++i)
            perm[i] = i;
    int k = 0;
    for (int i = 0; i < n; ++i)
        if (st->ismult[perm[i]])
            st->P[k++] = perm[i];
    for (int i = 0; i < n; ++i)
        if (!st->ismult[perm[i]])
            st->P[k++] = perm[i];
    ldl_symbolic(n, st->Bp, st->Bi, st->Lp, st->Parent, st->Lnz, st->Flag, st->P, st->Pinv);
    long lnz = st->Lp[n];
    st->Li = malloc((size_t)(lnz > 0 ? lnz : 1) * sizeof(int));
    st->Lx = malloc((size_t)(lnz > 0 ? lnz : 1) * sizeof(double));
    return st->Li && st->Lx ? 0 : -1;
}

/* The multipliers' regularization -delta_i of the method (stability.h):
 * b2[j] is the sum of the squares of column j's off-diagonal entries, kmax
 * the largest diagonal magnitude of the other unknowns. */

int bk_stability_init(bk_stability *st, const bk_system *s, bk_band *lu)
{
    double t0 = bk_clock_s();
    int rc = stability_init(st, s, lu);
    st->t_spent += bk_clock_s() - t0;
    return rc;
}
