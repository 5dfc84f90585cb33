/* constant_loads.c -- the dead loads of unit load factor (point forces,
 * gravity) and the moments on sections, whose direction follows the section
 * (system.h: bk_external_load, bk_gravity_load, bk_force_shape,
 * bk_assemble_follower). */
#include "assembly/system.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system_impl.h"

/* Position shape functions N of element e times a vector v into x:
 * x[dof of shape function a, component k] += c N[a] v[k]. */
static void scatter_shape(const bk_model *m, int e, const double *N, const double *v, double c, double *x)
{
    const int *d = m->elems[e].dofs;
    const bk_element *et = bk_elem_type(m, e);
    for (int a = 0; a < et->nshape; ++a)
        for (int k = 0; k < 3; ++k)
            x[d[et->shape_dof[a] + k]] += c * N[a] * v[k];
}


void bk_force_shape(const bk_model *m, const bk_force_load *f, double *N)
{
    const bk_element *et = bk_elem_type(m, f->elem);
    const double *g = m->geoms[m->elems[f->elem].geom];
    if (!f->section) {
        et->shape(g, f->xi, f->y, f->z, N);
        return;
    }
    /* uniform over the rectangle b x h: 3 x 3 Gauss points, exact for shape
     * functions up to degree 5 across the section */
    static const double gp[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
    static const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    double Na[BK_MAX_SHAPE];
    for (int a = 0; a < et->nshape; ++a)
        N[a] = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            et->shape(g, f->xi, 0.5 * g[BK_GEOM_B] * gp[i], 0.5 * g[BK_GEOM_H] * gp[j], Na);
            for (int a = 0; a < et->nshape; ++a)
                N[a] += gw[i] * gw[j] * Na[a];
        }
}

void bk_external_load(const bk_system *s, double *fext)
{
    const bk_model *m = s->m;
    double N[BK_MAX_SHAPE];
    memset(fext, 0, (size_t)m->ndof * sizeof *fext);
    for (int i = 0; i < m->nforce; ++i) {
        const bk_force_load *f = &m->forces[i];
        if (f->amp >= 0 || f->follower)
            continue;                  /* bk_assemble_loads (loads.h) */
        bk_force_shape(m, f, N);
        scatter_shape(m, f->elem, N, f->value, 1.0, fext);
    }
    if (m->has_gravity) {
        double *g = calloc((size_t)m->ndof, sizeof *g);
        if (g) {
            bk_gravity_load(s, g);
            for (int i = 0; i < m->ndof; ++i)
                fext[i] += g[i];
            free(g);
        }
    }
}

void bk_gravity_load(const bk_system *s, double *fg)
{
    const bk_model *m = s->m;
    double N[BK_MAX_SHAPE];
    memset(fg, 0, (size_t)m->ndof * sizeof *fg);
    if (m->has_gravity && !m->gravity_amp) {       /* with an amplitude: bk_assemble_loads */
        for (int e = 0; e < m->nelem; ++e) {
            bk_element_weight(m, e, N);
            scatter_shape(m, e, N, m->gravity, 1.0, fg);
        }
    }
}

void bk_assemble_follower(bk_system *s, const double *q, double lam, double *fint, double *Ax)
{
    const bk_model *m = s->m;
    double qe[BK_MAX_ELEMENT_DOF];
    for (int i = 0; i < m->nmoment; ++i) {
        const bk_moment_load *mo = &m->moments[i];
        if (mo->amp >= 0 || mo->follower)
            continue;                  /* bk_assemble_loads (loads.h) */
        const bk_elem *el = &m->elems[mo->elem];
        bk_gather(m, mo->elem, q, qe);
        bk_elem_type(m, mo->elem)->moment(m->geoms[el->geom], mo->xi, qe, mo->value, s->fe, s->Ke);
        bk_scatter(m, mo->elem, s->fe, -lam, fint);
        if (Ax)
            bk_scatter_matrix(s, mo->elem, s->Ke, -lam, Ax);
    }
}

/* Time factors of a rheonomic constraint: (C, S) = d^k/dt^k of (cos phi, sin phi). */
