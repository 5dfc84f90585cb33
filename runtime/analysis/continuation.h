/* continuation.h -- the arc-length continuation's parts (private to
 * analysis/): the bordered Newton step and its tangent, the bisection of limit
 * points, the branch switch (arc_step.c) and the visited path that detects
 * closed loops (arc_path.c); continuation.c runs the path. */
#ifndef BK_CONTINUATION_H
#define BK_CONTINUATION_H

#include "analysis/static_problem.h"

/* ---- Arc-length continuation (static.method = "arc_length") ----
 *
 * The unknowns x (free DOFs and multipliers) and the load factor lam follow
 * the equilibrium path r(x, lam) = 0 in steps of arc length dl:
 *     |x - x_n|_W^2 + psi^2 (lam - lam_n)^2 = dl^2
 * (Crisfield).  W weighs the free DOFs: 1 for positions, L^2 for the
 * dimensionless fields (position gradients, quaternions; L the model's length
 * scale), so that a rotation counts as the motion it causes over the model, 0
 * for multipliers; psi = 0 (cylindrical) or psi^2 = t0' W t0 (spherical: a
 * unit load factor counts as the linear displacement at full load, t0 the
 * tangent at the start).  Each Newton correction is bordered: with
 * K dx_r = -r and K t = -dr/dlam, dx = dx_r + dlam t with dlam from the
 * constraint (the root nearer the current increment; where the quadratic has
 * none, the dlam closest to satisfying it).  The predictor goes along the
 * tangent, oriented so that it makes an acute angle with the last increment:
 * the path never turns back, and the load factor may exceed 1 and go down.
 * The arc length follows the iteration count (sqrt(arc_iterations / iters),
 * in [0.5, 2], at most 8 times the first or 0.05 of the model length), is
 * halved on failure, and the first is the arc of a load increment
 * target / load_steps along the tangent.  With static.branch_switch the step
 * after the first bifurcation starts along the null vector of the tangent
 * (the eigenvector of its eigenvalue nearest zero) with the load factor kept:
 * the arc-length sphere about the equilibrium past the bifurcation meets the
 * secondary branch, and the path follows it from there. */
typedef struct arc_ctx {
    static_problem sp;               /* the residual, the update of q and nu; sp.lam: the iterate's */
    work *w;
    const double *W;                 /* [neq] weights of the constraint */
    const int *fdof;                 /* [nfree] equation -> DOF */
    double *rl, *t, *tmp, *fol;      /* [neq] x 3, [ndof] */
    double lam0;                     /* the load factor at the start of the step (x_n: w->qsave) */
    double dl, psi2;
    double pending;                  /* the load-factor part of the last correction */
} arc_ctx;

/* The path state of one equilibrium (for the bisection of a limit point). */
typedef struct arc_point {
    double *q, *nu;
    double lam;
} arc_point;

/* ---- Closed loops: a return to a visited point of the path ----
 * Every accepted equilibrium is kept: its load factor, the displacements of
 * the first sensors and, while the kept states fit in ARC_PATH_BUDGET doubles,
 * the full state q.  After each step the new point is compared with every
 * kept segment [k, k+1] of the path that ends at least two steps and four
 * tolerances (below) of arc length before it.
 * First cheaply: the load factor and each sensor's displacement inside the
 * segment's range widened by a quarter of the change over the last step and
 * over the segment.  Then, for those candidates, the full state: the distance
 * from the new point to the segment in the metric of the arc-length
 * constraint (W, psi), quaternions compared as the rotations they stand for
 * (normalised, p and -p alike).  Below a quarter of the larger of the last
 * arc and the segment's length, the path is back where it was: a closed
 * loop, reported with the segment and stopped. */
#define ARC_PATH_BUDGET (1L << 24)
typedef struct arc_path {
    int n, cap, ns, nd, nquat;       /* points, capacity, sensors, DOFs, quaternion nodes */
    double *lam, *arc, *u, *q;       /* [cap], [cap] (arc length from the start), [cap][3 ns], [cap][nd] (the first nq) */
    int nq, qcap;                    /* points whose state is kept, room for them */
    int *quat;                       /* [nquat][4] DOFs of each quaternion node */
    char *isq;                       /* [nd] 1: a DOF of a quaternion */
} arc_path;

/* A bifurcation candidate of a path: the critical point, the negative
 * eigenvalue counts before and after, taken back (a flicker about zero). */
typedef struct candidate {
    bk_critical_point cp;
    int neg[2];
    char gone;
} candidate;

/* Bisections of a limit point; steps within which a limit point claims a
 * change of the negative-eigenvalue count. */
#define ARC_BISECTIONS 14
#define ARC_NEAR 3

void bk_load_derivative(bk_system *s, work *w, const double *q, double lam, double *rl, double *fol,
                        double *tmp);
int bk_arc_augment(void *ctx, bk_linsolver *ls, double *dx);
void bk_arc_update(void *ctx, const double *dx, double alpha);
double bk_arc_step_limit(void *ctx, const double *dx);
/* (arc_step.c) assembled: w->Ax already holds the Newton matrix at (q, w->nu,
 * lam) (the stability check's assembly there): not assembled again. */
int bk_arc_tangent(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, double lam, int assembled, double *tWt);
int bk_arc_step(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, double lam0, double sigma, double tWt,
                double dl, const bk_static_opts *o, attempt *a, int step, bk_run_info *info, double lam_scale);
void bk_sensor_displacements(const bk_model *m, const double *q, bk_critical_point *cp);
double bk_max_sensor_displacement(const bk_model *m, const double *q);
void bk_arc_save(const bk_system *s, const work *w, const double *q, double lam, arc_point *p);
void bk_arc_restore(const bk_system *s, work *w, double *q, double *lam, const arc_point *p);
double bk_arc_orientation(const bk_system *s, const arc_ctx *c, const double *q, double lam,
                          const double *q_from, double lam_from);
double bk_arc_bisect_limit(bk_system *s, bk_nl *nl, arc_ctx *c, double *q, const arc_point *A,
                           double sigma_a, double dl, const bk_static_opts *o, attempt *a, int step,
                           bk_run_info *info, arc_point *best, double lam_b);
void bk_branch_direction(const bk_system *s, const bk_stability *st, arc_ctx *c, double *tWt);
void bk_arc_path_free(arc_path *p);
int bk_arc_path_push(arc_path *p, const bk_model *m, const double *q, double lam, double arc);
int bk_arc_path_near(const arc_path *p, int k, const double *u, double lam, const double *du, double dlam);
void bk_arc_path_distance(const arc_path *p, const bk_system *s, const arc_ctx *c, double L2, int k,
                          const double *q, double lam, double *dist, double *len);

#endif
