/* spring.c -- the spring interaction: linear springs between two points of the
 * model (beam points, bodies' centres) or between a point and a fixed point
 * (the model's record "spring", written by gen/scene/spring.py).
 *
 * A spring's ends are x_a = sum_i N_i(xi_a) r_i over element a's position
 * shape functions (bk_element shape, shape_dof), and x_b likewise or fixed.
 * With d = x_a - x_b, l = |d|, its energy k/2 (l - l0)^2 gives the force on a
 *     f = dE/dx_a = k (1 - l0 / l) d                          (on b: -f)
 * and the Hessian in d
 *     H = k [(1 - l0 / l) I + (l0 / l) u u^T],   u = d / l,
 * exact (tests/test_spring.py checks both against differences of the energy);
 * the element blocks get N_i N_j H (and -N_i N_j H between a and b, whose
 * coupling blocks the pattern gets once, at set-up).  A spring of positive
 * rest length whose ends meet has no direction: assemble returns -1 there.
 * Outputs: springs.csv (per output step and spring: its length, extension and
 * tension), summary.json "springs" (the final ones). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/interaction.h"
#include "assembly/system.h"
#include "base/csvrow.h"
#include "base/tables.h"
#include "model/reader.h"

typedef struct spring {
    char name[64];
    int e[2];                        /* the ends' elements (e[1] = -1: fixed at x0) */
    double xi[2], x0[3], k, l0;
    double N[2][BK_MAX_SHAPE];       /* the ends' shape functions */
} spring;

typedef struct springs {
    int n;
    spring *sp;
    double *K;                       /* [(2 maxdof)^2] scratch: one element block */
    FILE *table;                     /* springs.csv, or NULL */
} springs;

/* The end's position at q (the fixed point for e = -1). */
static void end_point(const bk_system *s, const spring *sp, int end, const double *q, double *x)
{
    const int e = sp->e[end];
    if (e < 0) {
        memcpy(x, sp->x0, 3 * sizeof *x);
        return;
    }
    const bk_element *et = bk_elem_type(s->m, e);
    const int *dofs = s->m->elems[e].dofs;
    x[0] = x[1] = x[2] = 0.0;
    for (int i = 0; i < et->nshape; ++i)
        for (int r = 0; r < 3; ++r)
            x[r] += sp->N[end][i] * q[dofs[et->shape_dof[i] + r]];
}

/* d = x_a - x_b and its length at q. */
static double separation(const bk_system *s, const spring *sp, const double *q, double *d)
{
    double xa[3], xb[3];
    end_point(s, sp, 0, q, xa);
    end_point(s, sp, 1, q, xb);
    for (int r = 0; r < 3; ++r)
        d[r] = xa[r] - xb[r];
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* The block c N_a N_b H of ends (a, b) into the element matrix K[nda ndb]. */
static void block(const bk_system *s, const spring *sp, int a, int b, const double *H, double c, double *K)
{
    const bk_element *ta = bk_elem_type(s->m, sp->e[a]), *tb = bk_elem_type(s->m, sp->e[b]);
    const int nda = ta->ndof, ndb = tb->ndof;
    memset(K, 0, (size_t)nda * (size_t)ndb * sizeof *K);
    for (int i = 0; i < ta->nshape; ++i)
        for (int j = 0; j < tb->nshape; ++j) {
            const double w = c * sp->N[a][i] * sp->N[b][j];
            for (int r = 0; r < 3; ++r)
                for (int t = 0; t < 3; ++t)
                    K[(ta->shape_dof[i] + r) * ndb + tb->shape_dof[j] + t] += w * H[3 * r + t];
        }
}

static int spring_assemble(void *self, bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax)
{
    (void)p;
    springs *w = self;
    for (int k = 0; k < w->n; ++k) {
        const spring *sp = &w->sp[k];
        double d[3];
        const double l = separation(s, sp, q, d);
        if (!(l > 0.0) && sp->l0 > 0.0)
            return -1;                   /* the ends meet: no direction */
        const double c = sp->l0 > 0.0 ? 1.0 - sp->l0 / l : 1.0;
        for (int end = 0; end < 2; ++end) {
            const int e = sp->e[end];
            if (e < 0)
                continue;
            const bk_element *et = bk_elem_type(s->m, e);
            const int *dofs = s->m->elems[e].dofs;
            const double sign = end == 0 ? 1.0 : -1.0;
            for (int i = 0; i < et->nshape; ++i)
                for (int r = 0; r < 3; ++r)
                    fint[dofs[et->shape_dof[i] + r]] += sign * sp->k * c * sp->N[end][i] * d[r];
        }
        if (!Ax)
            continue;
        double H[9];
        for (int r = 0; r < 3; ++r)
            for (int t = 0; t < 3; ++t)
                H[3 * r + t] = sp->k * (c * (r == t) + (sp->l0 > 0.0 ? sp->l0 / l * d[r] * d[t] / (l * l) : 0.0));
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) {
                if (sp->e[a] < 0 || sp->e[b] < 0)
                    continue;
                block(s, sp, a, b, H, a == b ? 1.0 : -1.0, w->K);
                if (sp->e[a] == sp->e[b])
                    bk_scatter_matrix(s, sp->e[a], w->K, 1.0, Ax);
                else
                    bk_scatter_coupling(s, sp->e[a], sp->e[b], w->K, 1.0, Ax);
            }
    }
    return 0;
}

static const bk_table_spec springs_csv =
    BK_TABLE("springs.csv", "runs with `[[spring]]`", "step,time,spring,length,extension,tension\n");

static int spring_tables(void *self, const bk_system *s, bk_tables *ts, const char *dir, FILE *err)
{
    (void)s;
    springs *w = self;
    w->table = bk_tables_open(ts, dir, &springs_csv, 1, err);
    return w->table ? 0 : -1;
}

static void spring_rows(void *self, const bk_system *s, int step, double t, const double *q, bk_rowqueue *rq)
{
    springs *w = self;
    for (int k = 0; w->table && k < w->n; ++k) {
        const spring *sp = &w->sp[k];
        double d[3];
        const double l = separation(s, sp, q, d);
        bk_row r;
        bk_row_begin(&r, w->table, rq);
        bk_row_int(&r, step);
        bk_row_num(&r, t);
        bk_row_str(&r, sp->name);
        bk_row_num(&r, l);
        bk_row_num(&r, l - sp->l0);
        bk_row_num(&r, sp->k * (l - sp->l0));
        bk_row_end(&r);
    }
}

/* summary.json "springs": {name: {length, tension}} at the final state. */
static int spring_summary(void *self, const bk_system *s, const double *q, char *buf, size_t n)
{
    springs *w = self;
    int len = snprintf(buf, n, "{");
    for (int k = 0; k < w->n && len > 0 && (size_t)len < n; ++k) {
        const spring *sp = &w->sp[k];
        double d[3];
        const double l = separation(s, sp, q, d);
        len += snprintf(buf + len, n - (size_t)len, "%s\"%s\": {\"length\": %.17g, \"tension\": %.17g}",
                        k ? ", " : "", sp->name, l, sp->k * (l - sp->l0));
    }
    if (len > 0 && (size_t)len < n)
        len += snprintf(buf + len, n - (size_t)len, "}");
    return len > 0 && (size_t)len < n ? 0 : -1;
}

static void spring_free(void *self)
{
    springs *w = self;
    if (w) {
        free(w->sp);
        free(w->K);
    }
    free(w);
}

static const bk_interaction_ops spring_ops = {.name = "springs", .assemble = spring_assemble,
                                              .tables = spring_tables, .rows = spring_rows,
                                              .summary_key = "springs", .summary = spring_summary,
                                              .free = spring_free, .depends = bk_depends_on_q};

/* The record: 'springs N', then per spring 'spring NAME EA XIA EB XIB X Y Z K L0'. */
static void read_springs(bk_reader *r, const bk_system *s, springs *w)
{
    const bk_model *m = s->m;
    rd_expect(r, "springs");
    w->n = rd_inum(r, "springs", 1, MAXN);
    w->sp = rd_xcalloc(r, (size_t)(w->n > 0 ? w->n : 1), sizeof *w->sp);
    for (int k = 0; k < w->n && !r->failed; ++k) {
        spring *sp = &w->sp[k];
        rd_expect(r, "spring");
        rd_copy_token(r, sp->name, sizeof sp->name, "spring name");
        for (int end = 0; end < 2; ++end) {
            sp->e[end] = rd_inum(r, "spring element", end == 0 ? 0 : -1, m->nelem - 1);
            sp->xi[end] = rd_num(r, "spring xi");
        }
        for (int c = 0; c < 3; ++c)
            sp->x0[c] = rd_num(r, "spring fixed point");
        sp->k = rd_num(r, "spring stiffness");
        sp->l0 = rd_num(r, "spring rest length");
        if (!r->failed && !(sp->k > 0.0 && sp->l0 >= 0.0 && sp->xi[0] >= 0.0 && sp->xi[0] <= 1.0 &&
                            sp->xi[1] >= 0.0 && sp->xi[1] <= 1.0))
            rd_fail(r, "spring %s: expected stiffness > 0, rest length >= 0 and xi in [0, 1] (%g, %g, %g, %g)",
                    sp->name, sp->k, sp->l0, sp->xi[0], sp->xi[1]);
        for (int end = 0; end < 2 && !r->failed; ++end)
            if (sp->e[end] >= 0) {
                const bk_element *et = bk_elem_type(m, sp->e[end]);
                et->shape(m->geoms[m->elems[sp->e[end]].geom], sp->xi[end], 0.0, 0.0, sp->N[end]);
            }
    }
}

static int spring_make(bk_system *s, const bk_model_record *rec, void **self, FILE *err)
{
    springs *w = calloc(1, sizeof *w);
    *self = w;
    bk_reader r;
    if (!w || rd_open_record(&r, rec, err) != 0) {
        if (!w)
            fprintf(err, "error: springs: out of memory\n");
        return -1;
    }
    read_springs(&r, s, w);
    if (rd_close_record(&r) != 0)
        return -1;
    const size_t md = (size_t)(s->maxdof > 0 ? s->maxdof : 1);
    w->K = malloc(md * md * sizeof *w->K);
    int *pairs = malloc(2 * (size_t)w->n * sizeof *pairs), np = 0;
    for (int k = 0; pairs && k < w->n; ++k)
        if (w->sp[k].e[1] >= 0 && w->sp[k].e[1] != w->sp[k].e[0]) {
            pairs[2 * np] = w->sp[k].e[0];
            pairs[2 * np + 1] = w->sp[k].e[1];
            np++;
        }
    const int couple = pairs ? bk_system_couple(s, np, pairs) : -1;   /* the blocks between the ends */
    free(pairs);
    if (!w->K || couple < 0) {
        fprintf(err, "error: springs: out of memory\n");
        return -1;
    }
    return 0;
}

const bk_interaction_module bk_interaction_spring = {.ops = &spring_ops, .order = 50, .record = "spring",
                                                     .make = spring_make};
