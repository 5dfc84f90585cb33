/* stability_setup.c -- the stability checker's set-up: the multiplier
 * unknowns, the symmetric solver object of the Newton matrix's pattern
 * (linalg/symsolve.h) and every buffer of the checks (see stability.h). */
#include "solver/stability.h"

#include <stdlib.h>
#include <string.h>

#include "base/bigalloc.h"
#include "base/clock.h"

static int stability_init(bk_stability *st, const bk_system *s, bk_linsolver *ls)
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

    /* the symmetric part's L D L^T: a band in the band LU's order, or its own,
     * or the multipliers first then AMD (linalg/symsolve.h) */
    if (bk_sym_init(&st->sym, n, s->Ap, s->Ai, st->ismult, ls) != 0)
        return -1;
    /* (on huge pages, as the values now it takes turns with: bk_sym_keep_now
     * swaps them, so each check of a long band filled fresh memory -- a
     * 10,000-element run's checks took 5,100-5,900 page faults and 66-70 ms
     * each on small pages, 22-50 ms on huge ones) */
    st->prev = bk_big_malloc((size_t)(st->sym.nval > 0 ? st->sym.nval : 1) * sizeof *st->prev);
    return st->prev ? 0 : -1;
}

int bk_stability_init(bk_stability *st, const bk_system *s, bk_linsolver *ls)
{
    double t0 = bk_clock_s();
    int rc = stability_init(st, s, ls);
    st->t_spent += bk_clock_s() - t0;
    return rc;
}
