/* contact_impl.h -- what the contact interaction's files share (private to
 * assembly/): its scratch, a sample point as the visitor sees it, the visitor
 * and the point's force (contact_points.c), the broad phase
 * (contact_near.c), the output hooks (contact_output.c). */
#ifndef BK_CONTACT_IMPL_H
#define BK_CONTACT_IMPL_H

#include <stdio.h>

#include "assembly/contact_force.h"
#include "assembly/contact_geometry.h"
#include "assembly/system.h"
#include "base/csvrow.h"
#include "base/pointframes.h"
#include "base/tables.h"

/* Scratch of the interaction: one element's force and matrix, the lagged
 * friction state, the primitives' placements. */
typedef struct contact_work {
    bk_contact_model *cm;            /* owned: the primitives and sets (the model's record "contact") */
    double *fe, *Ke;                 /* [maxdof + 7], [(maxdof + 7)^2]: the element's and its body's coordinates */
    double *Kc;                      /* [9 nshape (nshape + 1)] the element's position blocks (points without a body) */
    FILE *table;                     /* contacts.csv (registered in the run's tables), or NULL */
    FILE *totals;                    /* contact_totals.csv, or NULL */
    double *tot;                     /* [6 nset] the sets' sums of an output step */
    int npoint;                      /* sample points of every set */
    double *lam, *nrm, *xprev;       /* [npoint], [3 npoint] x 2: the lagged normal force, normal, anchor (in z) */
    double *arm;                     /* [3 npoint] a rolling point's lever arm in its node's frame (lagged) */
    int *qdof;                       /* [npoint] the element DOF of the quaternion of the node nearest the point
                                      * (its section's rotation), -1: the element has none (it slides) */
    double *place;                   /* [BK_CONTACT_PLACEMENT nprim] each primitive's placement at the path point
                                      * last assembled */
    double *Nc;                      /* the sample points' shape functions, each point's nshape of them */
    long *Noff;                      /* [npoint + 1] where each point's are in Nc */
    double *X;                       /* [3 npoint] the sample points' positions at the last broad phase */
    unsigned char *cand;             /* [the sets' elements] 1: a candidate of the last broad phase */
    double *lb;                      /* [the sets' elements] a lower bound of their points' distances there */
    bk_point_frames pf;              /* ParaView frames contacts_NNNNNN.vtp, contacts.pvd */
} contact_work;

/* A sample point as the visitor sees it (each_point). */
typedef struct point {
    const bk_contact_set *set;
    const bk_contact_prim *prim;
    int c, i, e, k, p;               /* set, member of the set, element, sample, index over every set */
    const bk_element *et;
    double wl;                       /* kappa times the point's share of the element's length */
    const double *N;                 /* shape functions (the element type's nshape, in contact_work.Nc) */
    double x[3];                     /* position */
    double qb[7];                    /* the primitive's body's coordinates (when it has one) */
    bk_contact_map mp;               /* x in the primitive's reference coordinates, mp.z, with derivatives */
    double g[13], dist;              /* the primitive's gap at mp.z with derivatives; the section's distance */
    const double *qe;                /* the element's coordinates */
    int roll;                        /* 1: friction acts on the section's surface point y = x + w (it rubs and
                                      * its element carries rotations), 0: on the centreline point x */
    double lev[31];                  /* roll: bk_contact_lever of the arm (w, dw/dp; the f term not set) */
    bk_contact_map mpf;              /* roll: y in the primitive's reference coordinates (friction's point) */
} point;

/* The shape functions of every sample point into w->Nc, w->Noff (allocated
 * here; they depend on the reference geometry only).  0, or -1 out of memory. */
int contact_sample_shapes(contact_work *w, const bk_model *m);

/* Each primitive's placement at the path point x (the amplitudes' variable). */
void contact_set_placement(contact_work *w, const bk_model *m, double x);

/* Calls fn(ctx, pt) for every sample point of every set at q (sets, their
 * elements, their samples, in order), and, when not NULL, element(ctx, pt,
 * 0) before an element's first point and element(ctx, pt, 1) after its last. */
void contact_each_point(const contact_work *w, const bk_system *s, const double *q, void (*fn)(void *, point *),
                        void (*element)(void *, point *, int), void *ctx);

/* The broad phase at q (contact_near.c; the placements set): every sample
 * point's position into w->X and, per element of every set, w->cand: 1 when
 * its points' box comes within the barrier's reach plus its section's radius
 * of the primitive, or one of its points rubs; w->lb a lower bound of the
 * element's points' distances (gap less radius).  Returns the candidates'
 * count.  An element that is no candidate has every point beyond the reach. */
int contact_broad(contact_work *w, const bk_system *s, const double *q);

/* After contact_broad at q, for the step limiter of the correction dx[neq]:
 * the elements that are no candidates but may move 0.9 of their distance's
 * lower bound (and every element of a primitive on a body) made candidates. */
void contact_limit_candidates(contact_work *w, const bk_system *s, const double *dx);

/* As contact_each_point, over the candidates of the last broad phase only
 * (their points' positions from w->X; run contact_broad at q first). */
void contact_each_candidate(const contact_work *w, const bk_system *s, const double *q,
                            void (*fn)(void *, point *), void (*element)(void *, point *, int), void *ctx);

/* Whether point pt feels the contact: within the barrier's reach, or rubbing. */
int contact_acts(const contact_work *w, const point *pt);

/* The barrier's force fp[3] (internal sign) and stiffness Kp[9] of a sample
 * point at the distance dist (g: the gap and its derivatives there). */
void contact_barrier_terms(const bk_contact_set *set, double wl, const double *g, double dist, double *fp,
                           double *Kp);

/* Adds the lagged friction's force and stiffness of sample point p at zf,
 * the point friction acts on in the primitive's reference coordinates. */
void contact_friction_terms(const contact_work *w, const bk_contact_set *set, int p, const double *zf, double *fp,
                            double *Kp);

/* Force fp[3] (internal sign) and stiffness Kp[9] of sample point p: the
 * barrier's at z, its centreline point in the primitive's reference
 * coordinates (g: the gap there), and the friction's at zf (z, or a rolling
 * point's surface point). */
void contact_point_terms(const contact_work *w, const bk_contact_set *set, int p, double wl, const double *z,
                         const double *zf, const double *g, double dist, double *fp, double *Kp);

/* The force fv[nv] and (Kv not NULL; not for a rolling point, whose friction
 * acts on other variables: contact_force.c assembles those) stiffness
 * Kv[nv^2] of point pt on its variables v (mp.nv: the point's position, then
 * its body's coordinates).  fv[0..2] is the force on the beam. */
void contact_point_force(const contact_work *w, const point *pt, double *fv, double *Kv);

/* The interaction's outputs (interaction.h: tables, rows, frame, summary). */
int contact_frame(void *self, const bk_system *s, const char *dir, int frame, double t, const double *q, FILE *err);
int contact_tables(void *self, const bk_system *s, bk_tables *ts, const char *dir, FILE *err);
void contact_rows(void *self, const bk_system *s, int step, double t, const double *q, bk_rowqueue *rq);
int contact_summary(void *self, const bk_system *s, const double *q, char *buf, size_t n);

#endif
