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
                    &w->qde, &w->qdde, &w->fe, &w->K1, &w->K2, &w->K3, &w->va};
    for (size_t i = 0; i < sizeof p / sizeof *p; ++i) {
        free(*p[i]);
        *p[i] = NULL;
    }
    free(w->Mp), free(w->Mi), free(w->Mv);
    w->Mp = w->Mi = NULL, w->Mv = NULL;
    double **v[] = {&w->vq, &w->vqd, &w->vtab, &w->vvisc, &w->vf, &w->vK};
    for (size_t i = 0; i < sizeof v / sizeof *v; ++i) {
        free(*v[i]);
        *v[i] = NULL;
    }
}

/* Element e's Kelvin-Voigt damping goes BK_LANES per call: its pair has the
 * lane kernels, its material the pair's parameters, and it has no rotary
 * inertia (whose terms would then come before the damping's). */
static int visc_lane_elem(const bk_model *m, int e)
{
    const bk_pair *p = m->pairs[m->elems[e].pair];
    const bk_mat *mat = &m->mats[m->elems[e].mat];
    return p->viscous_lanes && p->viscous_force_lanes && mat->nvisc > 0 && mat->nvisc == p->nvisc &&
           !p->element->rotary;
}

/* Elements e .. e+n-1 go in one lane-kernel call: n, the run of up to BK_LANES
 * elements of e's pair that visc_lane_elem takes (1 where it takes none). */
static int visc_lane_run(const bk_model *m, int e)
{
    int n = 1;
    if (visc_lane_elem(m, e))
        while (n < BK_LANES && e + n < m->nelem && m->elems[e + n].pair == m->elems[e].pair &&
               visc_lane_elem(m, e + n))
            ++n;
    return n;
}

/* n doubles aligned to 64 bytes (the lane kernels' vector loads), zeroed. */
static double *alloc_lanes(size_t n)
{
    size_t bytes = (n * sizeof(double) + 63) / 64 * 64;
    double *x = aligned_alloc(64, bytes ? bytes : 64);
    if (x)
        memset(x, 0, bytes ? bytes : 64);
    return x;
}

static int visc_lanes_alloc(dyn_work *w, const bk_model *m)
{
    size_t nd = 0, nt = 0;
    for (int e = 0; e < m->nelem; ++e)
        if (visc_lane_elem(m, e)) {
            const bk_pair *p = m->pairs[m->elems[e].pair];
            if ((size_t)p->element->ndof > nd)
                nd = (size_t)p->element->ndof;
            if ((size_t)p->ntab > nt)
                nt = (size_t)p->ntab;
        }
    if (nd == 0)
        return 0;
    const size_t L = BK_LANES;
    /* the lane groups' tables, lane-ordered once (constant through the run): group
     * g (the g-th run of visc_lane_run()) at vtab + g L nt */
    size_t ng = 0;
    for (int e = 0; e < m->nelem; e += visc_lane_run(m, e))
        ng += visc_lane_elem(m, e) != 0;
    w->vtab = alloc_lanes(ng * L * nt);
    w->vnt = nt;
    if (w->vtab)
        for (int e = 0, g = 0; e < m->nelem; e += visc_lane_run(m, e)) {
            if (!visc_lane_elem(m, e))
                continue;
            const int n = visc_lane_run(m, e), ntab = m->pairs[m->elems[e].pair]->ntab;
            double *vt = w->vtab + (size_t)g++ * L * nt;
            for (size_t l = 0; l < L; ++l) {
                const double *tab = m->tabs[m->elems[e + ((int)l < n ? (int)l : n - 1)].geom];
                for (int k = 0; k < ntab; ++k)
                    vt[k * L + l] = tab[k];
            }
        }
    w->vq = alloc_lanes(L * nd), w->vqd = alloc_lanes(L * nd);
    w->vvisc = alloc_lanes(L * BK_MAT_MAXPARAM), w->vf = alloc_lanes(L * nd), w->vK = alloc_lanes(L * nd * nd);
    return w->vq && w->vqd && w->vtab && w->vvisc && w->vf && w->vK ? 0 : -1;
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
    w->q_m = dalloc(nd), w->qd_m = dalloc(nd), w->va = dalloc(nd);
    w->fint = dalloc(nd), w->fext = dalloc(nd), w->fgrav = dalloc(nd);
    w->Mx = dalloc(nnz), w->tmp = dalloc(nd > ne ? nd : ne);
    w->qe = dalloc(md), w->qde = dalloc(md), w->qdde = dalloc(md), w->fe = dalloc(md);
    w->K1 = dalloc(md * md), w->K2 = dalloc(md * md), w->K3 = dalloc(md * md);
    double *all[] = {w->qd, w->qdd, w->a, w->nu, w->q_s, w->qd_s, w->qdd_s, w->a_s, w->nu_s, w->q_m, w->qd_m, w->fint,
                     w->fext, w->fgrav, w->Mx, w->tmp, w->qe, w->qde, w->qdde,
                     w->fe, w->K1, w->K2, w->K3, w->va};
    for (size_t i = 0; i < sizeof all / sizeof *all; ++i)
        if (!all[i])
            return -1;
    w->Mp = malloc(((size_t)s->nfree + 1) * sizeof *w->Mp);
    w->Mi = malloc((nnz ? nnz : 1) * sizeof *w->Mi);
    w->Mv = dalloc(nnz);
    w->mass_gen = s->pattern_gen;
    if (visc_lanes_alloc(w, m) != 0)
        return -1;
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

/* Kelvin-Voigt damping of the elements e0 .. e0+n-1 (n <= BK_LANES, one pair,
 * visc_lane_elem) in one lane-kernel call: the force into fint and its power into
 * w->p_visc; with Ax, gp C + kp df/dq (bk_pair.viscous_lanes).  Unused
 * lanes repeat the last element (valid inputs, outputs ignored).  Every element's
 * terms are added in element order, as one element at a time would. */
static void visc_lanes(const bk_system *s, dyn_work *w, int e0, int n, const double *vtab, const double *q,
                       double gp, double kp, double *fint, double *Ax)
{
    const bk_model *m = s->m;
    const bk_pair *p = m->pairs[m->elems[e0].pair];
    const int nd = p->element->ndof, nv = p->nvisc, L = BK_LANES;
    double *restrict vq = w->vq, *restrict vqd = w->vqd;
    for (int l = 0; l < L; ++l) {
        const bk_elem *el = &m->elems[e0 + (l < n ? l : n - 1)];
        const int *d = el->dofs;
        const double *visc = m->mats[el->mat].visc;
        for (int k = 0; k < nd; ++k) {
            vq[k * L + l] = q[d[k]];
            vqd[k * L + l] = w->qd[d[k]];
        }
        for (int k = 0; k < nv; ++k)
            w->vvisc[k * L + l] = visc[k];
    }
    const int matrix = Ax && (gp != 0.0 || kp != 0.0);
    if (matrix)
        p->viscous_lanes(vq, vqd, vtab, w->vvisc, gp, kp, w->vf, w->vK);
    else
        p->viscous_force_lanes(vq, vqd, vtab, w->vvisc, w->vf);
    double pv = w->p_visc;
    for (int l = 0; l < n; ++l) {
        const int e = e0 + l, *d = m->elems[e].dofs;
        for (int k = 0; k < nd; ++k) {
            const double v = w->vf[k * L + l];
            fint[d[k]] += v;
            pv += v * vqd[k * L + l];
        }
        w->p_visc = pv;
        if (matrix) {
            const int *sl = s->eslot + s->eslot_off[e];
            for (int k = 0; k < nd * nd; ++k) {
                const double v = w->vK[(size_t)k * L + l];
                if (sl[k] >= 0 && v != 0.0)
                    Ax[sl[k]] += v;
            }
        }
    }
}

/* Velocity- and acceleration-dependent element forces: Kelvin-Voigt damping and
 * rotary inertia.  Adds to fint and, with Ax, their contributions
 * gp C + bp M + kp K to the Newton matrix; returns the rotary kinetic energy.
 * The damping's matrix part gp C + kp df/dq comes from one kernel call
 * (bk_pair.viscous), and only when Ax is given and a factor is not zero; else
 * only the force is evaluated (bk_pair.viscous_force), BK_LANES elements per
 * call where the pair offers lane kernels. */
double bk_dyn_element_dynamics(const bk_system *s, dyn_work *w, const double *q, double gp, double bp,
                               double kp, double *fint, double *Ax)
{
    const bk_model *m = s->m;
    double Trot = 0.0;
    w->p_visc = 0.0;
    for (int e = 0, g = 0; e < m->nelem;) {
        if (w->vq && visc_lane_elem(m, e)) {
            const int n = visc_lane_run(m, e);
            visc_lanes(s, w, e, n, w->vtab + (size_t)g++ * BK_LANES * w->vnt, q, gp, kp, fint, Ax);
            e += n;
            continue;
        }
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        const bk_element *et = p->element;
        const bk_mat *mat = &m->mats[el->mat];
        int visc = mat->nvisc > 0 && p->viscous != NULL;
        if (!visc && !et->rotary) {
            ++e;
            continue;
        }
        bk_gather(m, e, q, w->qe);
        bk_gather(m, e, w->qd, w->qde);
        bk_gather(m, e, w->qdd, w->qdde);
        if (visc) {
            if (Ax && (gp != 0.0 || kp != 0.0)) {
                p->viscous(w->qe, w->qde, m->tabs[el->geom], mat->visc, gp, kp, w->fe, w->K1);
                bk_scatter_matrix(s, e, w->K1, 1.0, Ax);
            } else {
                p->viscous_force(w->qe, w->qde, m->tabs[el->geom], mat->visc, w->fe);
            }
            bk_scatter(m, e, w->fe, 1.0, fint);
            for (int i = 0; i < et->ndof; ++i)
                w->p_visc += w->fe[i] * w->qde[i];
        }
        if (et->rotary) {
            double T = 0.0;
            if (w->frame)           /* in the inertial frame and back (dyn_frame.h) */
                bk_frame_rotary_in(w->frame, et, w->qe, w->qde, w->qdde);
            et->rotary(m->geoms[el->geom], w->qe, w->qde, w->qdde, w->fe, w->K1, w->K2, w->K3, &T);
            if (w->frame)
                bk_frame_rotary_out(w->frame, et, w->fe, Ax ? w->K1 : NULL, w->K2, w->K3);
            Trot += mat->rho * T;
            bk_scatter(m, e, w->fe, mat->rho, fint);
            if (Ax) {
                bk_scatter_matrix(s, e, w->K1, mat->rho * bp, Ax);
                bk_scatter_matrix(s, e, w->K2, mat->rho * gp, Ax);
                bk_scatter_matrix(s, e, w->K3, mat->rho * kp, Ax);
            }
        }
        ++e;
    }
    return Trot;
}

const double *bk_dyn_power_velocity(const bk_system *s, dyn_work *w, const double *q, double t)
{
    if (!w->frame)
        return w->qd;
    bk_frame_at(w->frame, t);
    bk_frame_velocity(w->frame, s->m, q, w->qd, w->va);
    return w->va;
}

double bk_dyn_kinetic(const bk_system *s, dyn_work *w, const int *fdof, const double *q, double t)
{
    const double *v = bk_dyn_power_velocity(s, w, q, t);
    bk_dyn_mass_matvec(s, w, fdof, v, w->tmp);
    return 0.5 * bk_dyn_dot_free(s, fdof, v, w->tmp) + bk_dyn_element_dynamics(s, w, q, 0, 0, 0, w->tmp, NULL);
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
