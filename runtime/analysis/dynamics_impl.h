/* dynamics_impl.h -- what the time integration (dynamics.c) shares with its
 * work arrays and mass operations (dynamics_work.c), private to analysis/. */
#ifndef BK_DYNAMICS_IMPL_H
#define BK_DYNAMICS_IMPL_H

#include <stddef.h>

#include "assembly/system.h"

/* dynamic.jacobian = "reuse" (modified Newton across steps): the Jacobian-reuse
 * policy of the nonlinear solver (nonlinear.h, BK_REUSE_*); a step that fails
 * with kept factors is retried with full Newton before it is halved. */
typedef struct dyn_work {
    int nd, ne, nc;
    double *qd, *qdd, *a, *nu;                 /* state at t_n (q is the caller's)   */
    double *q_s, *qd_s, *qdd_s, *a_s, *nu_s;   /* saved for cut-backs                 */
    double *fint, *fext, *fgrav, *Mx, *tmp;
    double *r, *dx, *Ax;                       /* the nonlinear solver's buffers (not owned) */
    double *qe, *qde, *qdde, *fe, *K1, *K2, *K3;   /* element buffers */
    int *Mp, *Mi;             /* the mass matrix's nonzeros of the free block, compressed columns */
    double *Mv;
    /* powers at the last residual (dyn_energy.h): of the interactions' and the
     * constraints' forces as they enter the residual, of damping (Rayleigh, viscous) */
    double p_inter, p_con, p_damp, p_visc;
} dyn_work;

void bk_dyn_work_free(dyn_work *w);
int bk_dyn_work_alloc(dyn_work *w, const bk_system *s);
void bk_dyn_assemble_mass(const bk_system *s, double *Mx, double *work, double *Me);
void bk_dyn_free_matvec(const bk_system *s, const int *fdof, const double *Ax, const double *x,
                        double *y);
void bk_dyn_compact_mass(const bk_system *s, dyn_work *w, const double *Mx);
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
double bk_dyn_element_dynamics(const bk_system *s, dyn_work *w, const double *q, double gp, double bp,
                               double kp, double *fint, double *Ax);

#endif
