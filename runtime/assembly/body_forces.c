/* body_forces.c -- dead forces at body points off the centre of mass as an
 * interaction (interaction.h), read from the model's record "body_force"
 * (written by gen/scene/body_loads.py):
 *   body_forces N
 *   body_force ELEMENT CX CY CZ FX FY FZ AMP   (N times; ELEMENT a rigid body's,
 *              C the point in the body axes (m), F global (N), AMP an
 *              amplitude index, -1: the default)
 * A force F (global, fixed in direction) at the point o = r + R(p) c of a rigid
 * body does the work F . o, so Q = (do/dq)^T F and dQ/dq = sum_k F_k d2o_k/dq2.
 * Both come from the generated spherical joint (out/kernels/joints.c,
 * bk_joint.h) between the body (frame a, joint point c) and the ground (frame
 * b): its rows g = o_b - o_a give Q = -G^T F and dQ/dq = -H(F), H(nu) = sum_k
 * nu_k d2g_k/dx2. */
#include <stdlib.h>
#include <string.h>

#include "assembly/interaction.h"
#include "assembly/system.h"
#include "model/amplitude.h"
#include "model/reader.h"

/* Defined by the generated joint kernels (out/kernels/joints.c). */
extern const bk_joint_kind *const bk_joint_kinds[];
extern const int bk_njoint_kinds;

typedef struct body_force {
    int elem;                        /* the body's element (7 DOFs: r, p) */
    double c[3];                     /* the point in the body axes (m) */
    double value[3];                 /* N, global */
    int amp;                         /* amplitude index, -1: the default */
} body_force;

typedef struct body_forces {
    const bk_joint_kind *sph;        /* the generated spherical joint */
    int n;
    body_force *f;
} body_forces;

static int bf_assemble(void *self, bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax)
{
    const body_forces *w = self;
    const bk_joint_kind *sph = w->sph;
    const bk_model *m = s->m;
    const int nx = BK_JOINT_NX;
    double x[BK_JOINT_NX], prm[BK_JOINT_NPARAM] = {0}, g[3], G[3 * BK_JOINT_NX], H[BK_JOINT_NX * BK_JOINT_NX];
    double fe[7], Ke[49];
    for (int i = 0; i < w->n; ++i) {
        const body_force *f = &w->f[i];
        const double fac = bk_load_factor(m, f->amp, p->x);
        const int *d = m->elems[f->elem].dofs;
        for (int k = 0; k < 7; ++k)
            x[k] = q[d[k]];
        for (int k = 7; k < nx; ++k)               /* the ground: the identity's quaternion */
            x[k] = k == 10 ? 1.0 : 0.0;
        memcpy(prm, f->c, sizeof f->c);
        double F[3] = {fac * f->value[0], fac * f->value[1], fac * f->value[2]};
        sph->eval(x, prm, g, G);
        for (int k = 0; k < 7; ++k)
            fe[k] = G[k] * F[0] + G[nx + k] * F[1] + G[2 * nx + k] * F[2];     /* -Q */
        bk_scatter(m, f->elem, fe, 1.0, fint);
        if (!Ax)
            continue;
        sph->hessian(x, prm, F, H);
        for (int k = 0; k < 7; ++k)
            for (int l = 0; l < 7; ++l)
                Ke[7 * k + l] = H[nx * k + l];                                  /* d(-Q)/dq */
        bk_scatter_matrix(s, f->elem, Ke, 1.0, Ax);
    }
    return 0;
}

static void bf_free(void *self)
{
    body_forces *w = self;
    if (w)
        free(w->f);
    free(w);
}

/* Amplitudes of x; the body point turns with the body (q). */
static unsigned bf_depends(const void *self, const bk_system *s)
{
    (void)self, (void)s;
    return BK_DEPENDS_X | BK_DEPENDS_Q;
}

static const bk_interaction_ops bf_ops = {.name = "body forces", .assemble = bf_assemble, .free = bf_free,
                                          .depends = bf_depends};

/* The record (see the top), checked against the model's elements and amplitudes. */
static void read_body_forces(bk_reader *r, const bk_model *m, body_forces *w)
{
    rd_expect(r, "body_forces");
    const int n = rd_inum(r, "body forces", 1, MAXN);
    w->f = rd_xcalloc(r, (size_t)(n > 0 ? n : 1), sizeof *w->f);
    for (int i = 0; i < n && !r->failed; ++i) {
        body_force *f = &w->f[i];
        rd_expect(r, "body_force");
        f->elem = rd_inum(r, "body force element", 0, m->nelem - 1);
        for (int k = 0; k < 3; ++k)
            f->c[k] = rd_num(r, "body force point");
        for (int k = 0; k < 3; ++k)
            f->value[k] = rd_num(r, "body force value");
        f->amp = rd_inum(r, "body force amplitude", -1, m->namp - 1);
        if (!r->failed && m->pairs[m->elems[f->elem].pair]->element->ndof != 7)
            rd_fail(r, "body force %d: element %d is not a rigid body", i, f->elem);
        w->n = i + 1;
    }
}

static int bf_make(bk_system *s, const bk_model_record *rec, void **self, FILE *err)
{
    body_forces *w = calloc(1, sizeof *w);
    *self = w;
    bk_reader r;
    if (!w || rd_open_record(&r, rec, err) != 0) {
        if (!w)
            fprintf(err, "error: body forces: out of memory\n");
        return -1;
    }
    read_body_forces(&r, s->m, w);
    if (rd_close_record(&r) != 0)
        return -1;
    for (int k = 0; k < bk_njoint_kinds; ++k)
        if (strcmp(bk_joint_kinds[k]->name, "spherical") == 0)
            w->sph = bk_joint_kinds[k];
    if (!w->sph) {
        fprintf(err, "error: body forces: no spherical joint kernel linked into this solver (rebuild with "
                "./build.sh run)\n");
        return -1;
    }
    return 0;
}

const bk_interaction_module bk_interaction_body_forces = {.ops = &bf_ops, .order = 70, .record = "body_force",
                                                          .make = bf_make};
