/* beam_contact_impl.h -- what the beam contact interaction's files share
 * (private to assembly/): its work data, the candidate segment pairs' visitor
 * and the distance of two segments (beam_contact.c), used by the forces,
 * the step limiter and the outputs (beam_contact_force.c). */
#ifndef BK_BEAM_CONTACT_IMPL_H
#define BK_BEAM_CONTACT_IMPL_H

#include <stdio.h>

#include "assembly/beam_contact_model.h"
#include "assembly/contact_broad.h"
#include "assembly/system.h"
#include "base/pointframes.h"

/* Below this sin^2 of their angle two segments count as parallel: their
 * distance is then the smallest of an end's to the other segment (the lines'
 * formula is undefined). */
#define PARALLEL_SIN2 1e-12
/* The blend of crossing and parallel contact (bc_pair_energy): squared
 * cosines of 20 and 10 degrees. */
#define BC_BLEND_C1 0.88302222155948895
#define BC_BLEND_C2 0.96984631039295421

/* The lagged friction state of a pair of segments (beam_contact_friction.c). */
typedef struct bc_lag {
    int key[5];                      /* set, i, k, j, l: the pair */
    double lam;                      /* normal force (N) */
    double n[3];                     /* unit normal: the direction of the force on the first segment */
    double sg, tau;                  /* the closest points' parameters the slip follows */
    double anchor[3];                /* their relative position P(sg) - Q(tau) where the slip counts from */
} bc_lag;

typedef struct bc_work {
    const bk_beam_contact_model *bm; /* the sets */
    bk_beam_contact_model *own;      /* the same when read from the model's record (owned), else NULL */
    int npt;                         /* sample points of every set */
    int *base, *ebase;               /* [nset] each set's first point, first element entry */
    int *chain;                      /* [entries] the beam of each element entry of each set */
    int nsh;                         /* the most shape functions of an element of the sets */
    double *N;                       /* [npt nsh] shape functions of each point (constant) */
    double *X, *Xref, *D;            /* [3 npt] positions; where the last broad phase saw them; a motion */
    double *margin;                  /* [nset] the broad phase's margin M (m) */
    int have_ref;
    int ncand, capcand;
    int *cand;                       /* [3 ncand] set, i, j: element entries to compare */
    int npair, cappair;
    int *pairs;                      /* the broad phase's pairs (scratch) */
    bk_box *box;                     /* [largest set's nelem] */
    double *fe[2], *Kb[4];           /* [maxdof], [maxdof^2]: forces of elements i, j; blocks ii ij ji jj */
    double *gp, *Hp, *T;             /* a candidate's gradient [n3] and Hessian [n3^2] on its sample points
                                      * (n3 = 6 times the largest nsample), the contraction's [n3 maxdof] */
    char *used;                      /* [n3 / 3] the candidate's points some pair touched */
    FILE *table;                     /* contacts.csv (shared with rigid contact), or NULL */
    int nlag;
    bc_lag *lag;                     /* [nlag] sorted by key: pairs in contact at the last accepted state */
    bk_point_frames pf;              /* ParaView frames beam_contacts_NNNNNN.vtp, .pvd (beam_contact_frames.c) */
} bc_work;

typedef struct seg_pair {
    int c, i, j, k, l;               /* set, entries, segments */
    int ei, ej;                      /* their elements */
    const double *pts[4];            /* x0, x1 (of i), y0, y1 (of j) */
    int pidx[4];                     /* their point indices */
    double sg, tau, d, dist;         /* closest points, distance of the centrelines, of the sections */
    double hi, hj;                   /* the segments' reference lengths */
} seg_pair;

void bc_free(void *self);
/* The step limiter (beam_contact_limit.c): the fraction of the correction
 * dx[neq] at q that keeps every sample point within M/4 of its motion and
 * every candidate pair at more than a tenth of its distance. */
double bc_step_limit(void *self, const bk_system *s, const double *q, const double *dx);
/* The contact force (barrier and friction) on the pair's first segment (fa;
 * the second gets its opposite) and its magnitude (0: none); when fn, ft are
 * not NULL, the barrier's and the friction's magnitudes
 * (beam_contact_force.c). */
double bc_pair_force(const bc_work *w, const bk_model *m, const seg_pair *sp, double *fa, double *fn, double *ft);
/* ParaView frames (beam_contact_frames.c): beam_contacts_NNNNNN.vtp at q, and
 * the collection beam_contacts.pvd (0, or -1 with a message on err). */
int bc_frame(void *self, const bk_system *s, const char *dir, int frame, double t, const double *q, FILE *err);
/* The broad phase again when a sample point moved more than M/4 since the
 * last one (or there was none): 0, or -1 when out of memory. */
int bc_prepare(void *self, bk_system *s, const double *q);
/* Every sample point's position from the DOF values v into X[3 npt], or,
 * with on_eq, its motion by the correction v[neq] on the equations. */
void bc_points(bc_work *w, const bk_system *s, const double *v, int on_eq, double *X);
/* Calls fn(ctx, sp) for every allowed segment pair of every candidate, and,
 * when not NULL, cand(ctx, sp, 0) before a candidate's first and cand(ctx,
 * sp, 1) after its last (at the positions w->X). */
void bc_each_pair(const bc_work *w, const bk_model *m, void (*fn)(void *, seg_pair *),
                  void (*cand)(void *, seg_pair *, int), void *ctx);
/* As bc_each_pair, but a candidate of two elements is left out when
 * skip(ctx, sp, gap) says so (sp: its set, entries and elements; gap: the
 * distance between the boxes of the two elements' sample points, a lower
 * bound of their segments' distances). */
void bc_each_near_pair(const bc_work *w, const bk_model *m, void (*fn)(void *, seg_pair *),
                       void (*cand)(void *, seg_pair *, int), int (*skip)(void *, const seg_pair *, double),
                       void *ctx);
/* The closest points x0 + sg (x1 - x0), y0 + tau (y1 - y0) of two segments
 * (pts[4] = x0, x1, y0, y1); returns their distance. */
double bc_closest(const double *const *pts, double *sg, double *tau);
/* The barrier energy of a segment pair over kappa (R the sum of the radii,
 * shat the reach, ha, hb the segments' lengths), with its gradient g[12] and
 * Hessian H[144] (H may be NULL) in (x0, x1, y0, y1).  Two energies blended by
 * the squared cosine c of their angle (a quintic smoothstep from c = C1 to
 * C2, C2 when 10 degrees apart): crossing, (ha + hb)/2 b(s) of the closest
 * points' distance s; along each other, the mean over the four ends of the
 * end's share of its segment (h/2) times b of its distance to the other
 * segment (one barrier per length of beam where two lie along each other,
 * smooth as an end passes from one segment to the next).  Distances from the
 * generated kernels (out/kernels/contact_pairs.h), the barrier from
 * out/kernels/contact.h. */
double bc_pair_energy(const seg_pair *sp, double R, double shat, double ha, double hb, double *g, double *H);

/* Friction (beam_contact_friction.c): the lagged state of the pair, or NULL;
 * the friction energy's gradient and Hessian (H may be NULL) added into g[12],
 * H[144] (N, N/m; not over kappa); accept: the lagged states at q. */
const bc_lag *bc_lag_find(const bc_work *w, const seg_pair *sp);
/* Whether a pair of segment k of entry i and segment l of entry j of set c
 * has a lagged state, for any k, l. */
int bc_lag_any(const bc_work *w, int c, int i, int j);
/* The pair's slip u_t[3] since its lagged anchor; returns |u_t| (m). */
double bc_slip(const bc_lag *lg, const seg_pair *sp, double *ut);
void bc_friction(const bk_beam_contact_set *set, const bc_lag *lg, const seg_pair *sp, double *g, double *H);
void bc_accept(void *self, const bk_system *s, const double *q, const bk_path *p);

#endif
