/* springs_check.c -- the spring interaction (runtime/assembly/spring.c) of a
 * model file against differences: its forces against central differences of
 * the springs' energy k/2 (l - l0)^2, the ends' positions evaluated here by
 * the elements' own frame() kernels (bk_eval_point), not by the module's shape
 * functions; its Jacobian against central differences of its forces; both at
 * a deformed, turned state.  The springs' data is read here from the model's
 * record "spring" with sscanf (a second reader).
 *   springs_check MODEL_FILE  ->  "force_err force_max jac_err jac_max" */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/system.h"
#include "model/model.h"

extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;

#define MAXS 16

typedef struct sp {
    int e[2];
    double xi[2], x0[3], k, l0;
} sp;

static int nsp;
static sp sps[MAXS];

static double energy(const bk_model *m, const double *q)
{
    double E = 0.0;
    for (int k = 0; k < nsp; ++k) {
        double x[2][3];
        for (int end = 0; end < 2; ++end)
            if (sps[k].e[end] >= 0)
                bk_eval_point(m, q, sps[k].e[end], sps[k].xi[end], x[end], NULL);
            else
                memcpy(x[end], sps[k].x0, sizeof x[end]);
        const double l = sqrt(pow(x[0][0] - x[1][0], 2) + pow(x[0][1] - x[1][1], 2) + pow(x[0][2] - x[1][2], 2));
        E += 0.5 * sps[k].k * (l - sps[k].l0) * (l - sps[k].l0);
    }
    return E;
}

static void forces(bk_system *s, const double *q, double *f, double *Ax)
{
    memset(f, 0, (size_t)s->m->ndof * sizeof *f);
    if (Ax)
        memset(Ax, 0, (size_t)s->nnz * sizeof *Ax);
    bk_assemble_interactions(s, q, &(bk_path){.factor = 1.0, .x = 1.0}, f, Ax);
}

int main(int argc, char **argv)
{
    if (argc != 2)
        return 64;
    bk_model *m = bk_model_read(argv[1], bk_linked_pairs, bk_nlinked_pairs, stderr);
    bk_system *s = m ? bk_system_create(m, stderr) : NULL;
    const bk_model_record *rec = m ? bk_model_record_find(m, "spring") : NULL;
    if (!s || !rec)
        return 1;
    const char *p = strstr(rec->text, "springs");
    int used;
    if (!p || sscanf(p, "springs %d%n", &nsp, &used) != 1 || nsp > MAXS)
        return 1;
    p += used;
    for (int k = 0; k < nsp; ++k) {
        char name[64];
        sp *c = &sps[k];
        if (sscanf(p, " spring %63s %d %lf %d %lf %lf %lf %lf %lf %lf%n", name, &c->e[0], &c->xi[0], &c->e[1],
                   &c->xi[1], &c->x0[0], &c->x0[1], &c->x0[2], &c->k, &c->l0, &used) != 10)
            return 1;
        p += used;
    }
    const int n = m->ndof;
    double *q = malloc((size_t)n * sizeof *q), *f = malloc((size_t)n * sizeof *f);
    double *fp = malloc((size_t)n * sizeof *fp), *fm = malloc((size_t)n * sizeof *fm);
    double *Ax = malloc((size_t)s->nnz * sizeof *Ax);
    for (int i = 0; i < n; ++i)            /* a deformed, turned state */
        q[i] = m->q0[i] + (s->eq[i] >= 0 ? 0.05 * sin(1.7 * i + 0.3) : 0.0);
    forces(s, q, f, Ax);
    double ferr = 0.0, fmax_ = 0.0, jerr = 0.0, jmax = 0.0;
    for (int j = 0; j < n; ++j) {
        if (s->eq[j] < 0)
            continue;
        const double h = 1e-6 * fmax(1.0, fabs(q[j])), save = q[j];
        q[j] = save + h;
        const double Ep = energy(m, q);
        forces(s, q, fp, NULL);
        q[j] = save - h;
        const double Em = energy(m, q);
        forces(s, q, fm, NULL);
        q[j] = save;
        const double dE = (Ep - Em) / (2.0 * h);
        ferr = fmax(ferr, fabs(dE - f[j]));
        fmax_ = fmax(fmax_, fabs(dE));
        const int col = s->eq[j];
        for (int i = 0; i < n; ++i) {
            const int row = s->eq[i];
            if (row < 0)
                continue;
            double a = 0.0;
            for (int k = s->Ap[col]; k < s->Ap[col + 1]; ++k)
                if (s->Ai[k] == row)
                    a = Ax[k];
            const double d = (fp[i] - fm[i]) / (2.0 * h);
            jerr = fmax(jerr, fabs(a - d));
            jmax = fmax(jmax, fabs(d));
        }
    }
    printf("%.6e %.6e %.6e %.6e\n", ferr, fmax_, jerr, jmax);
    free(q), free(f), free(fp), free(fm), free(Ax);
    bk_system_free(s);
    bk_model_free(m);
    return 0;
}
