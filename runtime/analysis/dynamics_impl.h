/* dynamics_impl.h -- what the time integration (dynamics.c) shares with its
 * work arrays and mass operations (dynamics_work.c), private to analysis/. */
#ifndef BK_DYNAMICS_IMPL_H
#define BK_DYNAMICS_IMPL_H

#include <stddef.h>

#include "analysis/dyn_frame.h"
#include "assembly/system.h"
#include "solver/nonlinear.h"
#include "solver/norms.h"

/* dynamic.jacobian = "reuse" (modified Newton across steps): the Jacobian-reuse
 * policy of the nonlinear solver (nonlinear.h, BK_REUSE_*); a step that fails
 * with kept factors is retried with full Newton before it is halved. */
typedef struct dyn_work {
    int nd, ne, nc;
    double *qd, *qdd, *a, *nu;                 /* state at t_n (q is the caller's)   */
    double *q_s, *qd_s, *qdd_s, *a_s, *nu_s;   /* saved for cut-backs                 */
    double *q_m, *qd_m;                        /* a Bathe step's mid state (dyn_bathe.c) */
    double *fint, *fext, *fgrav, *Mx, *tmp;
    double *r, *dx, *Ax;                       /* the nonlinear solver's buffers (not owned) */
    double *qe, *qde, *qdde, *fe, *K1, *K2, *K3;   /* element buffers */
    /* Kelvin-Voigt damping BK_LANES elements per call (bk_pair.viscous_lanes), lane
     * order: coordinates, velocities, tables, parameters, force, Newton-matrix part
     * (64-byte aligned; NULL when no element of the model takes them); vtab holds
     * every lane group's tables, made once */
    double *vq, *vqd, *vtab, *vvisc, *vf, *vK;
    size_t vnt;               /* table entries per lane of vtab's groups (one run's tables each) */
    int *Mp, *Mi;             /* the mass matrix's nonzeros of the free block, compressed columns */
    double *Mv;
    int mass_gen;             /* the pattern version (system.h pattern_gen) Mx is in */
    /* powers at the last residual (dyn_energy.h): of the interactions' and the
     * constraints' forces as they enter the residual, of damping (Rayleigh, viscous) */
    double p_inter, p_con, p_damp, p_visc;
    /* the rotating frame (dyn_frame.h; NULL: inertial), and the velocity the powers
     * are taken with there (the inertial one in the frame's axes, bk_frame_velocity) */
    bk_dyn_frame *frame;
    double *va;
} dyn_work;

void bk_dyn_work_free(dyn_work *w);
int bk_dyn_work_alloc(dyn_work *w, const bk_system *s);
void bk_dyn_assemble_mass(const bk_system *s, double *Mx, double *work, double *Me);
void bk_dyn_free_matvec(const bk_system *s, const int *fdof, const double *Ax, const double *x,
                        double *y);
void bk_dyn_compact_mass(const bk_system *s, dyn_work *w, const double *Mx);
/* Mx again in the system's pattern when it grew since (beam-to-beam contact
 * couples elements as it finds them): 0, or -1 when out of memory. */
int bk_dyn_mass_follow(const bk_system *s, dyn_work *w);
void bk_dyn_mass_matvec(const bk_system *s, const dyn_work *w, const int *fdof, const double *x, double *y);
double bk_dyn_dot_free(const bk_system *s, const int *fdof, const double *a, const double *b);
int *bk_dyn_free_dofs(const bk_system *s);
/* The predictor of a step of length h from the state saved in w (q_s, qd_s,
 * qdd_s, a_s) into q, w->qd, w->qdd: position = 0, constant acceleration
 * (q''_{n+1} = q''_n: the best guess for smooth motion); position = 1, the
 * position held (q_{n+1} = q_n, velocities and accelerations from the
 * Newmark relations: after a sudden load the stiff local modes carry
 * accelerations that, extrapolated over a step many times their period, put
 * the guess far outside the admissible states). */
void bk_dyn_predict(const bk_system *s, dyn_work *w, double *q, double h, double am, double af, double bet,
                    double gam, int position);
/* The kinetic energy at q, w->qd, time t (in a rotating frame the inertial one),
 * and the velocity the powers are taken with (w->qd, in the frame w->va at t). */
double bk_dyn_kinetic(const bk_system *s, dyn_work *w, const int *fdof, const double *q, double t);
const double *bk_dyn_power_velocity(const bk_system *s, dyn_work *w, const double *q, double t);
double bk_dyn_element_dynamics(const bk_system *s, dyn_work *w, const double *q, double gp, double bp,
                               double kp, double *fint, double *Ax);


/* One step's Newton problem for the nonlinear solver (nonlinear.h): the
 * residual at t_{n+1} = tn, corrections of q by dq, of q' by gamma' dq and of
 * q'' by beta' dq. */
typedef struct dyn_problem {
    bk_system *s;
    dyn_work *w;
    const int *fdof;
    const bk_norms *norms;
    double *q;
    double tn, bp, gp;
} dyn_problem;

/* dyn_residual.c: the residual at q (t_{n+1} = tn) into w->r, its norm into
 * *rnorm, with `matrix` the iteration matrix into w->Ax (nonzero on a
 * non-finite force); the step's Newton problem for the nonlinear solver
 * (nonlinear.h bk_nl_problem: residual, update, step limit, ctx a dyn_problem);
 * the predictor cut to the interactions' step limit (dx: [neq] scratch; 0, or
 * -1 when out of memory). */
int bk_dyn_residual(bk_system *s, dyn_work *w, const int *fdof, const double *q, double tn, double bp, double gp,
                    int matrix, double *rnorm);
int bk_dyn_problem_residual(void *ctx, int matrix, double *r, double *Ax, bk_nl_eval *ev);
double bk_dyn_problem_step_limit(void *ctx, const double *dx);
void bk_dyn_problem_update(void *ctx, const double *dx, double alpha);
int bk_dyn_limit_predictor(dyn_problem *p, double *dx, double am, double af, double bet, double gam, double h);

#endif
