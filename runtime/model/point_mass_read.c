/* point_mass_read.c -- the point-mass records of the model file (model.h
 * bk_point_mass), written by gen/scene/point_masses.py:
 *   point_masses N
 *   point_mass ELEMENT XI MASS   (N times) */
#include "model/reader.h"

void bk_model_read_point_masses(bk_reader *r, bk_model *m)
{
    rd_expect(r, "point_masses");
    int n = rd_inum(r, "point masses", 0, MAXN);
    if (r->failed || n == 0)
        return;
    m->pmass = rd_xcalloc(r, (size_t)n, sizeof *m->pmass);
    for (int i = 0; i < n && !r->failed; ++i) {
        bk_point_mass *p = &m->pmass[i];
        rd_expect(r, "point_mass");
        p->elem = rd_inum(r, "point mass element", 0, m->nelem - 1);
        p->xi = rd_num(r, "point mass xi");
        p->mass = rd_num(r, "point mass");
        if (!r->failed && !(p->mass > 0.0 && p->xi >= 0.0 && p->xi <= 1.0))
            rd_fail(r, "point mass %d: expected mass > 0 and 0 <= xi <= 1 (%g, %g)", i, p->mass, p->xi);
        m->npmass = i + 1;
    }
}
