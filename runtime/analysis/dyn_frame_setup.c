/* dyn_frame_setup.c -- the rotating frame of a dynamic run made from its
 * constraint (dynamic.frame, dyn_frame.h): the constraint's angle, axis and
 * point, the coordinate blocks the frame turns, the refusals, the frame's
 * memory. */
#include "analysis/dyn_frame.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/amplitude.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The constraint's angle theta(t) and its k-th derivative (as the constraint's
 * rows evaluate it: assembly/constraints.c), the derivatives from the right (an
 * amplitude's kinks and first knot have none: amplitude.h; the run goes forward,
 * and a spin-up starts with the rate after t = 0). */
double bk_frame_angle(const bk_dyn_frame *c, double t, int k)
{
    if (k > 0)
        t = nextafter(t, INFINITY);
    const double w = 2.0 * M_PI * c->freq;
    double th = k == 0 ? c->rate * t + c->amp * sin(w * t) : k == 1 ? c->rate + c->amp * w * cos(w * t)
                                                                   : -c->amp * w * w * sin(w * t);
    if (c->ampl)
        th += c->scale * bk_amp_eval(c->ampl, t, k);
    return th;
}

/* The block kind of an element field: 1 position, 2 a vector that turns (a
 * gradient), 3 a quaternion, 0 a coordinate the frame does not turn. */
int bk_frame_field_kind(const bk_element *et, int k)
{
    const bk_field_role r = et->field_role[k];
    if (et->field_dim[k] == 3 && r == BK_FIELD_POSITION)
        return 1;
    if (et->field_dim[k] == 3 && bk_field_is_gradient(r))
        return 2;
    return et->field_dim[k] == 4 && r == BK_FIELD_QUATERNION ? 3 : 0;
}

void bk_frame_free(bk_dyn_frame *f)
{
    double **p[] = {&f->qa, &f->qda, &f->qdda, &f->nua, &f->y, &f->z, &f->g, &f->Me, &f->W, &f->S};
    for (size_t i = 0; i < sizeof p / sizeof *p; ++i) {
        free(*p[i]);
        *p[i] = NULL;
    }
    free(f->block), free(f->rowof);
    f->block = NULL, f->rowof = NULL;
}

/* The axis of linear rows turning a quaternion (p(phi) = (cos phi/2, sin phi/2 n) p0:
 * rc = p0, rs = (0, n) p0) or a vector (v(phi) = ... + (v0 - (n.v0) n) cos phi + n x v0
 * sin phi) of the block b; 0, or -1 when they give none. */
static int rows_axis(bk_dyn_frame *f, const bk_model *m, const int *bl)
{
    double rc[4], rs[4], a[3];
    const int dim = bl[0] == 3 ? 4 : 3;
    for (int i = 0; i < dim; ++i)
        rc[i] = m->lincons[f->rowof[bl[1 + i]]].rc, rs[i] = m->lincons[f->rowof[bl[1 + i]]].rs;
    if (dim == 4)                       /* vec(rs conj(rc)) / |rc|^2 */
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3, k = (i + 2) % 3;
            a[i] = -rs[0] * rc[1 + i] + rc[0] * rs[1 + i] - (rs[1 + j] * rc[1 + k] - rs[1 + k] * rc[1 + j]);
        }
    else
        for (int i = 0; i < 3; ++i)
            a[i] = rc[(i + 1) % 3] * rs[(i + 2) % 3] - rc[(i + 2) % 3] * rs[(i + 1) % 3];
    const double an = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(an > 1e-12))
        return -1;
    for (int i = 0; i < 3; ++i)
        f->n[i] = a[i] / an;
    return 0;
}

/* The coordinate blocks the frame turns (each once), the axis of linear rows;
 * refuses blocks held off the axis or turned by the rows in part. */
static int frame_blocks(bk_dyn_frame *f, const bk_system *s, char *msg, size_t n)
{
    const bk_model *m = s->m;
    char *seen = calloc((size_t)m->ndof + 1, 1);
    if (!seen)
        return snprintf(msg, n, "out of memory"), -1;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = bk_elem_type(m, e);
        for (int k = 0; k < et->nfield; ++k) {
            const int kind = bk_frame_field_kind(et, k), *d = m->elems[e].dofs + et->field_dof[k];
            if (!kind || seen[d[0]])
                continue;
            seen[d[0]] = 1;
            int *bl = f->block[f->nblock++];
            bl[0] = kind;
            for (int i = 0; i < (kind == 3 ? 4 : 3); ++i)
                bl[1 + i] = d[i];
        }
    }
    free(seen);
    int axis = f->joint;                /* (a joint: from its ground side) */
    for (int b = 0; b < f->nblock && !axis; ++b)
        if (f->block[b][0] > 1 && f->rowof[f->block[b][1]] >= 0)
            axis = rows_axis(f, m, f->block[b]) == 0;
    if (!axis)
        return snprintf(msg, n, "dynamic.frame = \"%s\": the constraint turns no nodal rotation or vector (its "
                        "axis)", m->dyn.frame), -1;
    const double tol = 1e-9 * fmax(1.0, m->length_scale);
    for (int b = 0; b < f->nblock; ++b) {
        const int *bl = f->block[b], dim = bl[0] == 3 ? 4 : 3;
        int held = 0, rows = 0;
        double y[4];
        for (int i = 0; i < dim; ++i)
            held += s->eq[bl[1 + i]] < 0, rows += f->rowof[bl[1 + i]] >= 0;
        for (int i = 0; i < dim; ++i)
            y[i] = m->q0[bl[1 + i]] - (bl[0] == 1 ? f->c[i] : 0.0);
        const double *c = f->n, ax[3] = {c[1] * y[2] - c[2] * y[1], c[2] * y[0] - c[0] * y[2], c[0] * y[1] - c[1] * y[0]};
        if ((rows && rows != dim) || (held && (bl[0] == 3 || held != dim || sqrt(ax[0] * ax[0] + ax[1] * ax[1] +
                                                                                   ax[2] * ax[2]) > tol)))
            return snprintf(msg, n, "dynamic.frame = \"%s\": DOF %d is %s; in the rotating frame only the "
                            "frame's own constraint may hold a coordinate, and whole (on the axis)", m->dyn.frame,
                            bl[1], rows ? "turned by the constraint only in part" : "held off the frame's axis"),
                   -1;
    }
    return 0;
}

/* The drive, axis and point of the frame from its constraint: a joint to the
 * ground (the point and axis of the ground's side), or linear rows (the node,
 * the axis of a block they turn); 0, or -1 with msg. */
static int frame_constraint(bk_dyn_frame *f, const bk_system *s, char *msg, size_t n)
{
    const bk_model *m = s->m;
    const bk_reaction *rc = f->rc;
    for (size_t i = 0; i < (size_t)m->ndof; ++i)
        f->rowof[i] = -1;
    if (rc->nlcon >= 0) {
        const bk_nlcon *jc = &m->nlcons[rc->nlcon];
        for (int i = 7; i < 14; ++i)
            if (jc->dof[i] >= 0)
                return snprintf(msg, n, "dynamic.frame = \"%s\": the constraint joins two parts; expected one to "
                                "the ground", m->dyn.frame), -1;
        f->joint = 1, f->row0 = s->jrow[rc->nlcon];
        f->rate = jc->rate, f->amp = jc->amp, f->freq = jc->freq, f->scale = jc->scale, f->ampl = jc->dampl;
        const double *ax = jc->prm + 21, an = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
        for (int i = 0; i < 3; ++i)     /* the ground's joint point and third axis */
            f->c[i] = jc->x0[7 + i], f->n[i] = ax[i] / an;
        return 0;
    }
    const bk_lincon *drive = NULL;
    for (int k = 0; k < rc->nlin; ++k) {
        const bk_lincon *lc = &m->lincons[rc->lin[k]];
        if (lc->nterm != 1 || lc->c0[0] != 1.0 || lc->cc[0] != 0.0 || lc->cs[0] != 0.0)
            return snprintf(msg, n, "dynamic.frame = \"%s\": its row %d is not one coordinate's prescribed value",
                            m->dyn.frame, rc->lin[k]), -1;
        f->rowof[lc->dof[0]] = rc->lin[k];
        if (!drive && lc->kappa != 0.0)
            drive = lc;
    }
    if (!drive)
        return snprintf(msg, n, "dynamic.frame = \"%s\": the constraint turns no coordinate", m->dyn.frame), -1;
    f->rate = drive->rate, f->amp = drive->amp, f->freq = drive->freq, f->scale = drive->angle;
    f->ampl = drive->ampl;
    bk_eval_point(m, m->q0, rc->elem, rc->xi, f->c, NULL);
    return 0;
}

int bk_frame_init(bk_dyn_frame *f, const bk_system *s, char *msg, size_t n)
{
    const bk_model *m = s->m;
    memset(f, 0, sizeof *f);
    if (!bk_model_in_time(m) || strcmp(m->dyn.frame, "none") == 0 || m->dyn.frame[0] == 0)
        return 0;
    for (int c = 0; c < m->nreaction && !f->rc; ++c)
        if (strcmp(m->reactions[c].name, m->dyn.frame) == 0)
            f->rc = &m->reactions[c];
    if (!f->rc || strcmp(f->rc->type, "prescribed_rotation") != 0)
        return snprintf(msg, n, "dynamic.frame = \"%s\": expected the name of a prescribed_rotation to the ground",
                        m->dyn.frame), -1;
    const size_t nd = (size_t)m->ndof, md = (size_t)s->maxdof, nc = (size_t)(s->ncon ? s->ncon : 1);
    f->block = malloc((nd / 3 + 1) * sizeof *f->block);
    f->rowof = malloc(nd * sizeof *f->rowof);
    f->qa = malloc(nd * sizeof *f->qa), f->qda = malloc(nd * sizeof *f->qa), f->qdda = malloc(nd * sizeof *f->qa);
    f->nua = malloc(nc * sizeof *f->nua);
    f->y = malloc(md * sizeof *f->y), f->z = malloc(md * sizeof *f->y), f->g = malloc(md * sizeof *f->y);
    f->Me = malloc(md * md * sizeof *f->Me), f->W = malloc(md * md * sizeof *f->Me);
    f->S = malloc(md * md * sizeof *f->Me);
    if (!f->block || !f->rowof || !f->qa || !f->qda || !f->qdda || !f->nua || !f->y || !f->z || !f->g || !f->Me ||
        !f->W || !f->S)
        return snprintf(msg, n, "out of memory"), -1;
    if (frame_constraint(f, s, msg, n) != 0 || frame_blocks(f, s, msg, n) != 0)
        return -1;
    f->th0 = bk_frame_angle(f, 0.0, 0);
    f->on = 1;
    bk_frame_at(f, 0.0);
    return 0;
}
