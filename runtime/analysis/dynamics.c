/* dynamics.c -- generalized-alpha for constrained (index-3) systems.
 *
 *   M q'' + f_int(q) + f_d(q, q') + f_rot(q, q', q'') + s G^T nu = f_ext(q, t),
 *   G(t) q = g(t)
 *
 * after Arnold and Bruls (2007): the equations hold exactly at t_{n+1}; the
 * algorithmic acceleration a obeys
 *   (1 - am) a_{n+1} + am a_n = (1 - af) q''_{n+1} + af q''_n,
 *   q_{n+1}  = q_n + h q'_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1},
 *   q'_{n+1} = q'_n + h (1 - gamma) a_n + h gamma a_{n+1},
 * with am = (2 rho - 1)/(rho + 1), af = rho/(rho + 1), gamma = 1/2 + af - am,
 * beta = (gamma + 1/2)^2 / 4 from the spectral radius at infinity rho
 * (Chung-Hulbert).  Newton corrects q by dq and q' by gamma' dq, q'' by beta' dq,
 * beta' = (1 - am)/(beta h^2 (1 - af)), gamma' = gamma/(beta h).  The constraint
 * rows and the multipliers are scaled by s = beta' m (m: mean mass diagonal),
 * so the iteration matrix stays balanced as h -> 0.
 *
 * Newton converges when the residual is below rtol times the force scale (or
 * its round-off floor), the constraints hold to 1e-12 L and the last increment
 * is below utol times the motion of the step.
 * A step whose Newton iteration fails is retried with half the step, and the
 * step controller (solver/step_control.h) remembers the failure: no regrowth
 * right after it, and not back to the size that failed until enough steps have
 * passed; with dynamic.tol > 0 the step follows the local error estimate
 *   e = h^2 |beta - 1/6| max|a_{n+1} - a_n| / L
 * (L the model's length scale), accepted when e <= tol.
 */
#include "analysis/analysis.h"
#include "analysis/dynamics.h"
#include "analysis/dynamics_impl.h"
#include "analysis/dyn_energy.h"
#include "analysis/dyn_bathe.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "output/checks.h"
#include "base/clock.h"
#include "base/interrupt.h"
#include "linalg/linsolve.h"
#include "solver/nonlinear.h"
#include "solver/norms.h"
#include "assembly/quaternion.h"
#include "solver/step_control.h"
#include "solver/null_motion.h"

enum { DYN_OK = BK_NL_OK, DYN_MAXIT = BK_NL_MAXIT, DYN_NONFINITE = BK_NL_NONFINITE, DYN_SINGULAR = BK_NL_SINGULAR,
       DYN_LINERR = BK_NL_LINERR, DYN_INADMISSIBLE = BK_NL_NCODES, DYN_ENERGY };

static const char *dyn_why(int c)
{
    switch (c) {
    case DYN_MAXIT: return "Newton did not converge within the iteration limit";
    case DYN_NONFINITE: return "non-finite force or increment (an element inverted, J <= 0, or a value overflowed)";
    case DYN_SINGULAR: return "singular iteration matrix: a motion with neither mass nor constraint, or a step "
                              "too large for the transient (try a smaller dt or a larger rho_inf)";
    case DYN_LINERR: return "linear solver error";
    case DYN_INADMISSIBLE: return "Newton converged to a state that is not physical (an element inverted)";
    case DYN_ENERGY: return "the step created energy";
    default: return "converged";
    }
}

/* A state's outputs (forces: reactions and sections too), in the inertial frame
 * (a rotating frame's state turned back: dyn_frame.h). */
static void dyn_output(bk_output *out, bk_system *s, dyn_work *w, int step, double t, const double *q,
                       const double *nu, int forces)
{
    const double *qd = w->qd, *qdd = w->qdd;
    if (w->frame) {
        bk_frame_at(w->frame, t);
        bk_frame_inertial(w->frame, s, q, qd, qdd, nu);
        q = w->frame->qa, qd = w->frame->qda, qdd = w->frame->qdda, nu = nu ? w->frame->nua : NULL;
    }
    if (forces)
        bk_output_forces(out, s, step, t, q, qd, qdd, nu);
    bk_output_step(out, step, t, q);
}

int bk_solve_dynamic(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    const bk_model *m = s->m;
    const bk_dynamic_opts *o = &m->dyn;
    dyn_work w = {0};
    bk_nl nl = {0};
    int have_nl = 0;
    bk_checks chk = {0};
    int rc = 1, *fdof = NULL;
    int nd = m->ndof;
    int nquat = 0;
    int step = 0, cuts = 0, written = 0;
    double t = 0.0, h = o->dt;
    int *quat = bk_quat_list(s, &nquat);
    FILE *energy = bk_output_table(out, &bk_energy_csv, stderr);
    bk_energy eb = {0};
    bk_dyn_frame frame = {0};
    if (!energy) {
        snprintf(info->message, sizeof info->message, "cannot write energy.csv");
        goto done;
    }
    if (bk_dyn_work_alloc(&w, s) != 0 || !(fdof = bk_dyn_free_dofs(s)) || nquat < 0 || bk_checks_init(&chk, s) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    if (bk_frame_init(&frame, s, info->message, sizeof info->message) != 0)
        goto done;
    w.frame = frame.on ? &frame : NULL;
    if (s->neq == 0) {
        snprintf(info->message, sizeof info->message, "every DOF is fixed: nothing to integrate");
        goto done;
    }
    have_nl = 1;
    if (bk_nl_init(&nl, s, info->message, sizeof info->message) != 0)
        goto done;
    w.r = nl.r, w.dx = nl.dx, w.Ax = nl.Ax;
    bk_linsolver *ls = &nl.ls;
    const double rho = o->rho_inf;
    const double am = (2.0 * rho - 1.0) / (rho + 1.0), af = rho / (rho + 1.0);
    const double gam = 0.5 + af - am, bet = 0.25 * (gam + 0.5) * (gam + 0.5);
    const double ra = o->rayleigh_alpha;
    /* Newton: rotation-invariant tests; converged when the residual is within
     * rtol (or far below it), the constraints hold to 1e-12 L and the last
     * correction is small in length or energy */
    const bk_nl_opts nlo = {.max_iter = o->max_iterations, .rtol = o->rtol, .utol = o->utol,
                            .ctol = 1e-12 * fmax(m->length_scale, 1.0), .accept_far_below = 1,
                            .stagnation = 0, .divergence = 0, .reuse = o->jacobian == BK_JACOBIAN_REUSE,
                            .lazy_matrix = 1};
    int full_retry = 0;                         /* this step failed with kept factors: full Newton */
    /* the predictor (bk_dyn_predict): constant acceleration, but the position
     * held once it failed at this step and, with memory, for the next
     * pred_hold steps (4, doubled while it keeps being needed, up to 64) */
    int retry_position = 0, pred_hold = 0, hold_len = 4;
    char inadm[640] = "";                       /* why the last inadmissible state was refused */
    bk_step_ctl ctl;
    bk_step_ctl_init(&ctl, fmax(o->dt, o->dt_min));
    const int bathe = o->integrator == BK_INTEGRATOR_BATHE;
    bk_dyn_mid mid = {0};
    double cscale_acc = 0.0;                    /* the scaling of the accepted multipliers (Bathe) */

    memcpy(q, m->q0, (size_t)nd * sizeof *q);
    memcpy(w.qd, m->qd0, (size_t)nd * sizeof *q);
    if (w.frame)
        bk_frame_initial(w.frame, s, q, w.qd);
    bk_external_load(s, w.fext);
    bk_gravity_load(s, w.fgrav);
    bk_dyn_assemble_mass(s, w.Mx, w.K1, w.K2);
    bk_dyn_compact_mass(s, &w, w.Mx);
    double mbar = 0.0;
    for (int j = 0; j < s->nfree; ++j)
        if (s->diag[j] >= 0)
            mbar += fabs(w.Mx[s->diag[j]]);
    mbar = s->nfree ? mbar / s->nfree : 1.0;
    if (!(mbar > 0.0))
        mbar = 1.0;

    /* Consistent initial accelerations: [M s G^T; s G 0] [q''; nu] = [f_ext - f(q, q'); -s (d^2/dt^2 of
     * the explicit time dependence)]; the mass is regularized by 1e-10 mbar where it vanishes
     * (gauge directions of quaternions). */
    {
        s->cscale = mbar;
        bk_assemble_internal(s, q, w.fint, w.Ax);
        memset(w.Ax, 0, (size_t)s->nnz * sizeof *w.Ax);
        const bk_path path = {.factor = 1.0, .x = t, .qd = w.qd};
        bk_assemble_interactions(s, q, &path, w.fint, NULL);
        bk_dyn_element_dynamics(s, &w, q, 0.0, 1.0, 0.0, w.fint, w.Ax);   /* q'' = 0 here: rotary mass into Ax */
        if (w.frame)
            bk_frame_forces(w.frame, s, q, w.qd, 0.0, 0.0, w.fint, NULL);
        for (int k = 0; k < (int)s->nnz; ++k)
            w.Ax[k] += w.Mx[k];
        for (int j = 0; j < s->nfree; ++j)
            if (s->diag[j] >= 0)
                w.Ax[s->diag[j]] += 1e-10 * mbar;
        bk_dyn_mass_matvec(s, &w, fdof, w.qd, w.tmp);               /* Rayleigh on the initial velocity */
        for (int i = 0; i < nd; ++i)
            if (s->eq[i] >= 0)
                w.r[s->eq[i]] = w.fext[i] - w.fint[i] - ra * w.tmp[i];
        bk_assemble_constraints(s, q, w.nu, bk_frame_ctime(w.frame, t), NULL, w.Ax);
        bk_constraint_accel_rhs(s, q, w.qd, bk_frame_ctime(w.frame, t), w.r);
        if (w.frame)
            bk_frame_held_rows(w.frame, s, w.r);   /* G q'' = -(d/dt G) q' - ... */
        if (bk_lin_factor(ls, w.Ax) != BK_LIN_OK || bk_lin_solve(ls, w.r) != BK_LIN_OK) {
            snprintf(info->message, sizeof info->message,
                     "initial accelerations: singular mass/constraint system (is every DOF given mass or held?)");
            goto done;
        }
        for (int i = 0; i < nd; ++i)
            w.qdd[i] = s->eq[i] >= 0 ? w.r[s->eq[i]] : 0.0;
        memcpy(w.a, w.qdd, (size_t)nd * sizeof *q);
    }
    double U0 = bk_strain_energy(s, q);
    double e_start = 0.0, e_scale = 0.0;   /* the total energy at t = 0, the largest of its parts since */
    int e_warned = 0, e_warned_num = 0;
    double w_con = 0.0, pcon_last = 0.0;   /* the work of prescribed motions (constraint forces) so far, their power */
    bk_interactions_accept(s, q, &(bk_path){.factor = 1.0, .x = 0.0});   /* the lagged states (friction) */
    dyn_output(out, s, &w, 0, 0.0, q, s->ncon ? w.r + s->nfree : NULL, 1);  /* initial multipliers */
    {
        double T = bk_dyn_kinetic(s, &w, fdof, q, 0.0);
        /* the powers of the initial state, with the initial multipliers (in w.r) */
        double rn, P0 = 0.0, Pd0 = 0.0;
        if (w.nc)
            memcpy(w.nu, w.r + s->nfree, (size_t)w.nc * sizeof *q);
        if (bk_dyn_residual(s, &w, fdof, q, 0.0, 0.0, 0.0, 0, &rn) == 0)
            P0 = bk_dyn_dot_free(s, fdof, w.fext, w.qd) - w.p_inter - w.p_con, Pd0 = w.p_damp, pcon_last = -w.p_con;
        if (w.nc)
            memset(w.nu, 0, (size_t)w.nc * sizeof *q);
        const double vs = m->length_scale / o->t_end;
        bk_energy_start(&eb, T, 0.0, P0, Pd0, 0.5 * mbar * s->nfree * vs * vs);
        bk_energy_row(&eb, out, energy, 0, 0.0, T, 0.0, 0.0, 0.0, bk_constraint_residual(s, q, 0.0));
        e_start = T, e_scale = fabs(T);
        info->max_constraint_residual = bk_constraint_residual(s, q, 0.0);
    }

    while (t < o->t_end * (1.0 - 1e-12)) {
        if (o->t_end - (t + h) < 1e-6 * h)      /* land on t_end, no sliver step */
            h = o->t_end - t;
        double tn = t + h;
        const double bp = (1.0 - am) / (bet * h * h * (1.0 - af)), gp = gam / (bet * h);
        s->cscale = bp * mbar;
        memcpy(w.q_s, q, (size_t)nd * sizeof *q);
        memcpy(w.qd_s, w.qd, (size_t)nd * sizeof *q);
        memcpy(w.qdd_s, w.qdd, (size_t)nd * sizeof *q);
        memcpy(w.a_s, w.a, (size_t)nd * sizeof *q);
        memcpy(w.nu_s, w.nu, (size_t)(w.nc ? w.nc : 1) * sizeof *q);
        const int pred_position = retry_position || pred_hold > 0 || (bathe && bk_interactions_cut_predictors(s));
        dyn_problem dp = {.s = s, .w = &w, .fdof = fdof, .norms = &nl.norms, .q = q, .tn = tn, .bp = bp, .gp = gp};
        bk_nl_result res;
        int st;
        if (bathe) {
            mid.cscale_last = cscale_acc;
            st = bk_dyn_bathe_step(&dp, &nl, &nlo, t, h, mbar, full_retry, pred_position, &mid, &res);
        } else {
            bk_dyn_predict(s, &w, q, h, am, af, bet, gam, pred_position);
            if (bk_interactions_cut_predictors(s) && !pred_position &&
                bk_dyn_limit_predictor(&dp, nl.dx, am, af, bet, gam, h) != 0) {
                snprintf(info->message, sizeof info->message, "out of memory");
                goto done;
            }
            bk_nl_problem prob = {.ctx = &dp, .q = q, .residual = bk_dyn_problem_residual,
                                  .update = bk_dyn_problem_update, .step_limit = bk_dyn_problem_step_limit};
            st = bk_nl_solve(&nl, &prob, &nlo, h, full_retry, NULL, &res);
        }
        int it = res.iters, signo = st == BK_NL_INTERRUPTED ? res.signo : 0, step_reused = res.reused;
        double rnorm = res.rnorm, dnorm = res.dnorm;
        info->newton_iterations += it;
        if (signo) {
            memcpy(q, w.q_s, (size_t)nd * sizeof *q);
            info->interrupted = signo;
            snprintf(info->message, sizeof info->message,
                     "interrupted by %s during step %d at t = %.6g s; the %d accepted steps (last t = %.6g s) "
                     "are kept", bk_interrupt_name(signo), step + 1, tn, step, t);
            goto done;
        }
        double err = 0.0;
        /* a step is accepted only at an admissible state (finite, no element
         * inverted): else it is retried and cut back like a failed one */
        if (st == DYN_OK && !bk_checks_admissible(&chk, s, q, inadm, sizeof inadm))
            st = DYN_INADMISSIBLE;
        bk_energy eb_trial;
        double pcon_trial = pcon_last, U_trial = NAN, T_trial = NAN;
        if (st == DYN_OK) {     /* the energy balance over the step, at the converged state's powers */
            const double P = bk_dyn_dot_free(s, fdof, w.fext, bk_dyn_power_velocity(s, &w, q, tn)) - w.p_inter
                             - w.p_con, Pd = w.p_damp;
            pcon_trial = -w.p_con;
            const double T = T_trial = bk_dyn_kinetic(s, &w, fdof, q, tn);
            bk_energy eb_from = eb;
            if (bathe)      /* the balance over the two sub-steps */
                bk_energy_step(&eb_from, mid.t, mid.t - t, mid.T, mid.U - U0, mid.P, mid.Pd);
            U_trial = bk_strain_energy(s, q) - U0;
            double created = bk_energy_trial(&eb_from, tn, bathe ? tn - mid.t : h, T, U_trial, P, Pd, &eb_trial);
            if (created > BK_ENERGY_CREATED) {
                st = DYN_ENERGY;
                snprintf(inadm, sizeof inadm, "the integrator created %.3g J (%.3g %% of the largest energy, %.3g J; "
                         "work of loads and prescribed motions and damping counted): a weakly damped high mode grows "
                         "(try a smaller dt, or dynamic.integrator = \"bathe\", which damps the unresolved modes)",
                         eb_trial.Dnum_max - eb_trial.Dnum, 100.0 * created,
                         eb_trial.scale);
            } else if (created > BK_ENERGY_CREATED_WARN && !e_warned_num) {
                e_warned_num = 1;
                bk_warn(info, out->console, m->name, "the integrator created %.3g J by t = %.6g s (%.3g %% of the "
                        "largest energy): a weakly damped high mode may be growing; results after it are suspect "
                        "(try a smaller dt, or dynamic.integrator = \"bathe\", which damps the unresolved modes)",
                        eb_trial.Dnum_max - eb_trial.Dnum, tn, 100.0 * created);
            }
        }
        if (st == DYN_OK) {
            /* the local error estimate: generalized-alpha's h^2 |beta - 1/6| |a_{n+1} - a_n|; for
             * Bathe's scheme (a = q'') that of its trapezoidal part, h^2/12 |q''_{n+1} - q''_n| */
            for (int i = 0; i < nd; ++i) {
                double an = bathe ? w.qdd[i] : ((1.0 - af) * w.qdd[i] + af * w.qdd_s[i] - am * w.a_s[i]) / (1.0 - am);
                err = fmax(err, fabs(an - w.a_s[i]));
                w.a[i] = an;
            }
            err *= h * h * (bathe ? 1.0 / 12.0 : fabs(bet - 1.0 / 6.0)) / m->length_scale;
        }
        int reject = st != DYN_OK || (o->tol > 0.0 && err > o->tol && h > o->dt_min * 1.0000001);
        if (reject) {
            memcpy(q, w.q_s, (size_t)nd * sizeof *q);
            memcpy(w.qd, w.qd_s, (size_t)nd * sizeof *q);
            memcpy(w.qdd, w.qdd_s, (size_t)nd * sizeof *q);
            memcpy(w.a, w.a_s, (size_t)nd * sizeof *q);
            memcpy(w.nu, w.nu_s, (size_t)(w.nc ? w.nc : 1) * sizeof *q);
            if (st != DYN_OK && st != DYN_SINGULAR && !pred_position) {
                /* first: the same step from the held position, with full Newton */
                retry_position = full_retry = 1;
                if (log)
                    fprintf(log, "  t = %.6g: step %.3g failed from the constant-acceleration predictor (%s), "
                            "retried from the held position\n", t, h, dyn_why(st));
                continue;
            }
            if (st != DYN_OK && step_reused && st != DYN_SINGULAR) {
                /* the fallback: the same step again with full Newton, before any halving */
                full_retry = 1;
                if (log)
                    fprintf(log, "  t = %.6g: step %.3g failed with kept factors (%s), retried with full Newton\n",
                            t, h, dyn_why(st));
                continue;
            }
            double hn = st != DYN_OK ? bk_step_ctl_failed(&ctl, h) : bk_step_ctl_error_reject(&ctl, h, err / o->tol);
            if (hn < o->dt_min || (st != DYN_OK && cuts >= o->max_cutbacks)) {
                char incr[64];
                char free_motion[400];
                if (st == DYN_SINGULAR && bk_null_motion(s, w.Ax, q, ls, free_motion, sizeof free_motion) == 0) {
                    snprintf(inadm, sizeof inadm, "singular iteration matrix; %s (held by nothing and without "
                             "mass? else the step is too large for the transient: try a smaller dt or a larger "
                             "rho_inf)", free_motion);
                    st = DYN_INADMISSIBLE;   /* the message names the free motion */
                }
                if (it > 0 && isfinite(dnorm))
                    snprintf(incr, sizeof incr, ", last increment %.3e", dnorm);
                else
                    incr[0] = 0;
                snprintf(info->message, sizeof info->message,
                         "dynamic solve failed at step %d, time %.6g s (step %.3g s): %s; residual %.3e%s after "
                         "%d iteration%s, %d cut-back%s in a row%s",
                         step + 1, tn, h, st == DYN_INADMISSIBLE || st == DYN_ENERGY ? inadm : st != DYN_OK ? dyn_why(st)
                         : "local error above tol at the smallest step",
                         rnorm, incr, it, it == 1 ? "" : "s", cuts, cuts == 1 ? "" : "s",
                         hn < o->dt_min ? " (the next step would be below dynamic.dt_min)" : "");
                goto done;
            }
            if (st != DYN_OK)
                info->cutbacks++, cuts++;
            if (log)
                fprintf(log, "  t = %.6g: step %.3g rejected (%s), retry with %.3g\n", t, h,
                        st != DYN_OK ? dyn_why(st) : "local error", hn);
            h = hn;
            continue;
        }
        cuts = 0;
        full_retry = 0;
        cscale_acc = s->cscale;
        if (retry_position)
            pred_hold = hold_len, hold_len = hold_len < 64 ? 2 * hold_len : 64;
        else if (pred_position)
            pred_hold--;
        else
            hold_len = 4;
        retry_position = 0;
        /* Quaternions back to unit length, their velocities without the gauge
         * component, their accelerations with that of a unit quaternion: the
         * rotations and angular velocities are unchanged,
         * and the massless gauge direction cannot drift over long runs. */
        {
            double *acc[2] = {w.qdd, w.a};
            bk_quat_normalize_motion(quat, nquat, q, w.qd, acc, 2);
        }
        eb = eb_trial;
        w_con += 0.5 * (tn - t) * (pcon_last + pcon_trial);
        pcon_last = pcon_trial;
        t = tn;
        step++;
        info->steps = step;
        info->load_factor = t;
        double cr = bk_constraint_residual(s, q, bk_frame_ctime(w.frame, t));
        info->max_constraint_residual = fmax(info->max_constraint_residual, cr);
        if (step % o->output_every == 0 || t >= o->t_end * (1.0 - 1e-12)) {
            dyn_output(out, s, &w, step, t, q, w.nu, 1);
            bk_checks_state(&chk, s, q, "t =", t, info, out->console);
            written = step;
            /* the accepted state's energies, computed for the step's energy balance
             * (again only where quaternions were renormalized since) */
            double T = nquat == 0 ? T_trial : bk_dyn_kinetic(s, &w, fdof, q, t);
            double U = nquat == 0 ? U_trial : bk_strain_energy(s, q) - U0;
            double Vg = 0.0, Vf = 0.0;
            for (int i = 0; i < nd; ++i) {
                Vg -= w.fgrav[i] * (q[i] - m->q0[i]);
                Vf -= (w.fext[i] - w.fgrav[i]) * (q[i] - m->q0[i]);
            }
            bk_interactions_potentials(s, q, t, &Vg, &Vf);
            bk_energy_row(&eb, out, energy, step, t, T, U, Vg, Vf, cr);
            /* contact with a step too long for its barrier can create energy (the
             * barrier's own energy is not in the total: a bounce gains) */
            e_scale = fmax(e_scale, fmax(fmax(fabs(T), fabs(U)), fmax(fabs(Vg), fabs(Vf))));
            double e_floor = 0.0;       /* round-off: a body at rest on the ground, every part ~1e-16 J */
            for (int i = 0; i < nd; ++i)
                e_floor += 1e-12 * fabs(w.fgrav[i]) * m->length_scale;
            /* less the work the prescribed motions did (a gripper's lifted bases) */
            const double grown = T + U + Vg + Vf - e_start - w_con;
            e_scale = fmax(e_scale, fabs(w_con));
            if (bk_interactions_uncounted_energy(s) && !e_warned && grown > 0.01 * e_scale && grown > e_floor) {
                e_warned = 1;
                bk_warn(info, out->console, m->name, "the total energy grew by %.3g J (%.3g %% of the largest of "
                        "its parts; the work of prescribed motions taken off) by t = %.6g s: contact at this step "
                        "size creates energy; use a shorter dt or rho_inf = 0", grown, 100.0 * grown / e_scale, t);
            }
        }
        bk_interactions_accept(s, q, &(bk_path){.factor = 1.0, .x = t});   /* after the step's outputs */
        if (log)
            fprintf(log, "  step %d: t = %.6g, h = %.3g, %d iterations, residual %.3e\n", step, t, h, it, rnorm);
        bk_output_progress(out, t / o->t_end, step, t, h, it, rnorm);
        h = bk_step_ctl_accepted(&ctl, h, it, o->tol > 0.0 ? fmax(err / o->tol, 1e-12) : 0.0);
    }
    rc = 0;
done:
    if (energy) {
        char etext[512];
        bk_energy_summary(&eb, etext, sizeof etext);
        if (bk_run_summary(info, "energy", etext) != 0 && rc == 0) {
            snprintf(info->message, sizeof info->message, "out of memory");
            rc = 1;
        }
    }
    /* a failed or interrupted run keeps its last accepted step even when the
     * output stride skipped it */
    if (rc != 0 && step > written)
        dyn_output(out, s, &w, step, t, q, NULL, 0);
    if (w.frame) {                  /* the caller's q in the inertial frame (its summary, final state) */
        bk_frame_at(w.frame, t);
        bk_frame_inertial(w.frame, s, q, w.qd, w.qdd, NULL);
        memcpy(q, frame.qa, (size_t)nd * sizeof *q);
    }
    info->converged = rc == 0;
    info->factorizations = nl.ls.nfactor;
    info->analyses = nl.ls.nanalyze;
    if (have_nl)
        bk_nl_free(&nl);
    bk_checks_free(&chk);
    bk_frame_free(&frame);
    free(fdof);
    free(quat);
    bk_dyn_work_free(&w);
    return rc;
}

static int runs_dynamic(const bk_model *m)
{
    return m->analysis == BK_ANALYSIS_DYNAMIC;
}

/* Time runs to t_end in steps of dt, a state output every output_every: the
 * frames are known; sections.csv without frames at the stride of 50 frames
 * (gen/options_schema.py DYNAMIC_FRAMES). */
static void plan_dynamic(const bk_model *m, bk_output_plan *p)
{
    const double states = m->dyn.t_end / (m->dyn.dt * m->dyn.output_every);
    p->frames = (int)fmin(1e9, states / (m->output.vtk_every > 0 ? m->output.vtk_every : 1)) + 1;
    p->room = p->frames + 3;
    p->states = (int)fmin(1e9, states) + 1;
    p->end = m->dyn.t_end > 0.0 ? m->dyn.t_end : 0.0;
    p->sections_every = (int)fmax(1.0, ceil(states / 50.0));
}

const bk_analysis_module bk_analysis_dynamic = {"dynamic", runs_dynamic, bk_solve_dynamic, plan_dynamic};
