/* dyn_residual.c -- one time step's Newton problem of the generalized-alpha
 * dynamics (dynamics.c): the residual and iteration matrix, the corrections of
 * q, q' and q'', the interactions' step limit, and the predictor cut to it. */
#include "analysis/dynamics_impl.h"

#include <math.h>
#include <string.h>

#include "solver/norms.h"

/* Residual of one Newton iteration at q (t_{n+1} = tn) into w->r (free rows, then the
 * scaled constraint rows), its 2-norm into *rnorm; with `matrix`, also the iteration
 * matrix K_t (1 + gamma' beta_R) + (beta' + gamma' alpha_R) M + rotary/viscous terms
 * + constraint rows into w->Ax.  Returns nonzero on a non-finite force. */
int bk_dyn_residual(bk_system *s, dyn_work *w, const int *fdof, const double *q, double tn, double bp, double gp,
                    int matrix, double *rnorm)
{
    const bk_model *m = s->m;
    const bk_dynamic_opts *o = &m->dyn;
    const int nd = m->ndof;
    const double ra = o->rayleigh_alpha, rb = o->rayleigh_beta;
    /* the damping force beta_R K_t q' needs K_t even when the matrix is kept */
    double *A = matrix || rb != 0.0 ? w->Ax : NULL;
    if (bk_assemble_internal(s, q, w->fint, A) != 0)
        return -1;
    const double *pv = bk_dyn_power_velocity(s, w, q, tn);      /* (sets the frame's time) */
    w->p_damp = 0.0;
    if (rb != 0.0) {                    /* stiffness-proportional Rayleigh damping */
        bk_dyn_free_matvec(s, fdof, w->Ax, w->qd, w->tmp);
        for (int i = 0; i < nd; ++i)
            w->fint[i] += rb * w->tmp[i];
        w->p_damp = rb * bk_dyn_dot_free(s, fdof, w->tmp, pv);
        if (matrix)
            for (long k = 0; k < s->nnz; ++k)
                w->Ax[k] *= 1.0 + gp * rb;
    }
    A = matrix ? w->Ax : NULL;
    const bk_path path = {.factor = 1.0, .x = tn, .qd = w->qd, .gp = gp};
    const double p_before = bk_dyn_dot_free(s, fdof, w->fint, pv);
    if (bk_assemble_interactions(s, q, &path, w->fint, A) != 0)
        return -1;
    w->p_inter = bk_dyn_dot_free(s, fdof, w->fint, pv) - p_before;
    bk_dyn_element_dynamics(s, w, q, gp, bp, 1.0, w->fint, A);
    if (w->frame)                       /* the frame's forces, inertia like M q'' */
        bk_frame_forces(w->frame, s, q, w->qd, gp, 1.0, w->fint, A);
    w->p_damp += w->p_visc;
    bk_dyn_mass_matvec(s, w, fdof, w->qdd, w->tmp);
    for (int i = 0; i < nd; ++i)
        w->fint[i] += w->tmp[i];
    if (ra != 0.0) {
        bk_dyn_mass_matvec(s, w, fdof, w->qd, w->tmp);
        for (int i = 0; i < nd; ++i)
            w->fint[i] += ra * w->tmp[i];
        w->p_damp += ra * bk_dyn_dot_free(s, fdof, w->tmp, pv);
    }
    if (matrix)
        for (long k = 0; k < s->nnz; ++k)
            w->Ax[k] += (bp + gp * ra) * w->Mx[k];
    for (int i = 0; i < nd; ++i)
        if (s->eq[i] >= 0)
            w->r[s->eq[i]] = w->fint[i] - w->fext[i];
    double c_before = 0.0, c_after = 0.0;
    for (int j = 0; j < s->nfree; ++j)
        c_before += w->r[j] * pv[fdof[j]];
    bk_assemble_constraints(s, q, w->nu, bk_frame_ctime(w->frame, tn), w->r, A);
    for (int j = 0; j < s->nfree; ++j)
        c_after += w->r[j] * pv[fdof[j]];
    w->p_con = c_after - c_before;
    *rnorm = bk_norm2(w->r, s->nfree);
    return isfinite(*rnorm) ? 0 : -1;
}


int bk_dyn_problem_residual(void *ctx, int matrix, double *r, double *Ax, bk_nl_eval *ev)
{
    dyn_problem *p = ctx;
    bk_system *s = p->s;
    dyn_work *w = p->w;
    const bk_model *m = s->m;
    (void)r;                                    /* w->r is the solver's buffer */
    w->Ax = Ax;                                 /* (made anew when the pattern grew: system.h) */
    if (bk_dyn_mass_follow(s, w) != 0 ||
        bk_dyn_residual(s, w, p->fdof, p->q, p->tn, p->bp, p->gp, matrix, &ev->rnorm) != 0)
        return -1;
    ev->ref = fmax(bk_norm2(w->fext, m->ndof), bk_norm2(w->fint, m->ndof));
    ev->cres = bk_norm2(w->r + s->nfree, s->ncon) / s->cscale;
    /* increments relative to the motion of this step */
    ev->uscale = fmax(1e-12 * m->length_scale, bk_norm_dof_max(p->norms, s, p->q, w->q_s));
    ev->escale = 0.0;
    return 0;
}

/* The interactions' step limit (e.g. no contact gap crosses zero). */
double bk_dyn_problem_step_limit(void *ctx, const double *dx)
{
    const dyn_problem *p = ctx;
    return bk_interactions_step_limit(p->s, p->q, dx);
}

void bk_dyn_problem_update(void *ctx, const double *dx, double alpha)
{
    dyn_problem *p = ctx;
    const bk_system *s = p->s;
    dyn_work *w = p->w;
    for (int j = 0; j < s->nfree; ++j) {
        int i = p->fdof[j];
        double d = alpha * dx[j];
        p->q[i] += d;
        w->qd[i] += p->gp * d;
        w->qdd[i] += p->bp * d;
    }
    for (int c = 0; c < s->ncon; ++c)
        w->nu[c] += alpha * dx[s->nfree + c];
}

/* Beam-to-beam contact: the constant-acceleration predictor q* of the step
 * is taken only as far as the interactions' step limit allows from q_n (a
 * predictor may carry a beam through another, where no distance is negative
 * to tell).  The held-position predictor plus alpha (q* - q_n) by dp_update
 * keeps the Newmark relations, since they are linear.  dx: [neq] scratch.
 * 0, or -1 when out of memory. */
int bk_dyn_limit_predictor(dyn_problem *p, double *dx, double am, double af, double bet, double gam, double h)
{
    bk_system *s = p->s;
    dyn_work *w = p->w;
    for (int j = 0; j < s->neq; ++j)
        dx[j] = j < s->nfree ? p->q[p->fdof[j]] - w->q_s[p->fdof[j]] : 0.0;
    if (bk_interactions_prepare(s, w->q_s) != 0)
        return -1;
    const double alpha = bk_interactions_step_limit(s, w->q_s, dx);
    if (alpha < 1.0) {
        bk_dyn_predict(s, w, p->q, h, am, af, bet, gam, 1);
        bk_dyn_problem_update(p, dx, alpha);
    }
    return 0;
}
