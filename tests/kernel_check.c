/* kernel_check.c -- checks every linked element x material kernel against
 * finite differences and rigid motions.  Linked with a kernel table of all
 * generated pairs (bk_linked_pairs); tests/test_kernels.py builds it with the
 * sanitizers on, runs it and asserts on the numbers it prints.
 *
 * Per pair and per element geometry, at NSTATE random deformed states (every
 * other one close to a rigid motion, where rotation functions use their
 * small-angle branches), each a rigid motion of any size plus a perturbation:
 *   fd_force    max_j |f_j - dU/dq_j (4th-order central difference)| / max|f|
 *               (max|f| not below the force of a 1 % strain)
 *   fd_tangent  max_ij |K_ij - df_i/dq_j (4th-order central)| / max|K|
 *   sym         max |K - K^T| / max|K|
 *   consist     max |f(force) - f(force_tangent)| / max|f|
 *   fd_moment   for elements that carry moments: max_ij |dQ_ij - dQ_i/dq_j
 *               (4th-order central)| / max|dQ| for a random moment on the
 *               section at each node (the Jacobian used by Newton)
 * and, for pairs with Kelvin-Voigt damping, at each deformed state with random
 * velocities qd:
 *   fd_viscous     max |C_ij - df_i/dqd_j (central)| / max|C|, C from viscous(gc=1, gk=0)
 *   fd_dissipation max |f_j - dD/dqd_j (4th-order central)| / max|f| and
 *                  |f . qd - 2 D| / |f . qd|, D the Rayleigh dissipation function
 *                  viscous_force() returns
 *   fd_visc_tangent max |K_ij - df_i/dq_j (4th-order central, qd held)| / max|K|,
 *                  K from viscous(gc=0, gk=1)
 *   visc_sym       asymmetry of C
 *   visc_consist   force of viscous() against viscous_force(), and
 *                  viscous(gc, gk) against gc C + gk K formed apart
 *   visc_lanes     the lane kernels against the one-element kernels (-1: none)
 *   (all -1 for pairs without damping)
 * and at NSTATE random rigid motions of the reference element:
 *   rigid_energy  |U| / (energy of a unit strain)
 *   rigid_force   max|f| / (force of a unit strain)
 * and, for pairs with lane kernels, one call of force_lanes and
 * force_tangent_lanes on BK_LANES different deformed states (lanes alternate
 * between the two geometries' tables, material parameters differ per lane)
 * against force() / force_tangent() of each lane's element:
 *   lanes_f     max |f_lane - f| / max|f|, force and force + tangent kernels
 *   lanes_K     max |K_lane - K| / max|K|
 * (both -1 when the pair has no lane kernels).
 * Output: one line per pair and geometry, "key=value" fields.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bk_kernel.h"

extern const bk_pair *const bk_linked_pairs[];
extern const int bk_nlinked_pairs;

#define MAXD 256

typedef struct rng {
    unsigned long long s;
} rng;

static double urand(rng *r) /* uniform in [-1, 1) */
{
    r->s ^= r->s << 13;
    r->s ^= r->s >> 7;
    r->s ^= r->s << 17;
    return 2.0 * ((double)(r->s >> 11) / 9007199254740992.0) - 1.0;
}

static void random_rotation(rng *r, double R[9], double qr[4])
{
    double q[4], n = 0.0;
    do {
        n = 0.0;
        for (int i = 0; i < 4; ++i) {
            q[i] = urand(r);
            n += q[i] * q[i];
        }
    } while (n > 1.0 || n < 1e-3);
    n = sqrt(n);
    for (int i = 0; i < 4; ++i)
        q[i] /= n;
    double w = q[0], x = q[1], y = q[2], z = q[3];
    for (int i = 0; i < 4; ++i)
        qr[i] = q[i];
    double M[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                   2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                   2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
    memcpy(R, M, sizeof M);
}

/* Reference coordinates of the straight element (element->reference) moved by
 * the rigid motion x -> R x + x0: positions move, slope vectors rotate,
 * quaternions are pre-multiplied by the rotation's quaternion, multipliers stay. */
static void rigid(const bk_element *e, const double *geom, const double R[9], const double qr[4],
                  const double x0[3], double *q)
{
    e->reference(geom, q);
    for (int f = 0; f < e->nfield; ++f) {
        double *v = q + e->field_dof[f];
        const bk_field_role role = e->field_role[f];
        if (role == BK_FIELD_POSITION || bk_field_is_gradient(role)) {
            double w[3];
            for (int i = 0; i < 3; ++i)
                w[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
            for (int i = 0; i < 3; ++i)
                v[i] = w[i] + (role == BK_FIELD_POSITION ? x0[i] : 0.0);
        } else if (role == BK_FIELD_QUATERNION) {
            double s = v[0], x = v[1], y = v[2], z = v[3];
            v[0] = qr[0] * s - qr[1] * x - qr[2] * y - qr[3] * z;
            v[1] = qr[0] * x + qr[1] * s + qr[2] * z - qr[3] * y;
            v[2] = qr[0] * y - qr[1] * z + qr[2] * s + qr[3] * x;
            v[3] = qr[0] * z + qr[1] * y - qr[2] * x + qr[3] * s;
        }
    }
}

/* Size of a perturbation of each DOF: positions ~ the nodes' spacing along the
 * axis (strains of the same size for any number of nodes), slopes and quaternions ~ 1,
 * curvature-like vectors ~ 1/h, multipliers ~ 1e-3. */
static void dof_scale(const bk_element *e, const double *geom, double *sc)
{
    double hmin = fmin(geom[BK_GEOM_B], geom[BK_GEOM_H]), gap = 1.0;
    for (int a = 1; a < e->nnode; ++a)             /* the nodes' spacing along the axis */
        gap = fmin(gap, fabs(e->node_xi[a] - e->node_xi[a - 1]));
    for (int f = 0; f < e->nfield; ++f) {
        const bk_field_role role = e->field_role[f];
        double v = 1.0;
        if (role == BK_FIELD_POSITION)
            v = gap * geom[BK_GEOM_L];
        else if (role == BK_FIELD_R_YY || role == BK_FIELD_R_YZ || role == BK_FIELD_R_ZZ)
            v = 1.0 / hmin;
        else if (role == BK_FIELD_MULTIPLIER)
            v = 1e-3;
        for (int i = 0; i < e->field_dim[f]; ++i)
            sc[e->field_dof[f] + i] = v;
    }
}

static double param_value(const char *name, int k)
{
    const double E = 1.0e7, nu = 0.3;
    if (!strcmp(name, "lambda"))
        return E * nu / ((1 + nu) * (1 - 2 * nu));
    if (!strcmp(name, "mu"))
        return E / (2 * (1 + nu));
    if (!strcmp(name, "kappa"))
        return 5.0e7;
    if (!strcmp(name, "lambda_m"))
        return 3.0;
    if (!strcmp(name, "c10"))
        return 1.5e6;
    if (!strcmp(name, "c01"))
        return 3.0e5;
    /* resultant stiffnesses of a 0.2 x 0.1 section with E = 1e7, nu = 0.3 */
    if (!strcmp(name, "EA"))
        return 2.0e5;
    if (!strcmp(name, "GA1") || !strcmp(name, "GA2"))
        return 6.5e4;
    if (!strcmp(name, "GJ"))
        return 90.0;
    if (!strcmp(name, "EI1"))
        return 170.0;
    if (!strcmp(name, "EI2"))
        return 670.0;
    return 1.0e6 / (k + 1);
}

static double maxabs(const double *v, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; ++i)
        m = fmax(m, fabs(v[i]));
    return m;
}

/* Lane kernels against the one-element kernels (see the header comment);
 * returns 0 when out of memory. */
static int lane_check(const bk_pair *p, const double *geom_a, const double *geom_b, const double *mat0,
                      const double *sc, rng *r, double *e_f, double *e_K)
{
    enum { W = BK_LANES };
    const bk_element *e = p->element;
    const int n = e->ndof, nt = p->ntab > 0 ? p->ntab : 1, np = p->nparam;
    double *tab[2] = {malloc((size_t)nt * sizeof(double)), malloc((size_t)nt * sizeof(double))};
    double *q = malloc((size_t)n * W * sizeof(double)), *lt = malloc((size_t)nt * W * sizeof(double));
    double *lm = malloc((size_t)(np + 1) * W * sizeof(double)), *lf = malloc((size_t)n * W * sizeof(double));
    double *lf2 = malloc((size_t)n * W * sizeof(double)), *lK = malloc((size_t)n * n * W * sizeof(double));
    double *qe = malloc((size_t)n * sizeof(double)), *f = malloc((size_t)n * sizeof(double));
    double *K = malloc((size_t)n * n * sizeof(double)), *mat = malloc((size_t)(np + 1) * sizeof(double));
    int ok = tab[0] && tab[1] && q && lt && lm && lf && lf2 && lK && qe && f && K && mat;
    if (ok) {
        const double *geoms[2] = {geom_a, geom_b};
        for (int g = 0; g < 2; ++g) {
            e->reference(geoms[g], qe);
            p->tabulate(geoms[g], qe, tab[g]);
        }
        for (int l = 0; l < W; ++l) {
            e->reference(geoms[l % 2], qe);
            for (int k = 0; k < n; ++k)
                q[k * W + l] = qe[k] + 0.08 * sc[k] * urand(r);
            for (int k = 0; k < p->ntab; ++k)
                lt[k * W + l] = tab[l % 2][k];
            for (int k = 0; k < np; ++k)
                lm[k * W + l] = mat0[k] * (1.0 + 0.05 * l);
        }
        p->force_lanes(q, lt, lm, lf2);
        p->force_tangent_lanes(q, lt, lm, lf, lK);
        double ef = 0.0, eK = 0.0;
        for (int l = 0; l < W; ++l) {
            for (int k = 0; k < n; ++k)
                qe[k] = q[k * W + l];
            for (int k = 0; k < np; ++k)
                mat[k] = lm[k * W + l];
            p->force_tangent(qe, tab[l % 2], mat, f, K);
            double fm = maxabs(f, n), Km = maxabs(K, n * n);
            for (int k = 0; k < n; ++k)
                ef = fmax(ef, fmax(fabs(lf[k * W + l] - f[k]), fabs(lf2[k * W + l] - f[k])) / fm);
            for (int k = 0; k < n * n; ++k)
                eK = fmax(eK, fabs(lK[k * W + l] - K[k]) / Km);
        }
        *e_f = ef, *e_K = eK;
    }
    free(tab[0]), free(tab[1]), free(q), free(lt), free(lm), free(lf), free(lf2), free(lK);
    free(qe), free(f), free(K), free(mat);
    return ok;
}

/* Kelvin-Voigt damping of a pair at the deformed state q (tab its element's
 * table), random velocities qd; maxima over calls into ev[NVCHECK] (see the
 * header comment): 0 fd_viscous, 1 fd_dissipation, 2 fd_visc_tangent, 3 visc_sym,
 * 4 visc_consist, 5 visc_lanes.  Returns 0 when out of memory. */
enum { NVCHECK = 6 };
static int visc_check(const bk_pair *p, const double *q0, const double *tab, const double *sc, rng *r,
                      double *ev)
{
    enum { W = BK_LANES };
    const int n = p->element->ndof, nt = p->ntab > 0 ? p->ntab : 1;
    const size_t nn = (size_t)n * n;
    double *q = malloc(n * sizeof(double)), *qd = malloc(n * sizeof(double)), *f = malloc(n * sizeof(double));
    double *f1 = malloc(n * sizeof(double)), *fp[4] = {0}, *C = malloc(nn * sizeof(double));
    double *Ks = malloc(nn * sizeof(double)), *G = malloc(nn * sizeof(double)), *X = malloc(nn * sizeof(double));
    double *lq = malloc(W * n * sizeof(double)), *lqd = malloc(W * n * sizeof(double));
    double *lt = malloc(W * (size_t)nt * sizeof(double)), *lv = malloc(W * 2 * sizeof(double));
    double *lf = malloc(W * n * sizeof(double)), *lf2 = malloc(W * n * sizeof(double));
    double *lK = malloc(W * nn * sizeof(double));
    int ok = q && qd && f && f1 && C && Ks && G && X && lq && lqd && lt && lv && lf && lf2 && lK;
    for (int k = 0; k < 4; ++k)
        ok = ok && (fp[k] = malloc(n * sizeof(double))) != NULL;
    if (ok) {
        const double visc[2] = {0.3 * 1e7 * 1e-3 + 1.0, 0.2 * 1e7 * 1e-3 + 1.0};
        const double off[4] = {2, 1, -1, -2};
        memcpy(q, q0, n * sizeof(double));
        for (int i = 0; i < n; ++i)
            qd[i] = sc[i] * urand(r);
        /* C = df/dqd (central differences of the force-only kernel: f is linear in qd);
         * f = dD/dqd (D quadratic in qd: the 4-point difference is exact but for round-off) */
        double D0 = p->viscous_force(q, qd, tab, visc, f);
        p->viscous(q, qd, tab, visc, 1.0, 0.0, f1, C);
        p->viscous(q, qd, tab, visc, 0.0, 1.0, f1, Ks);
        const double fmx = fmax(maxabs(f, n), 1e-300), Cmax = fmax(maxabs(C, (int)nn), 1e-300);
        double pw = 0.0;
        for (int i = 0; i < n; ++i)
            pw += f[i] * qd[i];
        ev[1] = fmax(ev[1], fabs(pw - 2.0 * D0) / fmax(fabs(pw), 1e-300));   /* f . qd = 2 D */
        for (int j = 0; j < n; ++j) {
            const double h = 1e-3 * sc[j], v0 = qd[j];
            double Dk[4];
            for (int k = 0; k < 4; ++k) {
                qd[j] = v0 + off[k] * h;
                Dk[k] = p->viscous_force(q, qd, tab, visc, fp[k]);
            }
            qd[j] = v0;
            const double dD = (-Dk[0] + 8 * Dk[1] - 8 * Dk[2] + Dk[3]) / (12 * h);
            ev[1] = fmax(ev[1], fabs(f[j] - dD) / fmx);
            for (int i = 0; i < n; ++i)
                ev[0] = fmax(ev[0], fabs(C[i * n + j] - (fp[1][i] - fp[2][i]) / (2 * h)) / Cmax);
        }
        /* symmetry of C; force of viscous() = viscous_force(); gc C + gk K
         * in one contraction = the two formed apart */
        const double gc = 733.0, gk = 1.0;
        p->viscous(q, qd, tab, visc, gc, gk, f1, X);
        double Xmax = fmax(maxabs(X, (int)nn), 1e-300);
        for (int i = 0; i < n; ++i) {
            ev[4] = fmax(ev[4], fabs(f1[i] - f[i]) / fmx);
            for (int j = 0; j < n; ++j) {
                ev[3] = fmax(ev[3], fabs(C[i * n + j] - C[j * n + i]) / Cmax);
                ev[4] = fmax(ev[4], fabs(X[i * n + j] - gc * C[i * n + j] - gk * Ks[i * n + j]) / Xmax);
            }
        }
        /* K = df/dq (qd held) by 4-point differences of the force (f is cubic in q:
         * exact but for round-off) */
        p->viscous(q, qd, tab, visc, 0.0, 1.0, f1, Ks);
        const double Kqmax = fmax(maxabs(Ks, (int)nn), 1e-300);
        for (int j = 0; j < n; ++j) {
            const double h = 1e-3 * sc[j], v0 = q[j];
            for (int k = 0; k < 4; ++k) {
                q[j] = v0 + off[k] * h;
                p->viscous_force(q, qd, tab, visc, fp[k]);
            }
            q[j] = v0;
            for (int i = 0; i < n; ++i) {
                G[i * n + j] = (-fp[0][i] + 8 * fp[1][i] - 8 * fp[2][i] + fp[3][i]) / (12 * h);
                ev[2] = fmax(ev[2], fabs(Ks[i * n + j] - G[i * n + j]) / Kqmax);
            }
        }
        /* lane kernels: lanes with their own states, velocities and parameters
         * (this element's table in every lane) against the one-element kernels */
        if (p->viscous_lanes && p->viscous_force_lanes) {
            for (int l = 0; l < W; ++l) {
                for (int k = 0; k < n; ++k) {
                    lq[k * W + l] = q0[k] + 1e-2 * sc[k] * urand(r);
                    lqd[k * W + l] = sc[k] * urand(r);
                }
                for (int k = 0; k < p->ntab; ++k)
                    lt[k * W + l] = tab[k];
                for (int k = 0; k < 2; ++k)
                    lv[k * W + l] = visc[k] * (1.0 + 0.1 * l);
            }
            p->viscous_force_lanes(lq, lqd, lt, lv, lf2);
            p->viscous_lanes(lq, lqd, lt, lv, gc, gk, lf, lK);
            for (int l = 0; l < W; ++l) {
                double vl[2] = {lv[l], lv[W + l]};
                for (int k = 0; k < n; ++k)
                    q[k] = lq[k * W + l], qd[k] = lqd[k * W + l];
                p->viscous(q, qd, tab, vl, gc, gk, f1, X);
                double fm = fmax(maxabs(f1, n), 1e-300), Xm = fmax(maxabs(X, (int)nn), 1e-300);
                for (int k = 0; k < n; ++k)
                    ev[5] = fmax(ev[5], fmax(fabs(lf[k * W + l] - f1[k]), fabs(lf2[k * W + l] - f1[k])) / fm);
                for (size_t k = 0; k < nn; ++k)
                    ev[5] = fmax(ev[5], fabs(lK[k * W + l] - X[k]) / Xm);
            }
        } else {
            ev[5] = -1.0;
        }
    }
    free(q), free(qd), free(f), free(f1), free(C), free(Ks), free(G), free(X), free(lq), free(lqd);
    free(lt), free(lv), free(lf), free(lf2), free(lK);
    for (int k = 0; k < 4; ++k)
        free(fp[k]);
    return ok;
}

int main(int argc, char **argv)
{
    /* kernel_check [NSTATE [PAIR_SUBSTRING]] */
    int NSTATE = argc > 1 ? atoi(argv[1]) : 20;
    const char *only = argc > 2 ? argv[2] : NULL;
    if (NSTATE < 1)
        NSTATE = 1;
    setvbuf(stdout, NULL, _IOLBF, 0);
    static const double geoms[2][BK_NGEOM] = {{0.5, 0.2, 0.1, 0.02, 1.6667e-5, 6.6667e-5, 8.3333e-5},
                                               {0.1, 0.01, 0.012, 1.2e-4, 1.44e-9, 1.0e-9, 2.44e-9}};
    int bad = 0;
    for (int ip = 0; ip < bk_nlinked_pairs; ++ip) {
        const bk_pair *p = bk_linked_pairs[ip];
        const bk_element *e = p->element;
        char pname[256];
        snprintf(pname, sizeof pname, "%s_%s_%s", e->name, p->material, p->integration);
        if (only && !strstr(pname, only))
            continue;
        int n = e->ndof;
        if (n > MAXD) {
            printf("pair=%s_%s_%s error=too_many_dofs\n", e->name, p->material, p->integration);
            bad = 1;
            continue;
        }
        double mat[16];
        for (int k = 0; k < p->nparam; ++k)
            mat[k] = param_value(p->param_names[k], k);
        for (int ig = 0; ig < 2; ++ig) {
            const double *geom = geoms[ig];
            double *tab = malloc((size_t)p->ntab * sizeof *tab);
            double *q0 = malloc(n * sizeof(double)), *q = malloc(n * sizeof(double));
            double *f = malloc(n * sizeof(double)), *f2 = malloc(n * sizeof(double));
            double *K = malloc((size_t)n * n * sizeof(double)), *Kd = malloc((size_t)n * n * sizeof(double));
            double *fp = malloc(n * sizeof(double)), *fm = malloc(n * sizeof(double));
            double *fp2 = malloc(n * sizeof(double)), *fm2 = malloc(n * sizeof(double));
            double *sc = malloc(n * sizeof(double)), *Kd2 = malloc((size_t)n * n * sizeof(double));
            if (!tab || !q0 || !q || !f || !f2 || !K || !Kd || !fp || !fm || !fp2 || !fm2 || !sc || !Kd2)
                return 3;
            double Rid[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, qid[4] = {1, 0, 0, 0}, zero[3] = {0, 0, 0};
            rigid(e, geom, Rid, qid, zero, q0);
            p->tabulate(geom, q0, tab);
            dof_scale(e, geom, sc);
            rng r = {0x9e3779b97f4a7c15ULL ^ (unsigned long long)(ip * 7919 + ig * 104729 + 1)};
            double R[9], qr[4], x0[3];

            /* Unit-strain scales from a small uniaxial stretch along the axis:
             * x components of positions and nodal vectors scaled by 1 + eps. */
            const double eps = 1e-4;
            rigid(e, geom, Rid, qid, zero, q);
            for (int f = 0; f < e->nfield; ++f)
                if (e->field_role[f] == BK_FIELD_POSITION || bk_field_is_gradient(e->field_role[f]))
                    q[e->field_dof[f]] *= 1.0 + eps;
            double Ueps = p->energy(q, tab, mat);
            p->force(q, tab, mat, f);
            double fscale = maxabs(f, n) / eps;
            /* inextensible elements store no energy in a stretch: use force x length */
            double Uscale = fmax(Ueps / (eps * eps), fscale * geom[BK_GEOM_L]);

            double e_force = 0, e_tan = 0, e_sym = 0, e_con = 0, e_rigU = 0, e_rigf = 0, e_mom = 0;
            double ev[NVCHECK] = {0};
            for (int k = 0; k < NVCHECK; ++k)
                ev[k] = p->viscous ? 0.0 : -1.0;

            for (int st = 0; st < NSTATE; ++st) {
                random_rotation(&r, R, qr);
                for (int i = 0; i < 3; ++i)
                    x0[i] = urand(&r);
                rigid(e, geom, R, qr, x0, q0);
                /* rigid motion */
                double U0 = p->energy(q0, tab, mat);
                p->force(q0, tab, mat, f);
                e_rigU = fmax(e_rigU, fabs(U0) / Uscale);
                e_rigf = fmax(e_rigf, maxabs(f, n) / fscale);
                /* deformed state; every other one close to the rigid motion (near-straight:
                 * the small-angle branches of the rotation functions) */
                double amp = st % 2 ? 1e-4 : 0.08;
                for (int i = 0; i < n; ++i)
                    q[i] = q0[i] + amp * sc[i] * urand(&r);
                p->force_tangent(q, tab, mat, f, K);
                p->force(q, tab, mat, f2);
                /* errors relative to the force of this state, but not below that of a 1 %
                 * strain (near-rigid states have tiny forces) */
                double fmax_ = fmax(maxabs(f, n), 1e-2 * fscale), Kmax = maxabs(K, n * n);
                for (int i = 0; i < n; ++i)
                    e_con = fmax(e_con, fabs(f[i] - f2[i]) / fmax_);
                for (int i = 0; i < n; ++i)
                    for (int j = 0; j < n; ++j)
                        e_sym = fmax(e_sym, fabs(K[i * n + j] - K[j * n + i]) / Kmax);
                for (int j = 0; j < n; ++j) {
                    double h = 1e-3 * sc[j], qj = q[j];
                    double U[4];
                    const double off[4] = {2, 1, -1, -2};
                    for (int k = 0; k < 4; ++k) {
                        q[j] = qj + off[k] * h;
                        U[k] = p->energy(q, tab, mat);
                    }
                    q[j] = qj + h;
                    p->force(q, tab, mat, fp);
                    q[j] = qj - h;
                    p->force(q, tab, mat, fm);
                    q[j] = qj + 2 * h;
                    p->force(q, tab, mat, fp2);
                    q[j] = qj - 2 * h;
                    p->force(q, tab, mat, fm2);
                    q[j] = qj;
                    double dU = (-U[0] + 8 * U[1] - 8 * U[2] + U[3]) / (12 * h);
                    e_force = fmax(e_force, fabs(f[j] - dU) / fmax_);
                    for (int i = 0; i < n; ++i)
                        Kd[i * n + j] = (-fp2[i] + 8 * fp[i] - 8 * fm[i] + fm2[i]) / (12 * h);
                }
                for (int k = 0; k < n * n; ++k)
                    e_tan = fmax(e_tan, fabs(K[k] - Kd[k]) / Kmax);
                /* moment loads: Q(q) and its Jacobian at every node */
                if (e->moment) {
                    double M[3] = {urand(&r), urand(&r), urand(&r)};
                    double *Q = f2, *dQ = Kd2, *Qp = fp, *Qm = fm, *Qp2 = fp2, *Qm2 = fm2;
                    for (int a = 0; a < e->nnode; ++a) {
                        double xi = e->node_xi[a];
                        e->moment(geom, xi, q, M, Q, dQ);
                        double dmax = fmax(maxabs(dQ, n * n), 1e-300);
                        for (int j = 0; j < n; ++j) {
                            double h = 1e-3 * sc[j], qj = q[j];
                            q[j] = qj + h;
                            e->moment(geom, xi, q, M, Qp, Kd);
                            q[j] = qj - h;
                            e->moment(geom, xi, q, M, Qm, Kd);
                            q[j] = qj + 2 * h;
                            e->moment(geom, xi, q, M, Qp2, Kd);
                            q[j] = qj - 2 * h;
                            e->moment(geom, xi, q, M, Qm2, Kd);
                            q[j] = qj;
                            for (int i = 0; i < n; ++i) {
                                double d = (-Qp2[i] + 8 * Qp[i] - 8 * Qm[i] + Qm2[i]) / (12 * h);
                                e_mom = fmax(e_mom, fabs(dQ[i * n + j] - d) / dmax);
                            }
                        }
                    }
                }
                /* Kelvin-Voigt damping (visc_check) */
                if (p->viscous && !visc_check(p, q, tab, sc, &r, ev))
                    return 3;
            }
            double e_lf = -1.0, e_lK = -1.0;
            if (p->force_lanes && p->force_tangent_lanes && !lane_check(p, geoms[ig], geoms[1 - ig], mat, sc, &r, &e_lf, &e_lK))
                return 3;
            printf("pair=%s_%s_%s geom=%d states=%d fd_force=%.3e fd_tangent=%.3e sym=%.3e consist=%.3e "
                   "rigid_energy=%.3e rigid_force=%.3e fd_viscous=%.3e fd_dissipation=%.3e fd_visc_tangent=%.3e "
                   "visc_sym=%.3e visc_consist=%.3e visc_lanes=%.3e fd_moment=%.3e lanes_f=%.3e lanes_K=%.3e "
                   "fscale=%.3e\n",
                   e->name, p->material, p->integration, ig, NSTATE, e_force, e_tan, e_sym, e_con,
                   e_rigU, e_rigf, ev[0], ev[1], ev[2], ev[3], ev[4], ev[5], e_mom, e_lf, e_lK, fscale);
            if (!isfinite(e_force) || !isfinite(e_tan))
                bad = 1;
            free(tab); free(q0); free(q); free(f); free(f2); free(K); free(Kd);
            free(fp); free(fm); free(fp2); free(fm2); free(sc); free(Kd2);
        }
    }
    return bad;
}
