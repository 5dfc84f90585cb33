/* contact_read.c -- the contact interaction's record of the model file
 * (assembly/contact_model.h), written by gen/scene/contact.py:
 *   record contact
 *   contacts NPRIM NSET
 *   prim SHAPE p0 .. p14 MX MY MZ TX TY TZ OX OY OZ AMP BODY [X R0]
 *        (NPRIM times; enum bk_contact_shape, translation, rotation vector,
 *        pivot, amplitude, the rigid body's element or -1, and for a body its
 *        reference centre and rotation, 12 numbers)
 *   cset PRIM REACH STIFFNESS MU_S MU_K SLIP SAMPLES N e r ..  (NSET times: N elements, radii) */
#include <stdlib.h>

#include "assembly/contact_model.h"
#include "model/reader.h"

static void read_contacts(bk_reader *r, const bk_model *m, bk_contact_model *cm)
{
    rd_expect(r, "contacts");
    int np = rd_inum(r, "contact primitives", 0, MAXN), ns = rd_inum(r, "contact sets", 0, MAXN);
    if (r->failed)
        return;
    cm->prims = rd_xcalloc(r, (size_t)np, sizeof *cm->prims);
    cm->sets = rd_xcalloc(r, (size_t)ns, sizeof *cm->sets);
    if (r->failed)
        return;
    cm->nprim = np;
    for (int i = 0; i < np && !r->failed; ++i) {
        rd_expect(r, "prim");
        bk_contact_prim *p = &cm->prims[i];
        p->shape = rd_inum(r, "contact primitive shape", 0, BK_CONTACT_BOX);
        for (int k = 0; k < BK_CONTACT_MAXPRM; ++k)
            p->prm[k] = rd_num(r, "contact primitive parameter");
        for (int k = 0; k < 3; ++k)
            p->motion[k] = rd_num(r, "contact primitive motion");
        for (int k = 0; k < 3; ++k)
            p->turn[k] = rd_num(r, "contact primitive rotation");
        for (int k = 0; k < 3; ++k)
            p->pivot[k] = rd_num(r, "contact primitive pivot");
        p->amp = rd_inum(r, "contact primitive amplitude", -1, m->namp - 1);
        p->body = rd_inum(r, "contact primitive body", -1, m->nelem - 1);
        if (p->body >= 0)
            for (int k = 0; k < 12; ++k)
                p->body_ref[k] = rd_num(r, "contact primitive body placement");
    }
    for (int c = 0; c < ns && !r->failed; ++c) {
        bk_contact_set *set = &cm->sets[c];
        rd_expect(r, "cset");
        set->prim = rd_inum(r, "contact set primitive", 0, np - 1);
        set->shat = rd_num(r, "contact reach");
        set->kappa = rd_num(r, "contact stiffness");
        set->mu = rd_num(r, "contact static friction");
        set->mu_k = rd_num(r, "contact kinetic friction");
        set->slip = rd_num(r, "contact slip tolerance");
        set->nsample = rd_inum(r, "contact samples", 1, 64);
        int n = rd_inum(r, "contact elements", 1, m->nelem > 0 ? m->nelem : 1);
        if (r->failed)
            break;
        cm->nset = c + 1;                  /* (freed from here on) */
        if (!(set->shat > 0.0) || !(set->kappa > 0.0) || !(set->mu_k >= 0.0) || !(set->mu >= set->mu_k) ||
            !(set->slip > 0.0))
            rd_fail(r, "contact set %d: reach, stiffness and slip tolerance must be positive, 0 <= kinetic <= static "
                    "friction (%g, %g, %g, %g, %g)", c, set->shat, set->kappa, set->slip, set->mu_k, set->mu);
        set->elems = rd_xcalloc(r, (size_t)n, sizeof *set->elems);
        set->radius = rd_xcalloc(r, (size_t)n, sizeof *set->radius);
        if (r->failed)
            break;
        set->nelem = n;
        for (int i = 0; i < n && !r->failed; ++i) {
            set->elems[i] = rd_inum(r, "contact element", 0, m->nelem - 1);
            set->radius[i] = rd_num(r, "contact radius");
            if (!(set->radius[i] >= 0.0))
                rd_fail(r, "contact set %d: negative section radius %g", c, set->radius[i]);
        }
    }
}

bk_contact_model *bk_contact_model_read(const bk_model *m, const bk_model_record *rec, FILE *err)
{
    bk_reader r;
    if (rd_open_record(&r, rec, err) != 0)
        return NULL;
    bk_contact_model *cm = rd_xcalloc(&r, 1, sizeof *cm);
    if (cm)
        read_contacts(&r, m, cm);
    if (rd_close_record(&r) != 0) {
        bk_contact_model_free(cm);
        return NULL;
    }
    return cm;
}

void bk_contact_model_free(bk_contact_model *cm)
{
    if (!cm)
        return;
    for (int c = 0; c < cm->nset; ++c) {
        free(cm->sets[c].elems);
        free(cm->sets[c].radius);
    }
    free(cm->sets);
    free(cm->prims);
    free(cm);
}
