/* contact_roll_check.c -- friction that turns sections and bodies, on a
 * model file: the contact interaction's friction on a rolling section
 * (runtime/assembly/contact_force.c assemble_roll: friction on the surface
 * point y = x + R(p) a of a gef rod, its moment on the node's quaternion), or
 * the body_contact interaction (runtime/assembly/body_contact.c: a body's
 * points y = r + R(p) a against a fixed primitive).  The interaction's own
 * residual and Jacobian, its Jacobian against central differences of its
 * residual, at states displaced from an accepted one by three amplitudes (the
 * points' slips below, across and beyond the slip tolerance: stick,
 * transition, slip).  A gef rod or a body lies on a primitive (nodes and
 * bodies: 7 DOF, r then p): the check displaces x, y and the quaternions, z
 * by little (a body turns about z).
 *   contact_roll_check MODEL_FILE A INTERACTION
 *     ->  "jac_err jac_max force_max rolling"
 * (rolling: the number of DOFs of quaternions that the residual reaches, > 0
 * when friction turns the sections or the body). */
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

static const char *which = "contact";

static const bk_interaction *contact(const bk_system *s)
{
    for (int k = 0; k < s->ninter; ++k)
        if (strcmp(s->inter[k].ops->name, which) == 0)
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
    if (argc != 4)
        return 64;
    const double A = atof(argv[2]);
    which = argv[3];
    bk_model *m = bk_model_read(argv[1], bk_linked_pairs, bk_nlinked_pairs, stderr);
    bk_system *s = m ? bk_system_create(m, stderr) : NULL;
    if (!s || !contact(s))
        return 1;
    const int n = m->ndof;
    double *q = malloc((size_t)n * sizeof *q), *f = malloc((size_t)n * sizeof *f);
    double *fp = malloc((size_t)n * sizeof *fp), *fm = malloc((size_t)n * sizeof *fm);
    double *Ax = malloc((size_t)s->nnz * sizeof *Ax);
    /* the rod's DOFs (its elements': gef; rod 1) and a body's (rod 2), k their place in a node (r, p) */
    int *rod = calloc((size_t)n, sizeof *rod), *k7 = calloc((size_t)n, sizeof *k7);
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = bk_elem_type(m, e);
        const int kind = strcmp(et->name, "gef") == 0 ? 1 : et->ndof == 7 ? 2 : 0;
        for (int a = 0; kind && a < et->ndof; ++a)
            rod[m->elems[e].dofs[a]] = kind, k7[m->elems[e].dofs[a]] = a % 7;
    }
    /* accepted: the sections turned (quaternions displaced), a body about z, the centreline where it is */
    for (int i = 0; i < n; ++i)
        q[i] = m->q0[i] + (rod[i] == 1 && k7[i] >= 3 ? 0.2 * sin(0.9 * i + 0.4) : rod[i] == 2 && k7[i] == 6 ? 0.1 : 0.0);
    const bk_path path = {.factor = 1.0, .x = 1.0};
    bk_interactions_accept(s, q, &path);
    /* then displaced along the ground by A (the surface points by about A), across it by little */
    for (int i = 0; i < n; ++i) {
        const double d = !rod[i] ? 1e-7 * sin(0.7 * i) : k7[i] == 2 ? 1e-6 * A / 1e-3 * sin(2.1 * i)
                         : k7[i] < 2 ? A * sin(1.7 * i + 0.3)
                         : rod[i] == 1 ? 0.25 * A / 0.005 * sin(1.3 * i) : k7[i] == 6 ? 2.0 * A : 1e-3 * A * sin(1.3 * i);
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
