/* body_forces.c -- dead forces at body points off the centre of mass as an
 * interaction (interaction.h; model.h bk_body_force): a force F (global, fixed
 * in direction) at the point o = r + R(p) c of a rigid body does the work
 * F . o, so Q = (do/dq)^T F and dQ/dq = sum_k F_k d2o_k/dq2.  Both come from the
 * generated spherical joint (out/kernels/joints.c, bk_joint.h) between the body
 * (frame a, joint point c) and the ground (frame b): its rows g = o_b - o_a give
 * Q = -G^T F and dQ/dq = -H(F), H(nu) = sum_k nu_k d2g_k/dx2. */
#include "assembly/body_forces.h"

#include <string.h>

#include "model/amplitude.h"

/* Defined by the generated joint kernels (out/kernels/joints.c). */
extern const bk_joint_kind *const bk_joint_kinds[];
extern const int bk_njoint_kinds;

int bk_body_forces_present(const bk_model *m)
{
    return m->nbforce > 0;
}

static int bf_assemble(void *self, bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax)
{
    const bk_joint_kind *sph = self;
    const bk_model *m = s->m;
    const int nx = BK_JOINT_NX;
    double x[BK_JOINT_NX], prm[BK_JOINT_NPARAM] = {0}, g[3], G[3 * BK_JOINT_NX], H[BK_JOINT_NX * BK_JOINT_NX];
    double fe[7], Ke[49];
    for (int i = 0; i < m->nbforce; ++i) {
        const bk_body_force *f = &m->bforces[i];
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

const bk_interaction_ops bk_body_force_ops = {.name = "body forces", .assemble = bf_assemble};

int bk_body_forces_make(bk_system *s, void **self)
{
    (void)s;
    *self = NULL;
    for (int k = 0; k < bk_njoint_kinds; ++k)
        if (strcmp(bk_joint_kinds[k]->name, "spherical") == 0)
            *self = (void *)bk_joint_kinds[k];
    return *self ? 0 : -1;
}
