/* contact_output.c -- the contact interaction's outputs: contacts.csv rows,
 * summary.json "contact", and the state the tests read (contact_force.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/contact_impl.h"
#include "assembly/system.h"
#include "model/amplitude.h"
#include "base/csvrow.h"
#include "base/tables.h"
#include "base/clock.h"
#include "contact.h"

/* summary.json "contact": the smallest distance of a sample point to its
 * primitive, the largest penetration (0: none; a state through a surface is
 * refused), and per set its primitive, the force on the beams and the sample
 * points within the barrier. */
int contact_summary(void *self, const bk_system *s, const double *q, char *buf, size_t n)
{
    const bk_contact_model *cm = ((const contact_work *)self)->cm;
    double F[3 * 64], dmin;
    int nact[64];
    if (cm->nset > 64)
        return -1;
    bk_contact_state(s, q, F, nact, &dmin);
    int len = snprintf(buf, n, "{\"min_distance\": %.17g, \"max_penetration\": %.17g, \"sets\": [", dmin,
                       dmin < 0.0 ? -dmin : 0.0);
    for (int c = 0; c < cm->nset && len > 0 && (size_t)len < n; ++c)
        len += snprintf(buf + len, n - (size_t)len, "%s{\"primitive\": %d, \"force\": [%.17g, %.17g, %.17g], "
                        "\"active_points\": %d}", c ? ", " : "", cm->sets[c].prim, F[3 * c], F[3 * c + 1],
                        F[3 * c + 2], nact[c]);
    if (len > 0 && (size_t)len < n)
        len += snprintf(buf + len, n - (size_t)len, "]}");
    return len > 0 && (size_t)len < n ? 0 : -1;
}

/* contacts.csv: one row per sample point within a barrier's reach and output
 * step: step, time (or load factor), set, primitive, element, point, its
 * position, distance, the normal force, the tangential force, the friction
 * state (none, stick: slip since the last step below the tolerance, slip) and
 * the force on the beam there (N), and three empty columns (the second
 * beam's of beam-to-beam rows, contact_force.h).  contact_totals.csv: per output step and
 * set, the sums over its points: the normal force, the force on the beams,
 * the points within the barrier's reach, and the smallest distance. */
const bk_table_spec bk_contacts_csv =
    BK_TABLE("contacts.csv", "runs with `[[contact]]` or `[[beam_contact]]`",
             "step,time,set,primitive,element,point,x,y,z,distance,normal_force,tangential_force,state,fx,fy,fz,"
             "beam_b,element_b,segment_b\n");
static const bk_table_spec contact_totals_csv =
    BK_TABLE("contact_totals.csv", "runs with contact",
             "step,time,set,primitive,normal_force,fx,fy,fz,active_points,min_distance\n");

int contact_tables(void *self, const bk_system *s, bk_tables *ts, const char *dir, FILE *err)
{
    (void)s;
    contact_work *w = self;
    w->table = bk_tables_find(ts, bk_contacts_csv.name);
    if (!w->table)
        w->table = bk_tables_open(ts, dir, &bk_contacts_csv, 1, err);
    w->totals = bk_tables_open(ts, dir, &contact_totals_csv, 1, err);
    return w->table && w->totals ? 0 : -1;
}

typedef struct rows {
    contact_work *w;
    int step;
    double t;
    bk_rowqueue *rq;
    double *tot;                     /* [6 nset]: normal force, force (3), active points, smallest distance */
} rows;

static void row_point(void *ctx, point *pt)
{
    rows *rw = ctx;
    contact_work *w = rw->w;
    const bk_contact_set *set = pt->set;
    const double *g = pt->g;
    double b[3], fp[3], Kp[9], *tot = rw->tot + 6 * pt->c;
    const int rubs = set->mu > 0.0 && w->lam[pt->p] > 0.0;
    tot[5] = fmin(tot[5], pt->dist);
    if (!(pt->dist > 0.0) || !contact_acts(w, pt))
        return;
    double fn = 0.0;
    if (pt->dist < set->shat) {
        bk_contact_barrier(pt->dist, set->shat, b);
        fn = -pt->wl * b[1];
        tot[4] += 1.0;
    }
    tot[0] += fn;
    const double *zf = pt->roll ? pt->mpf.z : pt->mp.z;   /* friction's point: a rolling section's surface */
    contact_point_terms(w, set, pt->p, pt->wl, pt->mp.z, zf, g, pt->dist, fp, Kp);
    const double fg = -(fp[0] * g[1] + fp[1] * g[2] + fp[2] * g[3]);
    double ft2 = 0.0, slip2 = 0.0, fv[10], u[3], un = 0.0;
    const double *nl = w->nrm + 3 * pt->p;       /* the slip in the tangent plane, as friction measures it */
    for (int r = 0; r < 3; ++r)
        u[r] = zf[r] - w->xprev[3 * pt->p + r], un += u[r] * nl[r];
    for (int r = 0; r < 3; ++r) {                /* split in z, where the normal is g's gradient */
        const double tr = -fp[r] - fg * g[1 + r];
        ft2 += tr * tr;
        slip2 += (u[r] - un * nl[r]) * (u[r] - un * nl[r]);
    }
    bk_contact_chain(&pt->mp, fp, Kp, fv, NULL);
    bk_row r;
    bk_row_begin(&r, w->table, rw->rq);
    bk_row_int(&r, rw->step);
    bk_row_num(&r, rw->t);
    bk_row_int(&r, pt->c);
    bk_row_int(&r, set->prim);
    bk_row_int(&r, pt->e);
    bk_row_int(&r, pt->k);
    for (int d = 0; d < 3; ++d)
        bk_row_num(&r, pt->x[d]);
    bk_row_num(&r, pt->dist);
    bk_row_num(&r, fn);
    bk_row_num(&r, sqrt(ft2));
    bk_row_str(&r, !rubs ? "none" : sqrt(slip2) < set->slip ? "stick" : "slip");
    for (int d = 0; d < 3; ++d) {
        bk_row_num(&r, -fv[d]);
        tot[1 + d] -= fv[d];
    }
    for (int k = 0; k < 3; ++k)
        bk_row_str(&r, "");                      /* (beam_b, element_b, segment_b: a beam-to-beam row's) */
    bk_row_end(&r);
}

void contact_rows(void *self, const bk_system *s, int step, double t, const double *q, bk_rowqueue *rq)
{
    contact_work *w = self;
    const bk_contact_model *cm = w->cm;
    rows rw = {.w = w, .step = step, .t = t, .rq = rq, .tot = w->tot};
    if (!w->table || !w->totals)
        return;
    for (int c = 0; c < cm->nset; ++c) {
        memset(w->tot + 6 * c, 0, 5 * sizeof *w->tot);
        w->tot[6 * c + 5] = INFINITY;
    }
    contact_each_point(w, s, q, row_point, NULL, &rw);
    for (int c = 0; c < cm->nset; ++c) {
        const double *tot = w->tot + 6 * c;
        bk_row r;
        bk_row_begin(&r, w->totals, rq);
        bk_row_int(&r, step);
        bk_row_num(&r, t);
        bk_row_int(&r, c);
        bk_row_int(&r, cm->sets[c].prim);
        for (int k = 0; k < 4; ++k)
            bk_row_num(&r, tot[k]);
        bk_row_int(&r, (int)tot[4]);
        bk_row_num(&r, tot[5]);
        bk_row_end(&r);
    }
}

/* ---- ParaView: contacts_NNNNNN.vtp per frame, contacts.pvd ---- */

typedef struct frame_points {
    const contact_work *w;
    const bk_system *s;
    const double *q;
    FILE *f;
    int pass, n;                     /* pass 0: count; 1: positions; 2: forces; 3: normal forces; 4: states */
} frame_points;

static void frame_point(void *ctx, point *pt)
{
    frame_points *fp = ctx;
    if (!(pt->dist > 0.0) || !contact_acts(fp->w, pt))
        return;
    double fv[10], b[3], fn = 0.0;
    switch (fp->pass) {
    case 0:
        fp->n++;
        return;
    case 1:
        fprintf(fp->f, "%.9g %.9g %.9g\n", pt->x[0], pt->x[1], pt->x[2]);
        return;
    case 2:
        contact_point_force(fp->w, pt, fv, NULL);
        fprintf(fp->f, "%.9g %.9g %.9g\n", -fv[0], -fv[1], -fv[2]);
        return;
    case 3:
        if (pt->dist < pt->set->shat) {
            bk_contact_barrier(pt->dist, pt->set->shat, b);
            fn = -pt->wl * b[1];
        }
        fprintf(fp->f, "%.9g\n", fn);
        return;
    default:
        fprintf(fp->f, "%d\n", pt->c);
    }
}

static void frame_visit(void *ctx, int pass, FILE *f, int *n)
{
    frame_points *fp = ctx;
    fp->pass = pass, fp->f = f, fp->n = 0;
    contact_each_point(fp->w, fp->s, fp->q, frame_point, NULL, fp);
    if (pass == 0)
        *n = fp->n;
}

/* contacts_NNNNNN.vtp: the sample points within a barrier's reach or rubbing
 * as vertices, with the force on the beam there (N, a vector for glyphs),
 * the normal force and the contact set; contacts.pvd lists them with their
 * times (base/pointframes.h). */
int contact_frame(void *self, const bk_system *s, const char *dir, int frame, double t, const double *q, FILE *err)
{
    contact_work *w = self;
    frame_points fp = {.w = w, .s = s, .q = q};
    return bk_point_frames_write(&w->pf, dir, frame, t, frame_visit, &fp, err);
}

/* ---- the state for the outputs and the tests ---- */

typedef struct state {
    const contact_work *w;
    double *F, *min_distance;
    int *nactive;
} state;

static void state_point(void *ctx, point *pt)
{
    state *st = ctx;
    double fv[10];
    *st->min_distance = fmin(*st->min_distance, pt->dist);
    if (!(pt->dist > 0.0) || !contact_acts(st->w, pt))
        return;
    contact_point_force(st->w, pt, fv, NULL);
    for (int r = 0; r < 3; ++r)
        st->F[3 * pt->c + r] -= fv[r];       /* the force on the beam */
    if (st->nactive && pt->dist < pt->set->shat)
        st->nactive[pt->c]++;
}

void bk_contact_state(const bk_system *s, const double *q, double *F, int *nactive, double *min_distance)
{
    const contact_work *w = NULL;
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops == &bk_contact_ops)
            w = s->inter[k].self;
    const bk_contact_model *cm = w ? w->cm : NULL;
    *min_distance = INFINITY;
    for (int c = 0; cm && c < cm->nset; ++c) {
        F[3 * c] = F[3 * c + 1] = F[3 * c + 2] = 0.0;
        if (nactive)
            nactive[c] = 0;
    }
    state st = {.w = w, .F = F, .min_distance = min_distance, .nactive = nactive};
    if (w)
        contact_each_point(w, s, q, state_point, NULL, &st);
}
