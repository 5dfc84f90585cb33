/* dynamics_work.c -- the work arrays of the time integration, the mass
 * matrix of the free DOFs (assembled once, compressed) and its products, and
 * the velocity- and acceleration-dependent element forces (Kelvin-Voigt
 * damping, rotary inertia) with their Newton-matrix terms, and the step
 * predictors (see dynamics_impl.h). */
#include "analysis/dynamics_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


static double *dalloc(size_t n)
{
    return calloc(n ? n : 1, sizeof(double));
}

void bk_dyn_work_free(dyn_work *w)
{
    double **p[] = {&w->qd, &w->qdd, &w->a, &w->nu, &w->q_s, &w->qd_s, &w->qdd_s, &w->a_s, &w->nu_s,
                    &w->q_m, &w->qd_m, &w->fint, &w->fext, &w->fgrav, &w->Mx, &w->tmp, &w->qe,
                    &w->qde, &w->qdde, &w->fe, &w->K1, &w->K2, &w->K3};
    for (size_t i = 0; i < sizeof p / sizeof *p; ++i) {
        free(*p[i]);
        *p[i] = NULL;
    }
    free(w->Mp), free(w->Mi), free(w->Mv);
    w->Mp = w->Mi = NULL, w->Mv = NULL;
}

int bk_dyn_work_alloc(dyn_work *w, const bk_system *s)
{
    const bk_model *m = s->m;
    size_t nd = (size_t)m->ndof, ne = (size_t)s->neq, nc = (size_t)s->ncon, nnz = (size_t)s->nnz;
    size_t md = (size_t)s->maxdof;
    w->nd = m->ndof;
    w->ne = s->neq;
    w->nc = s->ncon;
    w->qd = dalloc(nd), w->qdd = dalloc(nd), w->a = dalloc(nd), w->nu = dalloc(nc);
    w->q_s = dalloc(nd), w->qd_s = dalloc(nd), w->qdd_s = dalloc(nd), w->a_s = dalloc(nd);
    w->nu_s = dalloc(nc);
    w->q_m = dalloc(nd), w->qd_m = dalloc(nd);
    w->fint = dalloc(nd), w->fext = dalloc(nd), w->fgrav = dalloc(nd);
    w->Mx = dalloc(nnz), w->tmp = dalloc(nd > ne ? nd : ne);
    w->qe = dalloc(md), w->qde = dalloc(md), w->qdde = dalloc(md), w->fe = dalloc(md);
    w->K1 = dalloc(md * md), w->K2 = dalloc(md * md), w->K3 = dalloc(md * md);
    double *all[] = {w->qd, w->qdd, w->a, w->nu, w->q_s, w->qd_s, w->qdd_s, w->a_s, w->nu_s, w->q_m, w->qd_m, w->fint,
                     w->fext, w->fgrav, w->Mx, w->tmp, w->qe, w->qde, w->qdde,
                     w->fe, w->K1, w->K2, w->K3};
    for (size_t i = 0; i < sizeof all / sizeof *all; ++i)
        if (!all[i])
            return -1;
    w->Mp = malloc(((size_t)s->nfree + 1) * sizeof *w->Mp);
    w->Mi = malloc((nnz ? nnz : 1) * sizeof *w->Mi);
    w->Mv = dalloc(nnz);
    w->mass_gen = s->pattern_gen;
    return w->Mp && w->Mi && w->Mv ? 0 : -1;
}

int bk_dyn_mass_follow(const bk_system *s, dyn_work *w)
{
    if (w->mass_gen == s->pattern_gen)
        return 0;
    double *Mx = realloc(w->Mx, (size_t)(s->nnz > 0 ? s->nnz : 1) * sizeof *Mx);
    if (!Mx)
        return -1;
    w->Mx = Mx;
    bk_dyn_assemble_mass(s, w->Mx, w->K1, w->K2);
    w->mass_gen = s->pattern_gen;
    return 0;
}

/* Constant mass matrix (translational inertia) on the free DOFs, in the pattern
 * of the Newton matrix; work and Me: element buffers of maxdof^2. */
void bk_dyn_assemble_mass(const bk_system *s, double *Mx, double *work, double *Me)
{
    memset(Mx, 0, (size_t)s->nnz * sizeof *Mx);
    for (int e = 0; e < s->m->nelem; ++e) {
        bk_element_mass(s->m, e, work, Me);
        bk_scatter_matrix(s, e, Me, 1.0, Mx);
    }
}

/* y = A x over the free DOFs for A in compressed columns (Ap, Ai, Ax) over the
 * equations, rows beyond the free ones ignored; x, y indexed by DOF (y over all
 * ndof), fdof maps equations to DOFs. */
static void csc_free_matvec(int ndof, int nfree, const int *fdof, const int *Ap, const int *Ai,
                            const double *Ax, const double *x, double *y)
{
    memset(y, 0, (size_t)ndof * sizeof *y);
    for (int j = 0; j < nfree; ++j) {
        double xj = x[fdof[j]];
        if (xj == 0.0)
            continue;
        for (int k = Ap[j]; k < Ap[j + 1]; ++k)
            if (Ai[k] < nfree)
                y[fdof[Ai[k]]] += Ax[k] * xj;
    }
}

/* y = A x, A in the Newton pattern (its free block). */
void bk_dyn_free_matvec(const bk_system *s, const int *fdof, const double *Ax, const double *x,
                        double *y)
{
    csc_free_matvec(s->m->ndof, s->nfree, fdof, s->Ap, s->Ai, Ax, x, y);
}

/* The free block's nonzeros of the mass matrix Mx (in the Newton pattern, where
 * the mass couples no two components of a vector and no multipliers: about a
 * third of the pattern) into w->Mp, Mi, Mv. */
void bk_dyn_compact_mass(const bk_system *s, dyn_work *w, const double *Mx)
{
    int n = 0;
    w->Mp[0] = 0;
    for (int j = 0; j < s->nfree; ++j) {
        for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k)
            if (s->Ai[k] < s->nfree && Mx[k] != 0.0)
                w->Mi[n] = s->Ai[k], w->Mv[n++] = Mx[k];
        w->Mp[j + 1] = n;
    }
}

/* y = M x over the free DOFs, with the compact mass. */
void bk_dyn_mass_matvec(const bk_system *s, const dyn_work *w, const int *fdof, const double *x, double *y)
{
    csc_free_matvec(s->m->ndof, s->nfree, fdof, w->Mp, w->Mi, w->Mv, x, y);
}

double bk_dyn_dot_free(const bk_system *s, const int *fdof, const double *a, const double *b)
{
    double d = 0.0;
    for (int j = 0; j < s->nfree; ++j)
        d += a[fdof[j]] * b[fdof[j]];
    return d;
}

/* Equation -> DOF map for free DOFs (built once). */
int *bk_dyn_free_dofs(const bk_system *s)
{
    int *d = malloc((size_t)(s->nfree ? s->nfree : 1) * sizeof *d);
    if (!d)
        return NULL;
    for (int i = 0; i < s->m->ndof; ++i)
        if (s->eq[i] >= 0)
            d[s->eq[i]] = i;
    return d;
}

/* Velocity- and acceleration-dependent element forces: Kelvin-Voigt damping and
 * rotary inertia.  Adds to fint and, with Ax, their contributions
 * gp C + bp M + kp K to the Newton matrix; returns the rotary kinetic energy. */
double bk_dyn_element_dynamics(const bk_system *s, dyn_work *w, const double *q, double gp, double bp,
                               double kp, double *fint, double *Ax)
{
    const bk_model *m = s->m;
    double Trot = 0.0;
    w->p_visc = 0.0;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        const bk_element *et = p->element;
        const bk_mat *mat = &m->mats[el->mat];
        int visc = mat->nvisc > 0 && p->viscous != NULL;
        if (!visc && !et->rotary)
            continue;
        bk_gather(m, e, q, w->qe);
        bk_gather(m, e, w->qd, w->qde);
        bk_gather(m, e, w->qdd, w->qdde);
        if (visc) {
            p->viscous(w->qe, w->qde, m->tabs[el->geom], mat->visc, w->fe, w->K1, w->K2);
            bk_scatter(m, e, w->fe, 1.0, fint);
            for (int i = 0; i < et->ndof; ++i)
                w->p_visc += w->fe[i] * w->qde[i];
            if (Ax) {
                bk_scatter_matrix(s, e, w->K1, gp, Ax);
                bk_scatter_matrix(s, e, w->K2, kp, Ax);
            }
        }
        if (et->rotary) {
            double T = 0.0;
            et->rotary(m->geoms[el->geom], w->qe, w->qde, w->qdde, w->fe, w->K1, w->K2, w->K3, &T);
            Trot += mat->rho * T;
            bk_scatter(m, e, w->fe, mat->rho, fint);
            if (Ax) {
                bk_scatter_matrix(s, e, w->K1, mat->rho * bp, Ax);
                bk_scatter_matrix(s, e, w->K2, mat->rho * gp, Ax);
                bk_scatter_matrix(s, e, w->K3, mat->rho * kp, Ax);
            }
        }
    }
    return Trot;
}


void bk_dyn_predict(const bk_system *s, dyn_work *w, double *q, double h, double am, double af, double bet,
                    double gam, int position)
{
    for (int i = 0; i < s->m->ndof; ++i) {
        if (s->eq[i] < 0)
            continue;
        double an;                                 /* the algorithmic acceleration a_{n+1} */
        if (position) {
            an = -(w->qd_s[i] / h + (0.5 - bet) * w->a_s[i]) / bet;
            q[i] = w->q_s[i];
            w->qdd[i] = ((1.0 - am) * an + am * w->a_s[i] - af * w->qdd_s[i]) / (1.0 - af);
        } else {
            an = (w->qdd_s[i] - am * w->a_s[i]) / (1.0 - am);
            q[i] = w->q_s[i] + h * w->qd_s[i] + h * h * ((0.5 - bet) * w->a_s[i] + bet * an);
            w->qdd[i] = w->qdd_s[i];
        }
        w->qd[i] = w->qd_s[i] + h * ((1.0 - gam) * w->a_s[i] + gam * an);
    }
}
