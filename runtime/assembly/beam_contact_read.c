/* beam_contact_read.c -- the beam contact interaction's record of the model
 * file (assembly/beam_contact_model.h), written by gen/scene/beam_contact.py:
 *   record beam_contact
 *   beam_contacts NSET
 *   bcset REACH STIFFNESS MU_S MU_K SLIP SAMPLES EXCLUDE SELF NCHAIN   (NSET times, each followed by)
 *   chain N e r s0 ..                                           (NCHAIN times: N elements in order) */
#include <stdlib.h>

#include "assembly/beam_contact_model.h"
#include "model/reader.h"

static void read_set(bk_reader *r, const bk_model *m, bk_beam_contact_set *set, int c)
{
    rd_expect(r, "bcset");
    set->shat = rd_num(r, "beam contact reach");
    set->kappa = rd_num(r, "beam contact stiffness");
    set->mu = rd_num(r, "beam contact friction");
    set->mu_k = rd_num(r, "beam contact kinetic friction");
    set->slip = rd_num(r, "beam contact slip tolerance");
    set->nsample = rd_inum(r, "beam contact samples", 2, 64);
    set->exclude = rd_num(r, "beam contact exclusion");
    set->self = rd_inum(r, "beam contact self flag", 0, 1);
    int nc = rd_inum(r, "beam contact beams", 1, m->nelem > 0 ? m->nelem : 1);
    if (r->failed)
        return;
    if (!(set->shat > 0.0) || !(set->kappa > 0.0) || !(set->mu_k >= 0.0) || !(set->mu >= set->mu_k) ||
        !(set->slip > 0.0) || !(set->exclude >= 0.0))
        rd_fail(r, "beam contact set %d: reach, stiffness and slip tolerance must be positive, 0 <= kinetic <= "
                "static friction, exclusion >= 0 (%g, %g, %g, %g, %g, %g)", c, set->shat, set->kappa, set->slip,
                set->mu_k, set->mu, set->exclude);
    set->chain_off = rd_xcalloc(r, (size_t)nc + 1, sizeof *set->chain_off);
    set->elems = rd_xcalloc(r, (size_t)m->nelem + 1, sizeof *set->elems);
    set->radius = rd_xcalloc(r, (size_t)m->nelem + 1, sizeof *set->radius);
    set->s0 = rd_xcalloc(r, (size_t)m->nelem + 1, sizeof *set->s0);
    for (int k = 0; k < nc && !r->failed; ++k) {
        rd_expect(r, "chain");
        int n = rd_inum(r, "beam contact chain elements", 1, m->nelem - set->nelem);
        for (int i = 0; i < n && !r->failed; ++i) {
            set->elems[set->nelem] = rd_inum(r, "beam contact element", 0, m->nelem - 1);
            set->radius[set->nelem] = rd_num(r, "beam contact radius");
            set->s0[set->nelem] = rd_num(r, "beam contact arc length");
            if (!(set->radius[set->nelem] >= 0.0))
                rd_fail(r, "beam contact set %d: negative section radius %g", c, set->radius[set->nelem]);
            set->nelem++;
        }
        set->nchain = k + 1;
        set->chain_off[k + 1] = set->nelem;
    }
}

static void read_sets(bk_reader *r, const bk_model *m, bk_beam_contact_model *bm)
{
    rd_expect(r, "beam_contacts");
    int ns = rd_inum(r, "beam contact sets", 0, MAXN);
    if (r->failed || ns == 0)
        return;
    /* the Newton matrix's pattern grows as contacts are found (assembly/
     * beam_contact.h): dynamics and the static analysis without stability
     * checks follow it; the others keep arrays made from the first pattern */
    if (!bk_model_in_time(m) && (!bk_model_in_load(m) || m->stat.stability)) {
        rd_fail(r, "beam contact is available in dynamics and in static analyses with stability = false only");
        return;
    }
    bm->sets = rd_xcalloc(r, (size_t)ns, sizeof *bm->sets);
    for (int c = 0; c < ns && !r->failed; ++c) {
        bm->nset = c + 1;                  /* (freed from here on) */
        read_set(r, m, &bm->sets[c], c);
    }
}

bk_beam_contact_model *bk_beam_contact_model_read(const bk_model *m, const bk_model_record *rec, FILE *err)
{
    bk_reader r;
    if (rd_open_record(&r, rec, err) != 0)
        return NULL;
    bk_beam_contact_model *bm = rd_xcalloc(&r, 1, sizeof *bm);
    if (bm)
        read_sets(&r, m, bm);
    if (rd_close_record(&r) != 0) {
        bk_beam_contact_model_free(bm);
        return NULL;
    }
    return bm;
}

void bk_beam_contact_model_free(bk_beam_contact_model *bm)
{
    if (!bm)
        return;
    for (int c = 0; c < bm->nset; ++c) {
        free(bm->sets[c].chain_off);
        free(bm->sets[c].elems);
        free(bm->sets[c].radius);
        free(bm->sets[c].s0);
    }
    free(bm->sets);
    free(bm);
}
