/* loads_check.c -- the Jacobian of bk_assemble_loads (follower loads, tendons,
 * distributed loads) against central differences of the load vector itself,
 * at a perturbed configuration of a model file.
 *   loads_check MODEL_FILE X   ->  prints "max_abs_err max_abs_entry" and exits 0 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/loads.h"
#include "model/model.h"
#include "assembly/quaternion.h"
#include "assembly/system.h"

extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: loads_check MODEL_FILE X\n");
        return 64;
    }
    double x = atof(argv[2]);
    bk_model *m = bk_model_read(argv[1], bk_linked_pairs, bk_nlinked_pairs, stderr);
    if (!m)
        return 1;
    bk_system *s = bk_system_create(m, stderr);
    if (!s)
        return 1;
    int n = m->ndof;
    double *q = malloc((size_t)n * sizeof *q), *f = calloc((size_t)n, sizeof *f);
    double *fp = calloc((size_t)n, sizeof *fp), *fm = calloc((size_t)n, sizeof *fm);
    double *Ax = calloc((size_t)s->nnz, sizeof *Ax);
    /* a deterministic perturbation of every free DOF: a deformed, turned state */
    for (int i = 0; i < n; ++i)
        q[i] = m->q0[i] + (s->eq[i] >= 0 ? 0.05 * sin(1.7 * i + 0.3) : 0.0);
    bk_assemble_loads(s, q, x, f, Ax);
    double err = 0.0, big = 0.0;
    for (int j = 0; j < n; ++j) {
        int col = s->eq[j];
        if (col < 0)
            continue;
        double h = 1e-6 * fmax(1.0, fabs(q[j])), save = q[j];
        memset(fp, 0, (size_t)n * sizeof *fp);
        memset(fm, 0, (size_t)n * sizeof *fm);
        q[j] = save + h;
        bk_assemble_loads(s, q, x, fp, NULL);
        q[j] = save - h;
        bk_assemble_loads(s, q, x, fm, NULL);
        q[j] = save;
        for (int i = 0; i < n; ++i) {
            int row = s->eq[i];
            if (row < 0)
                continue;
            double a = 0.0;
            for (int k = s->Ap[col]; k < s->Ap[col + 1]; ++k)
                if (s->Ai[k] == row)
                    a = Ax[k];
            double d = (fp[i] - fm[i]) / (2.0 * h);
            err = fmax(err, fabs(a - d));
            big = fmax(big, fabs(d));
        }
    }
    printf("%.6e %.6e\n", err, big);
    free(q), free(f), free(fp), free(fm), free(Ax);
    bk_system_free(s);
    bk_model_free(m);
    return 0;
}
