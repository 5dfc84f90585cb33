/* beam_contact_check.c -- the beam-to-beam contact interaction (runtime/
 * assembly/beam_contact*.c) on in-memory chains of the hand-written springs
 * of spring_element.c: the broad phase against a comparison of every pair of
 * boxes (written here); the pattern growing when chains that started apart
 * come near; the assembled forces and Jacobian against central differences
 * of the residual on four chains (one crossing another at right angles, one
 * at 15 degrees: in the blend of crossing and parallel contact, one lying
 * beside it: edge-edge, point-edge and point-point distances);
 * action = reaction.
 * Prints "case=NAME key=value ..." lines for tests/test_beam_contact.py. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/beam_contact.h"
#include "assembly/contact_broad.h"
#include "assembly/system.h"
#include "spring_element.h"

#define NC 4                             /* chains */
#define NN 9                             /* nodes per chain */
#define NE (NN - 1)
#define NEL (NC * NE)
#define NDOF (3 * NC * NN)

typedef struct scene {
    bk_model m;
    const bk_pair *pairs[1];
    double geoms[NEL][BK_NGEOM];
    int geom_pair[NEL], geom_elem[NEL];
    double tabbuf[NEL][1];
    double *tabs[NEL];
    bk_mat mats[NEL];
    bk_elem elems[NEL];
    int dofs[NEL][6];
    double q0[NDOF], qd0[NDOF];
    bk_beam_contact_set set;
    bk_beam_contact_model bm;
    int chain_off[NC + 1], celems[NEL];
    double radius[NEL], s0[NEL];
} scene;

/* The point at t in [0, 1] along chain c: A along x at height za, B along y
 * crossing under A, C above A turned 15 degrees about z, D beside A. */
static void node_pos(int c, double t, double za, double *x)
{
    const double a = 15.0 * 3.14159265358979323846 / 180.0;
    if (c == 0)
        x[0] = t, x[1] = 0.5, x[2] = za;
    else if (c == 1)
        x[0] = 0.45, x[1] = t, x[2] = 0.0;
    else if (c == 2)
        x[0] = 0.5 + (t - 0.5) * cos(a), x[1] = 0.5 + (t - 0.5) * sin(a), x[2] = 2.0 * za;
    else
        x[0] = t, x[1] = 0.5 + za, x[2] = za;
}

static void build(scene *s, double za, double r, double shat, double kappa, int nsample)
{
    memset(s, 0, sizeof *s);
    bk_model *m = &s->m;
    snprintf(m->name, sizeof m->name, "beam_contact_check");
    m->analysis = BK_ANALYSIS_STATIC;
    m->length_scale = 1.0;
    m->ndof = NDOF;
    for (int c = 0; c < NC; ++c)
        for (int n = 0; n < NN; ++n)
            node_pos(c, (double)n / NE, za, s->q0 + 3 * (c * NN + n));
    s->pairs[0] = &spring_pair;
    m->q0 = s->q0, m->qd0 = s->qd0, m->npair = 1, m->pairs = s->pairs, m->geoms = s->geoms;
    m->geom_pair = s->geom_pair, m->geom_elem = s->geom_elem, m->tabs = s->tabs, m->mats = s->mats;
    m->elems = s->elems;
    for (int e = 0; e < NEL; ++e) {
        const int c = e / NE, k = e % NE, n0 = c * NN + k;
        for (int i = 0; i < 3; ++i)
            s->dofs[e][i] = 3 * n0 + i, s->dofs[e][3 + i] = 3 * (n0 + 1) + i;
        s->geoms[e][BK_GEOM_L] = 1.0 / NE;
        s->geoms[e][BK_GEOM_A] = 1e-4;
        s->mats[e].nparam = 1;
        s->mats[e].params[0] = 100.0;
        s->mats[e].rho = 1000.0;
        s->elems[e] = (bk_elem){.pair = 0, .geom = e, .mat = e, .dofs = s->dofs[e]};
        s->tabs[e] = s->tabbuf[e];
        s->celems[e] = e;
        s->radius[e] = r;
        s->s0[e] = (double)k / NE;
        double q0e[6];
        m->nelem = e + 1;
        m->ngeom = m->nmat = m->nelem;
        bk_gather(m, e, s->q0, q0e);
        spring_pair.tabulate(s->geoms[e], q0e, s->tabs[e]);
    }
    for (int c = 0; c <= NC; ++c)
        s->chain_off[c] = c * NE;
    s->set = (bk_beam_contact_set){.shat = shat, .kappa = kappa, .slip = 1e-6, .exclude = 0.0, .nsample = nsample,
                                   .self = 0, .nchain = NC, .chain_off = s->chain_off, .nelem = NEL,
                                   .elems = s->celems, .radius = s->radius, .s0 = s->s0};
    s->bm = (bk_beam_contact_model){.nset = 1, .sets = &s->set};
}

/* The system of the scene with the beam contact interaction made from the
 * scene's own sets (a model file would carry them in its record). */
static bk_system *make_system(scene *s)
{
    bk_system *sys = bk_system_create(&s->m, stderr);
    if (!sys)
        return NULL;
    void *self = NULL;
    const int r = bk_beam_contact_make(sys, &s->bm, &self);
    sys->inter[sys->ninter++] = (bk_interaction){&bk_beam_contact_ops, self};
    if (r != 0) {
        bk_system_free(sys);
        return NULL;
    }
    return sys;
}

/* The interaction's residual over all DOFs at q (nothing else). */
static int contact_force(bk_system *sys, const double *q, double *f, double *Ax)
{
    memset(f, 0, NDOF * sizeof *f);
    if (Ax)
        memset(Ax, 0, (size_t)sys->nnz * sizeof *Ax);
    return bk_assemble_interactions(sys, q, &(bk_path){.factor = 1.0, .x = 1.0}, f, Ax);
}

/* A configuration within the barrier's reach of several pairs: the chains'
 * nodes displaced by a few tenths of the reach, differently each. */
static void wavy(const scene *s, double shat, double *q)
{
    memcpy(q, s->q0, NDOF * sizeof *q);
    for (int i = 0; i < NDOF; ++i)
        q[i] += 0.3 * shat * sin(1.3 * i + 0.4);
}

static void check_jacobian(void)
{
    scene s;
    const double r = 0.01, shat = 0.01;
    build(&s, 2 * r + 0.6 * shat, r, shat, 1e3, 3);
    bk_system *sys = make_system(&s);
    double q[NDOF], f[NDOF], fp[NDOF], fm[NDOF], h = 1e-7;
    wavy(&s, shat, q);
    bk_interactions_prepare(sys, q);
    double *Ax = calloc((size_t)sys->nnz, sizeof *Ax);
    contact_force(sys, q, f, Ax);
    double amax = 0.0, err = 0.0, fmax_ = 0.0, sum[3] = {0.0, 0.0, 0.0};
    for (long k = 0; k < sys->nnz; ++k)
        amax = fmax(amax, fabs(Ax[k]));
    for (int i = 0; i < NDOF; ++i)
        sum[i % 3] += f[i], fmax_ = fmax(fmax_, fabs(f[i]));
    for (int j = 0; j < NDOF; ++j) {
        const double qj = q[j];
        q[j] = qj + h;
        contact_force(sys, q, fp, NULL);
        q[j] = qj - h;
        contact_force(sys, q, fm, NULL);
        q[j] = qj;
        for (int i = 0; i < NDOF; ++i) {
            double a = 0.0;
            for (int k = sys->Ap[sys->eq[j]]; k < sys->Ap[sys->eq[j] + 1]; ++k)
                if (sys->Ai[k] == sys->eq[i])
                    a = Ax[k];
            err = fmax(err, fabs((fp[i] - fm[i]) / (2 * h) - a));
        }
    }
    double F[3 * NC], dmin;
    int nact;
    bk_beam_contact_state(sys, q, 0, F, &nact, NULL, &dmin);
    printf("case=jacobian err=%.3e amax=%.4g active=%d min_distance=%.4g shat=%.4g force_sum=%.3e force_max=%.4g\n",
           amax > 0.0 ? err / amax : err, amax, nact, dmin, shat,
           sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]), fmax_);
    free(Ax);
    bk_system_free(sys);
}

/* Chains that start far apart (no candidate pair): the pattern holds no
 * coupling; brought within reach, prepare finds the pairs and the pattern
 * grows by their blocks. */
static void check_growth(void)
{
    scene s;
    const double r = 0.01, shat = 0.01;
    build(&s, 0.5, r, shat, 1e3, 3);
    bk_system *sys = make_system(&s);
    const long nnz0 = sys->nnz;
    const int gen0 = sys->pattern_gen, ncouple0 = sys->ncouple;
    double q[NDOF];
    memcpy(q, s.q0, sizeof q);
    for (int n = 0; n < NN; ++n)             /* chain A (and C) lowered onto B */
        q[3 * n + 2] = 2 * r + 0.5 * shat, q[3 * (2 * NN + n) + 2] = 1.0, q[3 * (3 * NN + n) + 2] = 1.0;
    bk_interactions_prepare(sys, q);
    double F[3 * NC], dmin;
    int nact;
    bk_beam_contact_state(sys, q, 0, F, &nact, NULL, &dmin);
    printf("case=growth nnz0=%ld nnz1=%ld gen0=%d gen1=%d couple0=%d couple1=%d active=%d\n", nnz0, sys->nnz, gen0,
           sys->pattern_gen, ncouple0, sys->ncouple, nact);
    bk_system_free(sys);
}

static unsigned long long rng = 0x9E3779B97F4A7C15ULL;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* Random boxes of mixed sizes: the spatial hash's pairs against every pair compared. */
static void check_broad(void)
{
    enum { NB = 2000 };
    static bk_box box[NB];
    int missing = 0, extra = 0, nbrute = 0, *pairs = NULL, cap = 0;
    for (int b = 0; b < NB; ++b)
        for (int d = 0; d < 3; ++d) {
            const double c = urand(), h = 0.01 + 0.05 * urand() * urand();
            box[b].lo[d] = c - h, box[b].hi[d] = c + h;
        }
    int np = bk_broad_pairs(box, NB, &pairs, &cap);
    char *hit = calloc((size_t)NB * NB, 1);
    for (int k = 0; k < np; ++k)
        hit[pairs[2 * k] * NB + pairs[2 * k + 1]]++;
    for (int i = 0; i < NB; ++i)
        for (int j = i + 1; j < NB; ++j) {
            int ov = 1;
            for (int d = 0; d < 3; ++d)
                ov &= !(box[i].hi[d] < box[j].lo[d] || box[j].hi[d] < box[i].lo[d]);
            nbrute += ov;
            missing += ov && hit[i * NB + j] != 1;
            extra += !ov && hit[i * NB + j];
        }
    printf("case=broad pairs=%d brute=%d missing=%d extra=%d\n", np, nbrute, missing, extra);
    free(hit);
    free(pairs);
}

/* Friction: the lagged states taken at the wavy configuration, then every
 * node moved sideways by a different amount (slips from a tenth of the
 * tolerance to many: sticking and sliding pairs); the Jacobian against
 * central differences there. */
static void check_friction(void)
{
    scene s;
    const double r = 0.01, shat = 0.01;
    build(&s, 2 * r + 0.6 * shat, r, shat, 1e3, 3);
    s.set.mu = 0.4;
    s.set.mu_k = 0.25;                       /* (slips across eps ... 2 eps: the transition's derivative) */
    s.set.slip = 1e-4;
    bk_system *sys = make_system(&s);
    double q[NDOF], f[NDOF], fp[NDOF], fm[NDOF], h = 1e-8;
    wavy(&s, shat, q);
    bk_interactions_prepare(sys, q);
    bk_interactions_accept(sys, q, &(bk_path){.factor = 1.0, .x = 1.0});
    for (int n = 0; n < NC * NN; ++n) {
        q[3 * n] += 2e-5 * (1 + n % 7) * cos(0.9 * n);
        q[3 * n + 1] += 2e-5 * (1 + n % 5) * sin(0.7 * n);
    }
    double *Ax = calloc((size_t)sys->nnz, sizeof *Ax);
    contact_force(sys, q, f, Ax);
    double amax = 0.0, err = 0.0, sum[3] = {0.0, 0.0, 0.0}, fmx = 0.0;
    for (long k = 0; k < sys->nnz; ++k)
        amax = fmax(amax, fabs(Ax[k]));
    for (int i = 0; i < NDOF; ++i)
        sum[i % 3] += f[i], fmx = fmax(fmx, fabs(f[i]));
    for (int j = 0; j < NDOF; ++j) {
        const double qj = q[j];
        q[j] = qj + h;
        contact_force(sys, q, fp, NULL);
        q[j] = qj - h;
        contact_force(sys, q, fm, NULL);
        q[j] = qj;
        for (int i = 0; i < NDOF; ++i) {
            double a = 0.0;
            for (int k = sys->Ap[sys->eq[j]]; k < sys->Ap[sys->eq[j] + 1]; ++k)
                if (sys->Ai[k] == sys->eq[i])
                    a = Ax[k];
            err = fmax(err, fabs((fp[i] - fm[i]) / (2 * h) - a));
        }
    }
    printf("case=friction err=%.3e amax=%.4g force_sum=%.3e force_max=%.4g\n", amax > 0.0 ? err / amax : err, amax,
           sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]), fmx);
    free(Ax);
    bk_system_free(sys);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    check_broad();
    check_growth();
    check_jacobian();
    check_friction();
    return 0;
}
