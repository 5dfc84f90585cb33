/* dyn_check.c -- the iteration matrix of a generalized-alpha step (the Newton
 * matrix analysis/dyn_residual.c assembles: K_t + gp C + bp M + the rotary
 * inertia's and the constraints' terms) against central differences of the
 * dynamic residual itself, with the step's coupling of the unknowns:
 *   q -> q + h e_j,  q' -> q' + gp h e_j,  q'' -> q'' + bp h e_j.
 * The state: the model's reference configuration turned rigidly about z by
 * THETA at the rate OMEGA (positions, nodal quaternions and their rates and
 * accelerations of that spin), plus a small deterministic perturbation of
 * every free DOF (so that no term vanishes by symmetry).
 *   dyn_check MODEL_FILE T THETA OMEGA DT
 * prints "max_abs_err max_abs_entry worst_row worst_col n_bad" (n_bad: the
 * entries off by more than 1e-4 max(|entry|, 1)) and exits 0; DT the step,
 * rho_inf the model's; with dynamic.frame the residual in the rotating frame at
 * T (the state then relative to the frame).  DYN_CHECK_ALL=1 lists the entries
 * off by 1e-6. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/dynamics_impl.h"
#include "assembly/quaternion.h"
#include "assembly/system.h"
#include "model/model.h"

extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;
extern const bk_joint_kind *const bk_joint_kinds[];
extern const int bk_njoint_kinds;

static void qmul(const double *a, const double *b, double *c)
{
    c[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    c[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    c[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    c[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

int main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: dyn_check MODEL_FILE T THETA OMEGA DT\n");
        return 64;
    }
    const double t = atof(argv[2]), th = atof(argv[3]), om = atof(argv[4]), h = atof(argv[5]);
    bk_model *m = bk_model_read(argv[1], bk_linked_pairs, bk_nlinked_pairs, stderr);
    if (!m || bk_model_bind_joints(m, bk_joint_kinds, bk_njoint_kinds, stderr) != 0)
        return 1;
    bk_system *s = bk_system_create(m, stderr);
    if (!s)
        return 1;
    const int n = m->ndof, neq = s->neq;
    dyn_work w = {0};
    int nquat = 0;
    int *quat = bk_quat_list(s, &nquat);
    int *fdof = bk_dyn_free_dofs(s);
    double *q = calloc((size_t)n, sizeof *q), *r0 = calloc((size_t)neq, sizeof *r0);
    double *rp = calloc((size_t)neq, sizeof *rp), *rm = calloc((size_t)neq, sizeof *rm);
    double *A = calloc((size_t)s->nnz, sizeof *A), *Ax = calloc((size_t)s->nnz, sizeof *Ax);
    char *isq = calloc((size_t)n, 1);
    if (bk_dyn_work_alloc(&w, s) != 0 || !fdof || nquat < 0 || !q || !r0 || !rp || !rm || !A || !Ax || !isq)
        return 1;
    w.r = calloc((size_t)neq, sizeof *w.r), w.Ax = Ax;
    bk_dyn_frame frame;                 /* dynamic.frame: the residual in the rotating frame */
    char msg[512];
    if (bk_frame_init(&frame, s, msg, sizeof msg) != 0) {
        fprintf(stderr, "%s\n", msg);
        return 1;
    }
    w.frame = frame.on ? &frame : NULL;
    bk_dyn_assemble_mass(s, w.Mx, w.K1, w.K2);
    bk_dyn_compact_mass(s, &w, w.Mx);
    const double rho = m->dyn.rho_inf;
    const double am = (2.0 * rho - 1.0) / (rho + 1.0), af = rho / (rho + 1.0);
    const double gam = 0.5 + af - am, bet = 0.25 * (gam + 0.5) * (gam + 0.5);
    const double bp = (1.0 - am) / (bet * h * h * (1.0 - af)), gp = gam / (bet * h);
    s->cscale = bp;
    /* the rigid spin: positions r = R r0, r' = w x r, r'' = -w^2 (x, y, 0);
     * quaternions p = z(th) p0, p' = z'(th) p0, p'' = -(w/2)^2 p */
    const double z[4] = {cos(0.5 * th), 0.0, 0.0, sin(0.5 * th)};
    const double zd[4] = {-0.5 * om * sin(0.5 * th), 0.0, 0.0, 0.5 * om * cos(0.5 * th)};
    memcpy(q, m->q0, (size_t)n * sizeof *q);
    for (int k = 0; k < nquat; ++k) {
        double *p = q + quat[k];
        double p0[4] = {p[0], p[1], p[2], p[3]};
        qmul(z, p0, p);
        qmul(zd, p0, w.qd + quat[k]);
        for (int i = 0; i < 4; ++i)
            w.qdd[quat[k] + i] = -0.25 * om * om * p[i], isq[quat[k] + i] = 1;
    }
    for (int i = 0; i + 2 < n; ++i) {
        /* the position triplets of the nodes: the DOFs not in a quaternion, in threes */
        if (isq[i] || isq[i + 1] || isq[i + 2])
            continue;
        const double x = m->q0[i], y = m->q0[i + 1];
        q[i] = cos(th) * x - sin(th) * y, q[i + 1] = sin(th) * x + cos(th) * y;
        w.qd[i] = -om * q[i + 1], w.qd[i + 1] = om * q[i];
        w.qdd[i] = -om * om * q[i], w.qdd[i + 1] = -om * om * q[i + 1];
        i += 2;
    }
    for (int i = 0; i < n; ++i)
        if (s->eq[i] >= 0) {
            q[i] += 1e-3 * sin(1.7 * i + 0.3);
            w.qd[i] += 1e-2 * cos(2.3 * i + 0.1);
            w.qdd[i] += 1e-1 * sin(0.7 * i + 0.2);
        }
    for (int c = 0; c < s->ncon; ++c)
        w.nu[c] = 10.0 * sin(0.9 * c + 0.4);
    double rn;
    if (bk_dyn_residual(s, &w, fdof, q, t, bp, gp, 1, &rn) != 0)
        return 1;
    memcpy(A, Ax, (size_t)s->nnz * sizeof *A);
    memcpy(r0, w.r, (size_t)neq * sizeof *r0);
    double err = 0.0, big = 0.0;
    int wr = -1, wc = -1, nbad = 0;
    for (int col = 0; col < neq; ++col) {
        const int j = col < s->nfree ? fdof[col] : -1;
        const double hq = 1e-6 * (j >= 0 ? fmax(1.0, fabs(q[j])) : fmax(1.0, fabs(w.nu[col - s->nfree])));
        for (int sg = -1; sg <= 1; sg += 2) {
            if (j >= 0)
                q[j] += sg * hq, w.qd[j] += sg * gp * hq, w.qdd[j] += sg * bp * hq;
            else
                w.nu[col - s->nfree] += sg * hq;
            if (bk_dyn_residual(s, &w, fdof, q, t, bp, gp, 0, &rn) != 0)
                return 1;
            memcpy(sg < 0 ? rm : rp, w.r, (size_t)neq * sizeof *rp);
            if (j >= 0)
                q[j] -= sg * hq, w.qd[j] -= sg * gp * hq, w.qdd[j] -= sg * bp * hq;
            else
                w.nu[col - s->nfree] -= sg * hq;
        }
        for (int row = 0; row < neq; ++row) {
            double a = 0.0, d = (rp[row] - rm[row]) / (2.0 * hq);
            for (int k = s->Ap[col]; k < s->Ap[col + 1]; ++k)
                if (s->Ai[k] == row)
                    a = A[k];
            if (getenv("DYN_CHECK_ALL") && fabs(a - d) > 1e-6 * fmax(fabs(d), 1.0))
                fprintf(stderr, "row %d (dof %d%s) col %d (dof %d%s): matrix %.9g, differences %.9g\n", row,
                        row < s->nfree ? fdof[row] : -1, row < s->nfree && isq[fdof[row]] ? " quat" : "", col, j,
                        j >= 0 && isq[j] ? " quat" : "", a, d);
            nbad += fabs(a - d) > 1e-4 * fmax(fabs(d), 1.0);
            if (fabs(a - d) > err)
                err = fabs(a - d), wr = row, wc = col;
            big = fmax(big, fabs(d));
        }
    }
    printf("%.6e %.6e %d %d %d\n", err, big, wr, wc, nbad);
    free(w.r);
    w.r = NULL;
    bk_dyn_work_free(&w);
    bk_frame_free(&frame);
    free(q), free(r0), free(rp), free(rm), free(A), free(Ax), free(isq), free(fdof), free(quat);
    bk_system_free(s);
    bk_model_free(m);
    return 0;
}
