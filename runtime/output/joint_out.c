/* joint_out.c -- joints.csv and the joints' peak efforts in summary.json: per
 * output step and joint with an axis (revolute, prismatic and the driven
 * joints, nonlinear in q), the relative angle (unwrapped) or displacement of
 * frame a relative to frame b about or along the axis, its rate, the effort
 * (the reaction's moment or force on frame a about or along the axis: the
 * motor torque or force of a driven joint) and the power effort x rate. */
#include "output/forces_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* 0: no axis; 1: rotation about it; 2: translation along it. */
static int joint_axis_kind(const bk_nlcon *c)
{
    if (strcmp(c->type, "revolute") == 0 || strcmp(c->type, "prescribed_rotation") == 0)
        return 1;
    if (strcmp(c->type, "prismatic") == 0 || strcmp(c->type, "prescribed_translation") == 0)
        return 2;
    return 0;
}

static void rotate(const double *p, const double *v, double *out)      /* R(p/|p|) v */
{
    double n = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3], w = p[0];
    const double *u = p + 1;
    double uv[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double uuv[3] = {u[1] * uv[2] - u[2] * uv[1], u[2] * uv[0] - u[0] * uv[2], u[0] * uv[1] - u[1] * uv[0]};
    for (int i = 0; i < 3; ++i)
        out[i] = v[i] + 2.0 * (w * uv[i] + uuv[i]) / n;
}

/* The spatial angular velocity of p with rate pd: 2 (w vd - wd v + v x vd)/|p|^2. */
static void omega(const double *p, const double *pd, double *om)
{
    double n = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
    const double *v = p + 1, *vd = pd + 1;
    double c[3] = {v[1] * vd[2] - v[2] * vd[1], v[2] * vd[0] - v[0] * vd[2], v[0] * vd[1] - v[1] * vd[0]};
    for (int i = 0; i < 3; ++i)
        om[i] = 2.0 * (p[0] * vd[i] - pd[0] * v[i] + c[i]) / n;
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static const bk_table_spec joints_csv =
    BK_TABLE("joints.csv", "statics and dynamics with a joint that has an axis",
             "step,time,constraint,name,type,motion,value,rate,effort,power\n");

int bk_joints_open(bk_forces *f, const bk_model *m, const char *dir, bk_tables *ts, FILE *err)
{
    int n = 0;
    for (int c = 0; c < m->nreaction; ++c)
        n += m->reactions[c].nlcon >= 0 && joint_axis_kind(&m->nlcons[m->reactions[c].nlcon]);
    if (n == 0)
        return 0;
    f->jstate = calloc(4 * (size_t)m->nreaction, sizeof *f->jstate);
    if (!f->jstate) {
        fprintf(err, "error: out of memory for joints.csv\n");
        return -1;
    }
    f->joints = bk_tables_open(ts, dir, &joints_csv, 1, err);
    return f->joints ? 0 : -1;
}

void bk_joints_step(bk_forces *f, int step, double x, const double *q, const double *qd)
{
    const bk_model *m = f->m;
    if (!f->joints)
        return;
    for (int c = 0; c < m->nreaction; ++c) {
        const bk_reaction *rc = &m->reactions[c];
        if (rc->nlcon < 0)
            continue;
        const bk_nlcon *jc = &m->nlcons[rc->nlcon];
        const int kind = joint_axis_kind(jc);
        if (!kind)
            continue;
        double xj[BK_JOINT_NX], xd[BK_JOINT_NX];
        for (int i = 0; i < BK_JOINT_NX; ++i) {
            xj[i] = jc->dof[i] >= 0 ? q[jc->dof[i]] : jc->x0[i];
            xd[i] = jc->dof[i] >= 0 && qd ? qd[jc->dof[i]] : 0.0;
        }
        const double *prm = jc->prm;
        double u[3][3], v[3][3], oa[3], ob[3], ca[3], cb[3], wa[3], wb[3];
        for (int k = 0; k < 3; ++k) {
            rotate(xj + 3, prm + 6 + 3 * k, u[k]);
            rotate(xj + 10, prm + 15 + 3 * k, v[k]);
        }
        rotate(xj + 3, prm, ca);
        rotate(xj + 10, prm + 3, cb);
        omega(xj + 3, xd + 3, wa);
        omega(xj + 10, xd + 10, wb);
        for (int i = 0; i < 3; ++i)
            oa[i] = xj[i] + ca[i], ob[i] = xj[7 + i] + cb[i];
        const double *L = f->last[c];          /* force, moment on a about the joint point */
        double *st = f->jstate + 4 * c;        /* raw angle, unwrapped angle, peak |effort|, its time */
        double value, rate, effort;
        if (kind == 1) {
            double raw = atan2(dot3(v[1], u[0]), dot3(v[0], u[0]));
            double d = raw - st[0];
            d -= 2.0 * M_PI * floor((d + M_PI) / (2.0 * M_PI));
            value = st[1] + d;
            st[0] = raw, st[1] = value;
            double wr[3] = {wa[0] - wb[0], wa[1] - wb[1], wa[2] - wb[2]};
            rate = dot3(wr, v[2]);
            effort = dot3(L + 3, v[2]);
        } else {
            double r[3] = {oa[0] - ob[0], oa[1] - ob[1], oa[2] - ob[2]}, va[3], vb[3], wu[3];
            cross3(wa, ca, va);
            cross3(wb, cb, vb);
            cross3(wa, u[2], wu);
            double rd[3];
            for (int i = 0; i < 3; ++i)
                rd[i] = xd[i] + va[i] - xd[7 + i] - vb[i];
            value = dot3(r, u[2]);
            rate = dot3(rd, u[2]) + dot3(r, wu);
            effort = dot3(L, u[2]);
        }
        if (isfinite(effort) && fabs(effort) >= st[2])
            st[2] = fabs(effort), st[3] = x;
        bk_row row;
        bk_row_begin(&row, f->joints, f->rq);
        bk_row_int(&row, step);
        bk_row_num(&row, x);
        bk_row_int(&row, rc->index);
        bk_row_str(&row, rc->name);
        bk_row_str(&row, rc->type);
        bk_row_str(&row, kind == 1 ? "rotation" : "translation");
        bk_row_num(&row, value);
        bk_row_num(&row, rate);
        bk_row_num(&row, effort);
        bk_row_num(&row, effort * rate);
        bk_row_end(&row);
    }
    f->have_joints = 1;
}

void bk_joints_summary(const bk_forces *f, FILE *fp)
{
    const bk_model *m = f->m;
    if (!m || !f->have_joints)
        return;
    fprintf(fp, "  \"joints\": [");
    int first = 1;
    for (int c = 0; c < m->nreaction; ++c) {
        const bk_reaction *rc = &m->reactions[c];
        if (rc->nlcon < 0 || !joint_axis_kind(&m->nlcons[rc->nlcon]))
            continue;
        const double *st = f->jstate + 4 * c;
        fprintf(fp, "%s\n    {\"constraint\": %d, \"name\": \"%s\", \"type\": \"%s\", \"peak_effort\": %.17g, "
                "\"peak_time\": %.17g}", first ? "" : ",", rc->index, rc->name, rc->type, st[2], st[3]);
        first = 0;
    }
    fprintf(fp, "\n  ],\n");
}
