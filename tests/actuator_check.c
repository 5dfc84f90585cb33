/* actuator_check.c -- the Jacobian the interactions give (of a model whose only
 * interactions are joint actuators) against central differences of their force
 * vector: d(fint)/dq + gp d(fint)/dq' at a turned state with velocities.
 *   actuator_check MODEL_FILE T GP  ->  prints "max_abs_err max_abs_entry" and exits 0 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/interaction.h"
#include "assembly/system.h"
#include "model/model.h"

extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;
extern const bk_joint_kind *const bk_joint_kinds[];
extern const int bk_njoint_kinds;

static void forces(bk_system *s, const double *q, const double *qd, double t, double gp, double *f, double *Ax)
{
    memset(f, 0, (size_t)s->m->ndof * sizeof *f);
    bk_path p = {.factor = 1.0, .x = t, .qd = qd, .gp = gp};
    bk_assemble_interactions(s, q, &p, f, Ax);
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: actuator_check MODEL_FILE T GP\n");
        return 64;
    }
    double t = atof(argv[2]), gp = atof(argv[3]);
    bk_model *m = bk_model_read(argv[1], bk_linked_pairs, bk_nlinked_pairs, stderr);
    if (!m || bk_model_bind_joints(m, bk_joint_kinds, bk_njoint_kinds, stderr) != 0)
        return 1;
    bk_system *s = bk_system_create(m, stderr);
    if (!s)
        return 1;
    int n = m->ndof;
    double *q = malloc((size_t)n * sizeof *q), *qd = malloc((size_t)n * sizeof *qd), *f = calloc((size_t)n, sizeof *f);
    double *fp = calloc((size_t)n, sizeof *fp), *fm = calloc((size_t)n, sizeof *fm);
    double *Ax = calloc((size_t)s->nnz, sizeof *Ax), *d = calloc((size_t)n, sizeof *d);
    /* a deterministic perturbation of every free DOF (quaternions off unit length), velocities */
    for (int i = 0; i < n; ++i) {
        q[i] = m->q0[i] + (s->eq[i] >= 0 ? 0.3 * sin(1.7 * i + 0.3) : 0.0);
        qd[i] = s->eq[i] >= 0 ? 0.8 * cos(2.3 * i + 0.1) : 0.0;
    }
    forces(s, q, qd, t, gp, f, Ax);
    double err = 0.0, big = 0.0;
    for (int j = 0; j < n; ++j) {
        int col = s->eq[j];
        if (col < 0)
            continue;
        double h = 1e-6 * fmax(1.0, fabs(q[j])), save = q[j], hv = 1e-6 * fmax(1.0, fabs(qd[j])), vsave = qd[j];
        q[j] = save + h;
        forces(s, q, qd, t, gp, fp, NULL);
        q[j] = save - h;
        forces(s, q, qd, t, gp, fm, NULL);
        q[j] = save;
        for (int i = 0; i < n; ++i)
            d[i] = (fp[i] - fm[i]) / (2.0 * h);
        qd[j] = vsave + hv;
        forces(s, q, qd, t, gp, fp, NULL);
        qd[j] = vsave - hv;
        forces(s, q, qd, t, gp, fm, NULL);
        qd[j] = vsave;
        for (int i = 0; i < n; ++i)
            d[i] += gp * (fp[i] - fm[i]) / (2.0 * hv);
        for (int i = 0; i < n; ++i) {
            int row = s->eq[i];
            if (row < 0)
                continue;
            double a = 0.0;
            for (int k = s->Ap[col]; k < s->Ap[col + 1]; ++k)
                if (s->Ai[k] == row)
                    a = Ax[k];
            err = fmax(err, fabs(a - d[i]));
            big = fmax(big, fabs(d[i]));
        }
    }
    printf("%.6e %.6e\n", err, big);
    free(q), free(qd), free(f), free(fp), free(fm), free(Ax), free(d);
    bk_system_free(s);
    bk_model_free(m);
    return 0;
}
