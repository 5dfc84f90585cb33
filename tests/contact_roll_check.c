/* contact_roll_check.c -- the contact interaction's friction on a rolling
 * section (runtime/assembly/contact_force.c assemble_roll: friction on the
 * surface point y = x + R(p) a of a gef rod, its moment on the node's
 * quaternion) on a model file: the contact interaction's own residual and
 * Jacobian, its Jacobian against central differences of its residual, at
 * states displaced from an accepted one by three amplitudes (the points'
 * slips below, across and beyond the slip tolerance: stick, transition,
 * slip).  The rod is a gef beam lying on a primitive (nodes: 7 DOF, r then
 * p): the check displaces x, y and the quaternions, z by little.
 *   contact_roll_check MODEL_FILE A  ->  "jac_err jac_max force_max rolling"
 * (rolling: the number of DOFs of quaternions that the contact's residual
 * reaches, > 0 when friction turns the sections). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/contact_force.h"
#include "assembly/interaction.h"
#include "assembly/system.h"
#include "model/model.h"

extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;

static const bk_interaction *contact(const bk_system *s)
{
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops == &bk_contact_ops)
            return &s->inter[k];
    return NULL;
}

static int forces(bk_system *s, const double *q, double *f, double *Ax)
{
    const bk_interaction *c = contact(s);
    memset(f, 0, (size_t)s->m->ndof * sizeof *f);
    if (Ax)
        memset(Ax, 0, (size_t)s->nnz * sizeof *Ax);
    return c->ops->assemble(c->self, s, q, &(bk_path){.factor = 1.0, .x = 1.0}, f, Ax);
}

int main(int argc, char **argv)
{
    if (argc != 3)
        return 64;
    const double A = atof(argv[2]);
    bk_model *m = bk_model_read(argv[1], bk_linked_pairs, bk_nlinked_pairs, stderr);
    bk_system *s = m ? bk_system_create(m, stderr) : NULL;
    if (!s || !contact(s))
        return 1;
    const int n = m->ndof;
    double *q = malloc((size_t)n * sizeof *q), *f = malloc((size_t)n * sizeof *f);
    double *fp = malloc((size_t)n * sizeof *fp), *fm = malloc((size_t)n * sizeof *fm);
    double *Ax = malloc((size_t)s->nnz * sizeof *Ax);
    /* the rod's DOFs (its elements': gef), k their place in a node (r, p); a body's are moved by little */
    int *rod = calloc((size_t)n, sizeof *rod), *k7 = calloc((size_t)n, sizeof *k7);
    for (int e = 0; e < m->nelem; ++e)
        if (strcmp(bk_elem_type(m, e)->name, "gef") == 0)
            for (int a = 0; a < bk_elem_type(m, e)->ndof; ++a)
                rod[m->elems[e].dofs[a]] = 1, k7[m->elems[e].dofs[a]] = a % 7;
    /* accepted: the sections turned (quaternions displaced), the centreline where it is */
    for (int i = 0; i < n; ++i)
        q[i] = m->q0[i] + (rod[i] && k7[i] >= 3 ? 0.2 * sin(0.9 * i + 0.4) : 0.0);
    const bk_path path = {.factor = 1.0, .x = 1.0};
    bk_interactions_accept(s, q, &path);
    /* then displaced along the ground by A (the surface points by about A), across it by little */
    for (int i = 0; i < n; ++i) {
        const double d = !rod[i] ? 1e-7 * sin(0.7 * i) : k7[i] == 2 ? 1e-6 * A / 1e-3 * sin(2.1 * i)
                         : k7[i] < 2 ? A * sin(1.7 * i + 0.3) : 0.25 * A / 0.005 * sin(1.3 * i);
        q[i] += s->eq[i] >= 0 ? d : 0.0;
    }
    if (forces(s, q, f, Ax) != 0)
        return 2;
    double jerr = 0.0, jmax = 0.0, fmx = 0.0;
    int rolling = 0;
    for (int i = 0; i < n; ++i) {
        fmx = fmax(fmx, fabs(f[i]));
        rolling += rod[i] && k7[i] >= 3 && f[i] != 0.0;
    }
    for (int j = 0; j < n; ++j) {
        if (s->eq[j] < 0)
            continue;
        const double h = 1e-8, save = q[j];
        q[j] = save + h;
        int bad = forces(s, q, fp, NULL);
        q[j] = save - h;
        bad |= forces(s, q, fm, NULL);
        q[j] = save;
        if (bad)
            return 3;
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
    printf("%.6e %.6e %.6e %d\n", jerr, jmax, fmx, rolling);
    free(q), free(f), free(fp), free(fm), free(Ax), free(rod), free(k7);
    bk_system_free(s);
    bk_model_free(m);
    return 0;
}
