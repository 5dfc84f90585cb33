/* actuators.c -- the joint actuators as an interaction (interaction.h), read
 * from the model's record "actuator" (written by gen/scene/actuators.py):
 *   actuators N
 *   actuator NAME KIND JOINT EFFORT EAMP KP KD SETPOINT SAMP   (N times; KIND
 *            rotation | translation, JOINT an index of model->nlcons, EAMP and
 *            SAMP amplitude indices, -1: none)
 * Motors acting equally and oppositely on the two frames of a joint with an
 * axis: each one's generalized force Q = tau ds/dx on the coordinates x of its
 * joint's two frames and its exact Jacobian, and actuators.csv (per output step
 * and actuator: the joint coordinate s, its rate, the effort tau and the power)
 * with each one's peak effort in summary.json.
 *
 * With s the joint coordinate (the angle of frame a relative to frame b about
 * the axis, or a's displacement along it; 0 in the reference configuration)
 * and x the time (dynamics) or the load factor, the effort is
 *   tau = effort0 a_e(x) + kp (s_ref a_s(x) - s) + kd (s_ref a_s'(x) - s'),
 * a torque on a about the axis (and its opposite on b) or a force along it;
 * a_e: the amplitude EAMP (-1: the load factor in statics, 1 in dynamics), a_s:
 * the amplitude SAMP (-1: the constant 1); s' = ds/dx . x'.
 * s(x), ds/dx and d2s/dx2 come from the generated kernels (gen/actuator.py,
 * out/kernels/joints.c), so that, with fint = -Q and g = ds/dx, H = d2s/dx2,
 *   dfint/dx  = -tau H + kp g g^T + kd g (H x')^T,
 *   dfint/dx' = kd g g^T   (times gp in the Newton matrix).
 * A rotation's s is the unwrapped angle: atan2 of the kernel's (X, Y), taken
 * nearest to the last accepted state's angle. */
#include "assembly/interaction.h"
#include "assembly/system.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system_impl.h"
#include "base/csvrow.h"
#include "base/tables.h"
#include "model/amplitude.h"
#include "model/reader.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Defined by the generated joint kernels (out/kernels/joints.c). */
void bk_actuator_rotation(const double *restrict x, const double *restrict prm, double *restrict val,
                          double *restrict grad, double *restrict H);
void bk_actuator_translation(const double *restrict x, const double *restrict prm, double *restrict val,
                             double *restrict grad, double *restrict H);

enum { ACT_ROTATION = 1, ACT_TRANSLATION = 2 };

typedef struct bk_actuator {
    char name[64];
    int kind;                    /* ACT_ROTATION | ACT_TRANSLATION */
    int nlcon;                   /* its joint (model->nlcons) */
    double effort0;              /* N m or N */
    int eamp;                    /* amplitude of effort0, -1: the default */
    double kp, kd;               /* N m/rad, N m s/rad (or N/m, N s/m), >= 0 */
    double setpoint;             /* rad or m */
    int samp;                    /* amplitude of the set-point, -1: constant */
} bk_actuator;

typedef struct act_state {
    double raw, angle;           /* the accepted state's atan2 and unwrapped angle */
    double s, sd, tau;           /* of the last evaluation */
    double peak, peak_t;         /* largest |tau| at output steps and its time */
} act_state;

typedef struct act_work {
    int n;
    bk_actuator *acts;           /* [n] the record's */
    act_state *st;
    FILE *table;                 /* actuators.csv (NULL: not opened) */
    int have_rows;
} act_work;

/* The joint coordinate's value (unwrapped from st), gradient and Hessian at x. */
static double coordinate(const bk_actuator *a, const bk_nlcon *c, const act_state *st, const double *x, double *g,
                         double *H, double *raw)
{
    double val[2];
    if (a->kind == ACT_ROTATION) {
        bk_actuator_rotation(x, c->prm, val, g, H);
        *raw = atan2(val[1], val[0]);
        double d = *raw - st->raw;
        d -= 2.0 * M_PI * floor((d + M_PI) / (2.0 * M_PI));
        return st->angle + d;
    }
    bk_actuator_translation(x, c->prm, val, g, H);
    *raw = val[0];
    return val[0];
}

static int act_assemble(void *self, bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax)
{
    act_work *w = self;
    const bk_model *m = s->m;
    const int nx = BK_JOINT_NX;
    int bad = 0;
    for (int i = 0; i < w->n; ++i) {
        const bk_actuator *a = &w->acts[i];
        const bk_nlcon *c = &m->nlcons[a->nlcon];
        act_state *st = &w->st[i];
        double x[BK_JOINT_NX], xd[BK_JOINT_NX] = {0}, g[BK_JOINT_NX], H[BK_JOINT_NX * BK_JOINT_NX], raw;
        joint_x(c, q, 0, x);
        const double sv = coordinate(a, c, st, x, g, H, &raw);
        double sd = 0.0;
        if (p->qd) {
            joint_x(c, p->qd, 1, xd);
            for (int k = 0; k < nx; ++k)
                sd += g[k] * xd[k];
        }
        const double as = a->samp >= 0 ? bk_amp_eval(&m->amps[a->samp], p->x, 0) : 1.0;
        const double asd = a->samp >= 0 && p->qd ? bk_amp_eval(&m->amps[a->samp], p->x, 1) : 0.0;
        const double tau = a->effort0 * bk_load_factor(m, a->eamp, p->x) + a->kp * (a->setpoint * as - sv)
                           + a->kd * (a->setpoint * asd - sd);
        bad |= !isfinite(tau);
        st->s = sv, st->sd = sd, st->tau = tau;
        for (int k = 0; k < nx; ++k)
            if (c->dof[k] >= 0)
                fint[c->dof[k]] -= tau * g[k];
        if (!Ax)
            continue;
        double hxd[BK_JOINT_NX];
        for (int l = 0; l < nx; ++l) {
            hxd[l] = 0.0;
            for (int k = 0; k < nx; ++k)
                hxd[l] += H[nx * k + l] * xd[k];
        }
        const int *sl = s->jslot + s->jslot_off[a->nlcon];
        const double kv = a->kp + p->gp * a->kd;
        for (int k = 0; k < nx; ++k)
            for (int l = 0; l < nx; ++l)
                if (sl[nx * k + l] >= 0)
                    Ax[sl[nx * k + l]] += -tau * H[nx * k + l] + g[k] * (kv * g[l] + a->kd * hxd[l]);
    }
    return bad ? -1 : 0;
}

/* The accepted state's angle: the reference the next states unwrap from. */
static void act_accept(void *self, const bk_system *s, const double *q, const bk_path *p)
{
    act_work *w = self;
    const bk_model *m = s->m;
    (void)p;
    for (int i = 0; i < w->n; ++i) {
        const bk_actuator *a = &w->acts[i];
        if (a->kind != ACT_ROTATION)
            continue;
        const bk_nlcon *c = &m->nlcons[a->nlcon];
        double x[BK_JOINT_NX], g[BK_JOINT_NX], H[BK_JOINT_NX * BK_JOINT_NX], raw;
        joint_x(c, q, 0, x);
        double th = coordinate(a, c, &w->st[i], x, g, H, &raw);
        w->st[i].raw = raw, w->st[i].angle = th;
    }
}

static const bk_table_spec actuators_csv =
    BK_TABLE("actuators.csv", "statics and dynamics with `[[actuator]]`",
             "step,time,actuator,joint,motion,value,rate,effort,power\n");

static int act_tables(void *self, const bk_system *s, bk_tables *ts, const char *dir, FILE *err)
{
    act_work *w = self;
    if (!bk_model_on_path(s->m))
        return 0;
    w->table = bk_tables_open(ts, dir, &actuators_csv, 1, err);
    return w->table ? 0 : -1;
}

/* One row per actuator: the values of the last evaluation, which the output
 * step's reactions (output/forces.c) made at this state. */
static void act_rows(void *self, const bk_system *s, int step, double t, const double *q, bk_rowqueue *rq)
{
    act_work *w = self;
    (void)s, (void)q;
    if (!w->table)
        return;
    for (int i = 0; i < w->n; ++i) {
        const bk_actuator *a = &w->acts[i];
        act_state *st = &w->st[i];
        if (isfinite(st->tau) && fabs(st->tau) >= st->peak)
            st->peak = fabs(st->tau), st->peak_t = t;
        bk_row r;
        bk_row_begin(&r, w->table, rq);
        bk_row_int(&r, step);
        bk_row_num(&r, t);
        bk_row_str(&r, a->name);
        bk_row_int(&r, a->nlcon);
        bk_row_str(&r, a->kind == ACT_ROTATION ? "rotation" : "translation");
        bk_row_num(&r, st->s);
        bk_row_num(&r, st->sd);
        bk_row_num(&r, st->tau);
        bk_row_num(&r, st->tau * st->sd);
        bk_row_end(&r);
    }
    w->have_rows = 1;
}

static int act_summary(void *self, const bk_system *s, const double *q, char *buf, size_t n)
{
    act_work *w = self;
    (void)s, (void)q;
    if (!w->have_rows)
        return -1;
    size_t k = (size_t)snprintf(buf, n, "[");
    for (int i = 0; i < w->n && k < n; ++i)
        k += (size_t)snprintf(buf + k, n - k, "%s{\"name\": \"%s\", \"peak_effort\": %.17g, \"peak_time\": %.17g, "
                              "\"final_value\": %.17g}", i ? ", " : "", w->acts[i].name,
                              w->st[i].peak, w->st[i].peak_t, w->st[i].s);
    if (k < n)
        snprintf(buf + k, n - k, "]");
    return k + 1 < n ? 0 : -1;
}

static void act_free(void *self)
{
    act_work *w = self;
    if (!w)
        return;
    free(w->acts);
    free(w->st);
    free(w);
}

/* The effort and the set-point follow amplitudes of x; the joint coordinate q. */
static unsigned act_depends(const void *self, const bk_system *s)
{
    (void)self, (void)s;
    return BK_DEPENDS_X | BK_DEPENDS_Q;
}

static const bk_interaction_ops act_ops = {.name = "actuators", .assemble = act_assemble, .accept = act_accept,
                                           .tables = act_tables, .rows = act_rows, .summary_key = "actuators",
                                           .summary = act_summary, .free = act_free, .depends = act_depends};

/* The record (see the top): the actuators, checked against the model's joints
 * and amplitudes. */
static void read_actuators(bk_reader *r, const bk_model *m, act_work *w)
{
    rd_expect(r, "actuators");
    const int n = rd_inum(r, "actuators", 1, MAXN);
    w->acts = rd_xcalloc(r, (size_t)(n > 0 ? n : 1), sizeof *w->acts);
    for (int i = 0; i < n && !r->failed; ++i) {
        bk_actuator *a = &w->acts[i];
        rd_expect(r, "actuator");
        rd_copy_token(r, a->name, sizeof a->name, "actuator name");
        const char *t = rd_next(r, "actuator kind");
        a->kind = !t ? 0 : strcmp(t, "rotation") == 0 ? ACT_ROTATION : strcmp(t, "translation") == 0 ? ACT_TRANSLATION
                                                                                                     : 0;
        if (t && !a->kind)
            rd_fail(r, "actuator %d: unknown kind '%s' (expected rotation or translation)", i, t);
        a->nlcon = rd_inum(r, "actuator joint", 0, m->nnlcon - 1);
        a->effort0 = rd_num(r, "actuator effort");
        a->eamp = rd_inum(r, "actuator effort amplitude", -1, m->namp - 1);
        a->kp = rd_num(r, "actuator kp");
        a->kd = rd_num(r, "actuator kd");
        a->setpoint = rd_num(r, "actuator set-point");
        a->samp = rd_inum(r, "actuator set-point amplitude", -1, m->namp - 1);
        if (!r->failed && !(a->kp >= 0.0 && a->kd >= 0.0))
            rd_fail(r, "actuator %d: gains kp, kd must be >= 0 (%g, %g)", i, a->kp, a->kd);
        w->n = i + 1;
    }
}

static int act_make(bk_system *s, const bk_model_record *rec, void **self, FILE *err)
{
    act_work *w = calloc(1, sizeof *w);
    *self = w;
    bk_reader r;
    if (!w || rd_open_record(&r, rec, err) != 0) {
        if (!w)
            fprintf(err, "error: actuators: out of memory\n");
        return -1;
    }
    read_actuators(&r, s->m, w);
    if (rd_close_record(&r) != 0)
        return -1;
    w->st = calloc((size_t)w->n, sizeof *w->st);
    if (!w->st) {
        fprintf(err, "error: actuators: out of memory\n");
        return -1;
    }
    return 0;
}

const bk_interaction_module bk_interaction_actuators = {.ops = &act_ops, .order = 60, .record = "actuator",
                                                        .make = act_make};
