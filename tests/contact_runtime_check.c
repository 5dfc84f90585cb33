/* contact_runtime_check.c -- the contact interaction (runtime/assembly/
 * contact_force.c) on in-memory models of the hand-written springs of
 * spring_element.c: its Jacobian against central differences of its residual
 * for a half-space, a sphere and a capsule; a chain of springs settling on the
 * ground under its weight by Newton's method with the interaction's step
 * limiter (no iterate through the surface; the contact forces balance the
 * weight); the step limiter against a correction that would cross the
 * surface; the broad phase's candidates against a sphere.  Prints
 * "case=NAME key=value ..." lines for tests/test_contact.py. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/contact_force.h"
#include "assembly/contact_model.h"
#include "assembly/system.h"
#include "linalg/linsolve.h"
#include "spring_element.h"

#define NN 9                             /* nodes of the chain */
#define NE (NN - 1)

typedef struct scene {
    bk_model m;
    const bk_pair *pairs[1];
    double geoms[NE][BK_NGEOM];
    int geom_pair[NE], geom_elem[NE];
    double tabbuf[NE][1];
    double *tabs[NE];
    bk_mat mats[NE];
    bk_elem elems[NE];
    int dofs[NE][6];
    int fixed[3 * NN];
    double q0[3 * NN], qd0[3 * NN];
    bk_contact_prim prim;
    bk_contact_set set;
    bk_model_record rec;                 /* the contact data as the model file's record holds it */
    char text[8192], where[32];
    int celems[NE];
    double radius[NE];
} scene;

/* A chain of NN nodes along x at height z, springs of stiffness k; contact of
 * every element with `prim` (radius r, reach shat, stiffness kappa). */
static void build_xy(scene *s, double z, double k, bk_contact_prim prim, double r, double shat, double kappa,
                     int free_xy)
{
    memset(s, 0, sizeof *s);
    bk_model *m = &s->m;
    snprintf(m->name, sizeof m->name, "contact_check");
    m->analysis = BK_ANALYSIS_STATIC;
    m->length_scale = 1.0;
    m->ndof = 3 * NN;
    for (int n = 0; n < NN; ++n) {
        s->q0[3 * n] = (double)n / NE;
        s->q0[3 * n + 2] = z;
    }
    s->pairs[0] = &spring_pair;
    m->q0 = s->q0, m->qd0 = s->qd0, m->npair = 1, m->pairs = s->pairs, m->geoms = s->geoms;
    m->geom_pair = s->geom_pair, m->geom_elem = s->geom_elem, m->tabs = s->tabs, m->mats = s->mats;
    m->elems = s->elems, m->fixed = s->fixed;
    for (int e = 0; e < NE; ++e) {
        for (int i = 0; i < 3; ++i)
            s->dofs[e][i] = 3 * e + i, s->dofs[e][3 + i] = 3 * (e + 1) + i;
        s->geoms[e][BK_GEOM_L] = 1.0 / NE;
        s->geoms[e][BK_GEOM_A] = 1e-4;
        s->mats[e].nparam = 1;
        s->mats[e].params[0] = k;
        s->mats[e].rho = 1000.0;
        s->elems[e] = (bk_elem){.pair = 0, .geom = e, .mat = e, .dofs = s->dofs[e]};
        s->tabs[e] = s->tabbuf[e];
        s->celems[e] = e;
        s->radius[e] = r;
        double q0e[6];
        m->nelem = e + 1;
        m->ngeom = m->nmat = m->nelem;
        bk_gather(m, e, s->q0, q0e);
        spring_pair.tabulate(s->geoms[e], q0e, s->tabs[e]);
    }
    for (int n = 0; n < NN && !free_xy; ++n) {  /* x and y held: the chain moves in z only */
        s->fixed[m->nfixed++] = 3 * n;
        s->fixed[m->nfixed++] = 3 * n + 1;
    }
    s->prim = prim;
    s->set = (bk_contact_set){.prim = 0, .shat = shat, .kappa = kappa, .slip = 1e-6, .nsample = 4, .nelem = NE,
                              .elems = s->celems, .radius = s->radius};
}

/* The scene's primitive and set as the record "contact" of the model file
 * (runtime/assembly/contact_read.c), then its system. */
static bk_system *create(scene *s)
{
    const bk_contact_prim *p = &s->prim;
    const bk_contact_set *c = &s->set;
    int n = snprintf(s->text, sizeof s->text, "contacts 1 1\nprim %d", p->shape);
    for (int k = 0; k < BK_CONTACT_MAXPRM; ++k)
        n += snprintf(s->text + n, sizeof s->text - (size_t)n, " %.17g", p->prm[k]);
    for (int k = 0; k < 9; ++k)
        n += snprintf(s->text + n, sizeof s->text - (size_t)n, " %.17g", k < 3 ? p->motion[k] : k < 6 ? p->turn[k - 3]
                      : p->pivot[k - 6]);
    n += snprintf(s->text + n, sizeof s->text - (size_t)n, " %d -1\ncset 0 %.17g %.17g %.17g %.17g %.17g %d %d",
                  p->amp, c->shat, c->kappa, c->mu, c->mu_k, c->slip, c->nsample, c->nelem);
    for (int i = 0; i < c->nelem; ++i)
        n += snprintf(s->text + n, sizeof s->text - (size_t)n, " %d %.17g", c->elems[i], c->radius[i]);
    snprintf(s->where, sizeof s->where, "contact_check");
    s->rec = (bk_model_record){.name = "contact", .text = s->text, .where = s->where};
    s->m.records = &s->rec;
    s->m.nrecord = 1;
    return bk_system_create(&s->m, stderr);
}

static void build(scene *s, double z, double k, bk_contact_prim prim, double r, double shat, double kappa)
{
    build_xy(s, z, k, prim, r, shat, kappa, 0);
}

/* The half-space z < 0, fixed. */
static bk_contact_prim ground(void)
{
    return (bk_contact_prim){.shape = BK_CONTACT_HALF_SPACE, .prm = {0.0, 0.0, 1.0, 0.0}, .amp = -1, .body = -1};
}

/* The interaction's residual over all DOFs at q (nothing else). */
static int contact_force(bk_system *sys, const double *q, double *f, double *Ax)
{
    memset(f, 0, (size_t)sys->m->ndof * sizeof *f);
    if (Ax)
        memset(Ax, 0, (size_t)sys->nnz * sizeof *Ax);
    return bk_assemble_interactions(sys, q, &(bk_path){.factor = 1.0, .x = 1.0}, f, Ax);
}

/* Largest |dF/dq - Ax| over the free block relative to max |Ax|, by central differences. */
static double jacobian_error(bk_system *sys, const double *q0)
{
    const int nd = sys->m->ndof;
    double *q = malloc((size_t)nd * sizeof *q), *fp = malloc((size_t)nd * sizeof *fp);
    double *fm = malloc((size_t)nd * sizeof *fm), *f = malloc((size_t)nd * sizeof *f);
    double *Ax = calloc((size_t)sys->nnz, sizeof *Ax);
    memcpy(q, q0, (size_t)nd * sizeof *q);
    contact_force(sys, q, f, Ax);
    double amax = 0.0, err = 0.0, h = 1e-8;
    for (long k = 0; k < sys->nnz; ++k)
        amax = fmax(amax, fabs(Ax[k]));
    for (int j = 0; j < nd; ++j) {
        int cj = sys->eq[j];
        if (cj < 0)
            continue;
        q[j] = q0[j] + h;
        contact_force(sys, q, fp, NULL);
        q[j] = q0[j] - h;
        contact_force(sys, q, fm, NULL);
        q[j] = q0[j];
        for (int i = 0; i < nd; ++i) {
            int ri = sys->eq[i];
            if (ri < 0)
                continue;
            double d = (fp[i] - fm[i]) / (2 * h), a = 0.0;
            for (int k = sys->Ap[cj]; k < sys->Ap[cj + 1]; ++k)
                if (sys->Ai[k] == ri)
                    a = Ax[k];
            err = fmax(err, fabs(d - a));
        }
    }
    free(q), free(fp), free(fm), free(f), free(Ax);
    return amax > 0.0 ? err / amax : err;
}

static void check_jacobians(void)
{
    const char *names[5] = {"jacobian_half_space", "jacobian_sphere", "jacobian_capsule", "jacobian_box",
                            "jacobian_turned_capsule"};
    /* the box's x faces at 0.05 and 0.95: the chain's ends (x = 0, 1) feel its edges, the rest its top; the
     * turned capsule is the capsule turned by 0.3 rad about z through (0.5, 0, -0.1) and moved 1 cm along y
     * (at the factor 1 of the residual) */
    bk_contact_prim prims[5] = {
        {.shape = BK_CONTACT_HALF_SPACE, .prm = {0.0, 0.0, 1.0, 0.0}, .amp = -1, .body = -1},
        {.shape = BK_CONTACT_SPHERE, .prm = {0.5, 0.0, -0.3, 0.3}, .amp = -1, .body = -1},
        {.shape = BK_CONTACT_CAPSULE, .prm = {0.2, -0.5, -0.1, 0.8, 0.5, -0.1, 0.1}, .amp = -1, .body = -1},
        {.shape = BK_CONTACT_BOX, .prm = {0.5, 0.0, -0.1, 0.45, 0.3, 0.1, 1, 0, 0, 0, 1, 0, 0, 0, 1}, .amp = -1,
         .body = -1},
        {.shape = BK_CONTACT_CAPSULE, .prm = {0.2, -0.5, -0.1, 0.8, 0.5, -0.1, 0.1}, .turn = {0.0, 0.0, 0.3},
         .pivot = {0.5, 0.0, -0.1}, .motion = {0.0, 0.01, 0.0}, .amp = -1, .body = -1},
    };
    for (int c = 0; c < 5; ++c) {
        scene s;
        build(&s, 0.0, 100.0, prims[c], 0.01, 0.05, 1e3);
        double q[3 * NN];
        memcpy(q, s.q0, sizeof q);
        for (int n = 0; n < NN; ++n)               /* a wavy chain: every point within the barrier's reach */
            q[3 * n + 2] = 0.01 + 0.012 + 0.008 * sin(1.7 * n);
        bk_system *sys = create(&s);
        double F[3], dmin;
        int nact;
        bk_contact_state(sys, q, F, &nact, &dmin);
        printf("case=%s err=%.3e active=%d min_distance=%.4g\n", names[c], jacobian_error(sys, q), nact, dmin);
        bk_system_free(sys);
    }
}

/* Friction: the lagged state taken at a wavy chain (normal forces of the
 * barrier), then every node moved sideways by a different amount, some below
 * the slip tolerance (sticking: the spring part), some beyond (sliding); the
 * Jacobian against central differences there, and the friction force of a
 * sliding point against mu times its lagged normal force. */
static void check_friction(void)
{
    scene s;
    build_xy(&s, 0.0, 100.0, ground(), 0.01, 0.05, 1e3, 1);
    s.set.mu = s.set.mu_k = 0.4;
    s.set.slip = 1e-3;
    double q[3 * NN];
    memcpy(q, s.q0, sizeof q);
    for (int n = 0; n < NN; ++n)
        q[3 * n + 2] = 0.01 + 0.012 + 0.008 * sin(1.7 * n);
    bk_system *sys = create(&s);
    bk_interactions_accept(sys, q, &(bk_path){.factor = 1.0, .x = 1.0});
    double F0[3], d0;
    int n0;
    bk_contact_state(sys, q, F0, &n0, &d0);
    for (int n = 0; n < NN; ++n) {             /* slips from 0.1 to 4 tolerances, in x and y */
        q[3 * n] += 1e-4 * (1 + 5 * n) * cos(0.9 * n);
        q[3 * n + 1] += 1e-4 * (1 + 5 * n) * sin(0.9 * n);
    }
    double err = jacobian_error(sys, q);
    /* all slid far (100 tolerances along x): the tangential force is mu times the normal force */
    double qs[3 * NN], F[3], d;
    int nact;
    memcpy(qs, q, sizeof qs);
    for (int n = 0; n < NN; ++n)
        qs[3 * n] += 0.1;
    bk_contact_state(sys, qs, F, &nact, &d);
    double ratio = -F[0] / F0[2];          /* the friction opposes the slip along +x */
    printf("case=jacobian_friction err=%.3e active=%d coulomb_ratio=%.12f mu=%.3f\n", err, n0, ratio, s.set.mu);
    bk_system_free(sys);
}

/* Newton on the free DOFs (z of every node) from a chain held just above the
 * ground: r(q) = fint + contact - weight; every iterate checked admissible. */
static void check_resting_chain(void)
{
    scene s;
    const double r = 0.01, shat = 1e-3, g = 9.81;
    build(&s, r + 0.8 * shat, 1e4, ground(), r, shat, 1e4);
    bk_system *sys = create(&s);
    const int nd = s.m.ndof, n = sys->neq;
    double q[3 * NN], fint[3 * NN], fc[3 * NN], fext[3 * NN], rr[3 * NN], weight = 0.0;
    double *Ax = calloc((size_t)sys->nnz, sizeof *Ax), *Ac = calloc((size_t)sys->nnz, sizeof *Ac);
    memcpy(q, s.q0, sizeof q);
    memset(fext, 0, sizeof fext);
    for (int e = 0; e < NE; ++e) {             /* lumped weight of the springs' mass: half to each node */
        double w = 1000.0 * 1e-4 * (1.0 / NE) * g;
        fext[3 * e + 2] -= 0.5 * w, fext[3 * (e + 1) + 2] -= 0.5 * w;
        weight += w;
    }
    bk_linsolver ls;
    bk_lin_init_kind(&ls, n, sys->Ap, sys->Ai, BK_LIN_DENSE);
    int it = 0, crossed = 0, converged = 0;
    double res = INFINITY, alpha_min = 1.0;
    for (; it < 100; ++it) {
        if (bk_assemble_internal(sys, q, fint, Ax) != 0 || contact_force(sys, q, fc, Ac) != 0) {
            crossed = 1;
            break;
        }
        res = 0.0;
        for (int i = 0; i < nd; ++i)
            if (sys->eq[i] >= 0) {
                rr[sys->eq[i]] = -(fint[i] + fc[i] - fext[i]);
                res = fmax(res, fabs(fint[i] + fc[i] - fext[i]));
            }
        if (res < 1e-10 * weight) {
            converged = 1;
            break;
        }
        for (long k = 0; k < sys->nnz; ++k)
            Ax[k] += Ac[k];
        if (bk_lin_factor_solve(&ls, Ax, rr) != BK_LIN_OK)
            break;
        double a = bk_interactions_step_limit(sys, q, rr);
        alpha_min = fmin(alpha_min, a);
        for (int i = 0; i < nd; ++i)
            if (sys->eq[i] >= 0)
                q[i] += a * rr[sys->eq[i]];
    }
    double F[3], dmin;
    int nact;
    bk_contact_state(sys, q, F, &nact, &dmin);
    printf("case=resting_chain converged=%d iterations=%d crossed=%d weight=%.17g contact_z=%.17g "
           "balance_err=%.3e min_distance=%.4g shat=%.4g active=%d alpha_min=%.3g\n", converged, it, crossed, weight,
           F[2], fabs(F[2] - weight) / weight, dmin, shat, nact, alpha_min);
    bk_lin_free(&ls);
    free(Ax), free(Ac);
    bk_system_free(sys);
}

/* A correction that would take the chain 10 cm through the ground. */
static void check_step_limit(void)
{
    scene s;
    const double r = 0.01, shat = 1e-3;
    build(&s, r + 0.5 * shat, 1e4, ground(), r, shat, 1e4);
    bk_system *sys = create(&s);
    double dx[3 * NN] = {0}, q[3 * NN], F[3], d0, d1;
    int nact;
    for (int i = 0; i < sys->neq; ++i)
        dx[i] = -0.1;
    double a = bk_interactions_step_limit(sys, s.q0, dx);
    memcpy(q, s.q0, sizeof q);
    bk_contact_state(sys, q, F, &nact, &d0);
    for (int i = 0; i < s.m.ndof; ++i)
        if (sys->eq[i] >= 0)
            q[i] += a * dx[sys->eq[i]];
    bk_contact_state(sys, q, F, &nact, &d1);
    printf("case=step_limit alpha=%.6g distance_before=%.6g distance_after=%.6g\n", a, d0, d1);
    bk_system_free(sys);
}

/* The broad phase against a sphere (radius R = 0.1 at (0.5, 0, 0), or moved
 * by 0.25 along x) under the chain at z = 0.115 (r = 0.01, reach 0.01): only
 * the two elements meeting above the centre come within R + r + reach = 0.12
 * of it (the next ones are 0.125 away along x); the points within reach there
 * (bk_contact_state visits every point); the step limiter of a fall of 0.2 by
 * every node: 0.9 of the nearest point's distance 0.005 over 0.2. */
static void check_broad_phase(void)
{
    int cand[2], nact = 0;
    double alpha = 0.0;
    for (int moved = 0; moved < 2; ++moved) {
        scene s;
        bk_contact_prim sphere = {.shape = BK_CONTACT_SPHERE, .prm = {0.5, 0.0, 0.0, 0.1}, .amp = -1, .body = -1};
        sphere.motion[0] = moved ? 0.25 : 0.0;
        build(&s, 0.115, 100.0, sphere, 0.01, 0.01, 1e3);
        bk_system *sys = create(&s);
        double f[3 * NN], F[3], dmin, dx[3 * NN];
        contact_force(sys, s.q0, f, NULL);       /* (places the sphere at the factor 1) */
        cand[moved] = bk_contact_broad_phase(sys, s.q0, &(bk_path){.factor = 1.0, .x = 1.0});
        if (!moved) {
            bk_contact_state(sys, s.q0, F, &nact, &dmin);
            for (int i = 0; i < sys->neq; ++i)
                dx[i] = -0.2;
            alpha = bk_interactions_step_limit(sys, s.q0, dx);
        }
        bk_system_free(sys);
    }
    printf("case=broad_phase elements=%d candidates=%d candidates_moved=%d active=%d alpha=%.17g\n", NE, cand[0],
           cand[1], nact, alpha);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    check_jacobians();
    check_friction();
    check_resting_chain();
    check_step_limit();
    check_broad_phase();
    return 0;
}
