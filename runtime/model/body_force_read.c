/* body_force_read.c -- the records of dead forces at body points off the centre
 * of mass (model.h bk_body_force), written by gen/scene/body_loads.py:
 *   body_forces N
 *   body_force ELEMENT CX CY CZ FX FY FZ AMP   (N times; C in the body axes, F global) */
#include "model/reader.h"

void bk_model_read_body_forces(bk_reader *r, bk_model *m)
{
    rd_expect(r, "body_forces");
    int n = rd_inum(r, "body forces", 0, MAXN);
    if (r->failed || n == 0)
        return;
    m->bforces = rd_xcalloc(r, (size_t)n, sizeof *m->bforces);
    for (int i = 0; i < n && !r->failed; ++i) {
        bk_body_force *f = &m->bforces[i];
        rd_expect(r, "body_force");
        f->elem = rd_inum(r, "body force element", 0, m->nelem - 1);
        for (int k = 0; k < 3; ++k)
            f->c[k] = rd_num(r, "body force point");
        for (int k = 0; k < 3; ++k)
            f->value[k] = rd_num(r, "body force value");
        f->amp = rd_inum(r, "body force amplitude", -1, m->namp - 1);
        if (!r->failed && m->pairs[m->elems[f->elem].pair]->element->ndof != 7)
            rd_fail(r, "body force %d: element %d is not a rigid body", i, f->elem);
        m->nbforce = i + 1;
    }
}
