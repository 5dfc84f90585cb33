/* spring_check.c -- assembly and stability analysis of the runtime against the
 * hand-written spring and link elements of spring_element.c, which reach the
 * runtime through the same bk_element / bk_pair descriptors as the generated
 * kernels.  Models are built in memory (no model file).  tests/test_spring.py
 * builds it with the sanitizers on, runs it and asserts on what it prints:
 * one line per check, "case=NAME key=value ...".
 *
 * References are independent of the runtime: matrices and forces written out
 * by hand (or from the closed-form spring formulas), finite differences of the
 * assembled force, GSL's dense symmetric eigensolver, and inertia counts known
 * from Sylvester's law (a chain fixed at one end has as many negative tangent
 * eigenvalues as negative springs) or from the two-bar truss in closed form.
 */
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spring_element.h"
#include "solver/stability.h"
#include "assembly/system.h"

#define MAXN 16                     /* nodes              */
#define MAXE 8                      /* elements           */
#define MAXD (3 * MAXN + MAXE)      /* DOFs               */

typedef struct scene {
    bk_model m;
    const bk_pair *pairs[2];
    double geoms[MAXE][BK_NGEOM];
    int geom_pair[MAXE], geom_elem[MAXE];
    double tabbuf[MAXE][1];
    double *tabs[MAXE];
    bk_mat mats[MAXE];
    bk_elem elems[MAXE];
    int dofs[MAXE][7];
    int fixed[MAXD];
    bk_lincon lincons[4];
    int lc_dof[4][2];
    double lc_c0[4][2], lc_cc[4][2], lc_cs[4][2];
    double q0[MAXD], qd0[MAXD];
    int nnode;
} scene;

static void scene_init(scene *s, int nnode, const double (*x)[3])
{
    memset(s, 0, sizeof *s);
    s->nnode = nnode;
    s->pairs[0] = &spring_pair;
    s->pairs[1] = &link_pair;
    for (int n = 0; n < nnode; ++n)
        for (int i = 0; i < 3; ++i)
            s->q0[3 * n + i] = x[n][i];
    bk_model *m = &s->m;
    snprintf(m->name, sizeof m->name, "spring_check");
    m->analysis = BK_ANALYSIS_STATIC;
    m->length_scale = 1.0;
    m->stat.eigenvalues = 1;          /* the eigenvalue estimates are checked too */
    m->ndof = 3 * nnode;
    m->q0 = s->q0;
    m->qd0 = s->qd0;
    m->npair = 2;
    m->pairs = s->pairs;
    m->geoms = s->geoms;
    m->geom_pair = s->geom_pair;
    m->geom_elem = s->geom_elem;
    m->tabs = s->tabs;
    m->mats = s->mats;
    m->elems = s->elems;
    m->fixed = s->fixed;
    m->lincons = s->lincons;
}

/* Element between nodes a and b: a spring of stiffness par, or (link) an
 * inextensible link with multiplier scale par and a multiplier DOF of its own.
 * Section area A, density rho. */
static int add_elem(scene *s, int link, int a, int b, double par, double A, double rho)
{
    bk_model *m = &s->m;
    int e = m->nelem++;
    const bk_pair *p = s->pairs[link];
    for (int i = 0; i < 3; ++i) {
        s->dofs[e][i] = 3 * a + i;
        s->dofs[e][3 + i] = 3 * b + i;
    }
    if (link)
        s->dofs[e][6] = m->ndof++;
    double d2 = 0.0;
    for (int i = 0; i < 3; ++i)
        d2 += (s->q0[3 * b + i] - s->q0[3 * a + i]) * (s->q0[3 * b + i] - s->q0[3 * a + i]);
    s->geoms[e][BK_GEOM_L] = sqrt(d2);
    s->geoms[e][BK_GEOM_A] = A;
    s->mats[e].nparam = 1;
    s->mats[e].params[0] = par;
    s->mats[e].rho = rho;
    s->elems[e] = (bk_elem){.pair = link, .geom = e, .mat = e, .dofs = s->dofs[e]};
    s->geom_pair[e] = link;
    s->geom_elem[e] = e;
    s->tabs[e] = s->tabbuf[e];
    m->ngeom = m->nmat = m->nelem;
    double q0e[7];
    bk_gather(m, e, s->q0, q0e);
    p->tabulate(s->geoms[e], q0e, s->tabs[e]);
    return e;
}

static void fix(scene *s, int dof)
{
    s->fixed[s->m.nfixed++] = dof;
}

/* Linear constraint q[a] - q[b] = 0. */
static void tie(scene *s, int a, int b)
{
    int c = s->m.nlincon++;
    s->lc_dof[c][0] = a;
    s->lc_dof[c][1] = b;
    s->lc_c0[c][0] = 1.0;
    s->lc_c0[c][1] = -1.0;
    s->lincons[c] = (bk_lincon){.nterm = 2, .dof = s->lc_dof[c], .c0 = s->lc_c0[c], .cc = s->lc_cc[c],
                                .cs = s->lc_cs[c]};
}

/* The Newton matrix of state q (internal tangent and constraint rows, no loads)
 * as a dense neq x neq matrix, and the internal force over all DOFs. */
static double *newton_matrix(bk_system *sys, const double *q, double *fint, double **Ax_out)
{
    int n = sys->neq;
    double *Ax = calloc((size_t)sys->nnz + 1, sizeof *Ax), *nu = calloc((size_t)sys->ncon + 1, sizeof *nu);
    double *A = calloc((size_t)n * n + 1, sizeof *A);
    if (!Ax || !nu || !A)
        exit(3);
    bk_assemble_internal(sys, q, fint, Ax);
    bk_assemble_constraints(sys, q, nu, 0.0, NULL, Ax);
    for (int j = 0; j < n; ++j)
        for (int k = sys->Ap[j]; k < sys->Ap[j + 1]; ++k)
            A[sys->Ai[k] * n + j] = Ax[k];
    free(nu);
    if (Ax_out)
        *Ax_out = Ax;
    else
        free(Ax);
    return A;
}

static double maxabs(const double *v, int n)
{
    double m = 0.0;
    for (int i = 0; i < n; ++i)
        m = fmax(m, fabs(v[i]));
    return m;
}

/* Closed-form force of a spring k, rest length L0, between points xa, xb on
 * the two nodes: fa = -k (|d| - L0) d/|d|, fb = -fa. */
static void spring_force_ref(const double *xa, const double *xb, double k, double L0, double *fa, double *fb)
{
    double d[3] = {xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; ++i) {
        fb[i] = k * (len - L0) * d[i] / len;
        fa[i] = -fb[i];
    }
}

/* ---------------------------------------------------------------- assembly */

static void check_assembly(void)
{
    /* L-shaped pair of springs: node 0 clamped, node 2 held in z. */
    const double x[3][3] = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}};
    const double k0 = 100.0, k1 = 300.0, A = 1e-4, rho = 2000.0;
    scene S;
    scene_init(&S, 3, x);
    add_elem(&S, 0, 0, 1, k0, A, rho);
    add_elem(&S, 0, 1, 2, k1, A, rho);
    for (int i = 0; i < 3; ++i)
        fix(&S, i);
    fix(&S, 8);
    bk_system *sys = bk_system_create(&S.m, stderr);
    if (!sys)
        exit(3);
    int n = sys->neq, nd = S.m.ndof;
    double fint[MAXD];

    /* Reference state: K = sum k n n^T over the free DOFs (node 1 x y z, node 2 x y),
     * written out by hand. */
    const double Kref[5][5] = {{k0, 0, 0, 0, 0}, {0, k1, 0, 0, -k1}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0},
                               {0, -k1, 0, 0, k1}};
    double *K = newton_matrix(sys, S.q0, fint, NULL);
    double err = 0.0;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
            err = fmax(err, fabs(K[i * n + j] - Kref[i][j]));
    printf("case=reference_tangent neq=%d expected_neq=5 err=%.3e fint=%.3e\n", n, err / k1, maxabs(fint, nd));
    free(K);

    /* Deformed state: node 1 at (1.2, 0.1, 0.05), node 2 at (0.9, 2.3, 0). */
    double q[MAXD];
    memcpy(q, S.q0, sizeof q);
    q[3] = 1.2, q[4] = 0.1, q[5] = 0.05, q[6] = 0.9, q[7] = 2.3;
    double fe[4][3], fref[MAXD] = {0};
    spring_force_ref(q + 0, q + 3, k0, 1.0, fe[0], fe[1]);
    spring_force_ref(q + 3, q + 6, k1, 2.0, fe[2], fe[3]);
    for (int i = 0; i < 3; ++i) {
        fref[i] += fe[0][i];
        fref[3 + i] += fe[1][i] + fe[2][i];
        fref[6 + i] += fe[3][i];
    }
    double *Ax = NULL;
    K = newton_matrix(sys, q, fint, &Ax);
    double ferr = 0.0;
    for (int i = 0; i < nd; ++i)
        ferr = fmax(ferr, fabs(fint[i] - fref[i]));
    printf("case=deformed_force err=%.3e\n", ferr / maxabs(fref, nd));

    /* its tangent against central differences of the assembled force */
    double terr = 0.0, Kmax = maxabs(K, n * n), fp[MAXD], fm[MAXD];
    for (int i = 0; i < nd; ++i) {
        int j = sys->eq[i];
        if (j < 0)
            continue;
        double h = 1e-6, qi = q[i];
        q[i] = qi + h;
        bk_assemble_internal(sys, q, fp, NULL);
        q[i] = qi - h;
        bk_assemble_internal(sys, q, fm, NULL);
        q[i] = qi;
        for (int r = 0; r < nd; ++r)
            if (sys->eq[r] >= 0)
                terr = fmax(terr, fabs(K[sys->eq[r] * n + j] - (fp[r] - fm[r]) / (2 * h)));
    }
    printf("case=deformed_tangent_fd err=%.3e\n", terr / Kmax);

    /* strain energy against the closed form */
    double e0 = sqrt(1.44 + 0.01 + 0.0025) - 1.0, e1 = sqrt(0.09 + 4.84 + 0.0025) - 2.0;
    double Uref = 0.5 * k0 * e0 * e0 + 0.5 * k1 * e1 * e1;
    printf("case=energy err=%.3e\n", fabs(bk_strain_energy(sys, q) - Uref) / Uref);

    /* element mass: rho A l / 6 [2 1; 1 2] (x) I3, l = 2 for element 1 */
    double work[4], Me[36], merr = 0.0, c = rho * A * 2.0 / 6.0;
    bk_element_mass(&S.m, 1, work, Me);
    for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) {
            double ref = a % 3 == b % 3 ? (a / 3 == b / 3 ? 2.0 * c : c) : 0.0;
            merr = fmax(merr, fabs(Me[a * 6 + b] - ref));
        }
    printf("case=mass err=%.3e\n", merr / (2.0 * c));

    /* gravity: half of each element's weight on each of its nodes */
    S.m.has_gravity = 1;
    S.m.gravity[2] = -9.81;
    double fg[MAXD], wg[3] = {rho * A * 1.0 * -9.81 / 2, rho * A * 3.0 * -9.81 / 2, rho * A * 2.0 * -9.81 / 2};
    bk_gravity_load(sys, fg);
    double gerr = 0.0;
    for (int nn = 0; nn < 3; ++nn)
        for (int i = 0; i < 3; ++i)
            gerr = fmax(gerr, fabs(fg[3 * nn + i] - (i == 2 ? wg[nn] : 0.0)));
    printf("case=gravity err=%.3e\n", gerr / fabs(wg[1]));
    S.m.has_gravity = 0;

    /* gather / scatter round trip: scatter(gather(q)) adds each element's DOFs once */
    double acc[MAXD] = {0}, qe[7];
    for (int e = 0; e < S.m.nelem; ++e) {
        bk_gather(&S.m, e, q, qe);
        bk_scatter(&S.m, e, qe, 1.0, acc);
    }
    double serr = 0.0;
    for (int i = 0; i < nd; ++i)
        serr = fmax(serr, fabs(acc[i] - (i >= 3 && i < 6 ? 2.0 : 1.0) * q[i]));
    printf("case=gather_scatter err=%.3e\n", serr);
    free(K);
    free(Ax);
    bk_system_free(sys);
}

/* --------------------------------------------------------------- stability */

/* Smallest-magnitude eigenvalue of a dense symmetric n x n matrix (GSL). */
static double eig_min_ref(const double *A, int n)
{
    gsl_matrix *M = gsl_matrix_alloc((size_t)n, (size_t)n);
    gsl_vector *ev = gsl_vector_alloc((size_t)n);
    gsl_eigen_symm_workspace *w = gsl_eigen_symm_alloc((size_t)n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            gsl_matrix_set(M, (size_t)i, (size_t)j, A[i * n + j]);
    gsl_eigen_symm(M, ev, w);
    double best = gsl_vector_get(ev, 0);
    for (int i = 1; i < n; ++i)
        if (fabs(gsl_vector_get(ev, (size_t)i)) < fabs(best))
            best = gsl_vector_get(ev, (size_t)i);
    gsl_eigen_symm_free(w);
    gsl_vector_free(ev);
    gsl_matrix_free(M);
    return best;
}

/* Stability check of state q: negative count, eig_min, multipliers. */
static void stability_of(bk_system *sys, bk_stability *st, const double *q, bk_stability_result *res)
{
    double fint[MAXD], *Ax = NULL;
    free(newton_matrix(sys, q, fint, &Ax));
    bk_stability_check(st, Ax, res);
    free(Ax);
}

/* Chain of four springs along x, node 0 clamped, y and z held everywhere;
 * variant 0: plain, 1: x4 tied to x3 by a linear constraint, 2: by an
 * inextensible link element (element-internal multiplier). */
static void check_chain(int variant)
{
    static const char *const names[3] = {"chain", "chain_lincon", "chain_link"};
    const double x[5][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}};
    const double k[4] = {1.0, -0.5, 2.0, -3.0};
    scene S;
    scene_init(&S, 5, x);
    for (int e = 0; e < 4; ++e)
        add_elem(&S, 0, e, e + 1, k[e], 1e-4, 1000.0);
    if (variant == 2)
        add_elem(&S, 1, 3, 4, 1.0, 1e-4, 1000.0);
    fix(&S, 0);
    for (int nn = 0; nn < 5; ++nn) {
        fix(&S, 3 * nn + 1);
        fix(&S, 3 * nn + 2);
    }
    if (variant == 1)
        tie(&S, 12, 9);
    bk_system *sys = bk_system_create(&S.m, stderr);
    bk_stability st;
    if (!sys || bk_stability_init(&st, sys, NULL) != 0)
        exit(3);
    bk_stability_result res;
    stability_of(sys, &st, S.q0, &res);
    /* Sylvester: K = B^T diag(k) B with B invertible: as many negative
     * eigenvalues as negative springs; the tie (or the link) leaves spring 4
     * without extension on the constraint tangent space. */
    int expected = variant == 0 ? 2 : 1;
    printf("case=%s negative=%d expected=%d nmult=%d expected_nmult=%d ok=%d", names[variant], res.negative,
           expected, st.nmult, variant == 0 ? 0 : 1, res.ok);
    if (variant == 0) {
        /* the tridiagonal chain matrix over x1..x4, by hand */
        const double Kc[16] = {k[0] + k[1], -k[1], 0, 0,          -k[1], k[1] + k[2], -k[2], 0,
                               0,           -k[2], k[2] + k[3], -k[3], 0,   0,          -k[3], k[3]};
        double fint[MAXD], *K = newton_matrix(sys, S.q0, fint, NULL), err = 0.0;
        for (int i = 0; i < 16; ++i)
            err = fmax(err, fabs(K[i] - Kc[i]));
        free(K);
        double lref = eig_min_ref(Kc, 4);
        printf(" tangent_err=%.3e eig_min=%.12g eig_min_ref=%.12g", err, res.eig_min, lref);
    }
    printf("\n");
    bk_stability_free(&st);
    bk_system_free(sys);
}

/* Two-bar truss (von Mises): supports at (-1, 0, 0) and (1, 0, 0) clamped, apex
 * at (0, h, 0) with z held.  With the apex at (0, y, 0), l = sqrt(1 + y^2), the
 * tangent of the apex is diagonal:
 *   K_xx = 2k [1 + (1 - L0/l) y^2] / l^2,  K_yy = 2k [y^2 + (1 - L0/l)] / l^2,
 * L0 = sqrt(1 + h^2): no negative eigenvalue at y = +-h, one at y = 0 (the
 * compressed bars push the apex through), K_yy(0) = 2k (1 - L0). */
static void check_truss(void)
{
    const double h = 0.5, k = 1000.0, L0 = sqrt(1.0 + h * h);
    const double x[3][3] = {{-1, 0, 0}, {1, 0, 0}, {0, h, 0}};
    scene S;
    scene_init(&S, 3, x);
    add_elem(&S, 0, 0, 2, k, 1e-4, 1000.0);
    add_elem(&S, 0, 1, 2, k, 1e-4, 1000.0);
    for (int i = 0; i < 6; ++i)
        fix(&S, i);
    fix(&S, 8);
    bk_system *sys = bk_system_create(&S.m, stderr);
    bk_stability st;
    if (!sys || bk_stability_init(&st, sys, NULL) != 0)
        exit(3);
    double q[MAXD];
    const double ys[3] = {h, 0.0, -h};
    const char *const names[3] = {"truss_up", "truss_flat", "truss_down"};
    double Kyy[3];
    for (int c = 0; c < 3; ++c) {
        double y = ys[c], l2 = 1.0 + y * y, l = sqrt(l2);
        double Kxx = 2 * k * (1 + (1 - L0 / l) * y * y) / l2;
        Kyy[c] = 2 * k * (y * y + (1 - L0 / l)) / l2;
        memcpy(q, S.q0, sizeof q);
        q[7] = y;
        bk_stability_result res;
        stability_of(sys, &st, q, &res);
        double lref = fabs(Kxx) < fabs(Kyy[c]) ? Kxx : Kyy[c];
        printf("case=%s negative=%d expected=%d eig_min=%.12g eig_min_ref=%.12g ok=%d\n", names[c], res.negative,
               (Kxx < 0) + (Kyy[c] < 0), res.eig_min, lref, res.ok);
        if (c == 0)
            bk_stability_accept(&st);
        if (c == 1) {
            /* between the accepted state (y = h) and this one the interpolated
             * K_yy crosses zero at t = K_yy(h) / (K_yy(h) - K_yy(0)); K_xx > 0 */
            double t = bk_stability_crossing(&st, 0);
            printf("case=truss_crossing t=%.12g expected=%.12g\n", t, Kyy[0] / (Kyy[0] - Kyy[1]));
        }
    }
    bk_stability_free(&st);
    bk_system_free(sys);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    check_assembly();
    for (int v = 0; v < 3; ++v)
        check_chain(v);
    check_truss();
    return 0;
}
