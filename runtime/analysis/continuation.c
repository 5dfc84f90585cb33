/* continuation.c -- statics by arc-length continuation (static.method =
 * "arc_length"): the equilibrium path followed past limit points, critical
 * points refined and reported, optionally a branch switch at the first
 * bifurcation (method in continuation.h); the analysis module "continuation"
 * (analysis.h). */
#include "analysis/analysis.h"
#include "analysis/continuation.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/static.h"
#include "assembly/quaternion.h"
#include "base/interrupt.h"

static int arc_length(bk_system *s, bk_nl *nl, work *w, double *q, bk_output *out, bk_run_info *info, FILE *log,
                      bk_stability *stab, int have_stab, bk_checks *chk)
{
    const bk_model *m = s->m;
    const bk_static_opts *o = &m->stat;
    int nd = m->ndof, ne = s->neq, nc = s->ncon > 0 ? s->ncon : 1, rc = 1;
    candidate *cand = NULL;                          /* bifurcation candidates */
    int ncand = 0, cand_cap = 0;
    arc_ctx c = {.sp = {.s = s, .w = w, .q = q, .lscale = m->length_scale}, .w = w};
    double *W = calloc((size_t)ne, sizeof *W);
    int *fdof = calloc((size_t)(s->nfree > 0 ? s->nfree : 1), sizeof *fdof);
    c.rl = calloc((size_t)ne, sizeof *c.rl), c.t = calloc((size_t)ne, sizeof *c.t);
    c.tmp = calloc((size_t)ne, sizeof *c.tmp), c.fol = calloc((size_t)nd, sizeof *c.fol);
    arc_point A = {calloc((size_t)nd, sizeof(double)), calloc((size_t)nc, sizeof(double)), 0.0};
    arc_point B = {calloc((size_t)nd, sizeof(double)), calloc((size_t)nc, sizeof(double)), 0.0};
    arc_point best = {calloc((size_t)nd, sizeof(double)), calloc((size_t)nc, sizeof(double)), 0.0};
    double *tprim = calloc((size_t)ne, sizeof(double));
    arc_path path = {.ns = m->nsensor < BK_CRIT_SENSORS ? m->nsensor : BK_CRIT_SENSORS, .nd = nd};
    path.isq = calloc((size_t)nd, 1), path.quat = malloc((size_t)(nd / 4 + 1) * 4 * sizeof *path.quat);
    double pu[3 * BK_CRIT_SENSORS], pdu[3 * BK_CRIT_SENSORS];
    info->continuation = 1;
    if (!W || !fdof || !c.rl || !c.t || !c.tmp || !c.fol || !A.q || !A.nu || !B.q || !B.nu || !best.q ||
        !best.nu || !tprim || !path.isq || !path.quat) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    c.W = W, c.fdof = fdof;
    for (int i = 0; i < nd; ++i)
        if (s->eq[i] >= 0 && s->eq[i] < s->nfree)
            fdof[s->eq[i]] = i;
    {
        const double L2 = m->length_scale * m->length_scale;
        for (int e = 0; e < m->nelem; ++e) {
            const bk_elem *el = &m->elems[e];
            const bk_element *et = m->pairs[el->pair]->element;
            for (int f = 0; f < et->nfield; ++f) {
                bk_field_role role = et->field_role[f];
                double wt = role == BK_FIELD_POSITION ? 1.0
                            : bk_field_is_gradient(role) || role == BK_FIELD_QUATERNION ? L2 : 0.0;
                for (int i = 0; i < et->field_dim[f]; ++i) {
                    int eqn = s->eq[el->dofs[et->field_dof[f] + i]];
                    if (eqn >= 0 && eqn < s->nfree)
                        W[eqn] = wt;
                }
                const int *d = el->dofs + et->field_dof[f];
                if (role == BK_FIELD_QUATERNION && et->field_dim[f] == 4 && !path.isq[d[0]]) {
                    for (int i = 0; i < 4; ++i)
                        path.isq[d[i]] = 1, path.quat[4 * path.nquat + i] = d[i];
                    path.nquat++;
                }
            }
        }
    }
    if (bk_arc_path_push(&path, m, q, 0.0, 0.0) != 0) {
        snprintf(info->message, sizeof info->message, "out of memory");
        goto done;
    }
    double lam = 0.0, target = o->target_load_factor, dl = 0.0, dl0 = 0.0, sigma_prev = 1.0, dl_prev = 0.0;
    double prev_lam = 0.0;
    int have_dir = 0, calm = 2, claimed = -1;    /* claimed: the step of the last critical point */
    int switching = 0, switched = 0, after_switch = 0;   /* static.branch_switch: pending, done, last step */
    char inadm[320] = "";                /* why the last inadmissible state was refused */
    int switch_mult = 0;                                 /* eigenvalues crossing at the switched bifurcation */
    attempt a = {0};
    bk_stability_result sres;
    if (bk_norm2(w->fext, nd) == 0.0 && !bk_interactions_load_on_path(s) && s->ncon == 0) {
        snprintf(info->message, sizeof info->message,
                 "static.method = \"arc_length\": the scene has no load to scale (expected a force, moment or "
                 "gravity load)");
        goto done;
    }
    int assembled = 0;                  /* w->Ax: the matrix at (q, lam), made for the last step's stability check */
    for (;;) {
        double tWt;
        int st = bk_arc_tangent(s, nl, &c, q, lam, assembled, &tWt);
        assembled = 0;
        if (st != BK_NL_OK || !(tWt > 0.0)) {
            snprintf(info->message, sizeof info->message,
                     "arc-length: no tangent at the equilibrium of step %d, load factor %.6g (%s): the tangent "
                     "is singular there (a bifurcation point hit exactly, or a mechanism)", info->steps, lam,
                     st != BK_NL_OK ? bk_nl_why(st) : "the load moves nothing");
            goto done;
        }
        if (info->steps == 0) {
            c.psi2 = o->arc_constraint == BK_ARC_CONSTRAINT_SPHERICAL ? tWt : 0.0;
            dl = dl0 = target / o->load_steps * sqrt(tWt + c.psi2);
        }
        double sigma = have_dir ? bk_arc_orientation(s, &c, q, lam, A.q, A.lam) : 1.0;
        /* a limit point between the last two equilibria: the load factor turned */
        if (have_dir && sigma != sigma_prev && !after_switch) {
            bk_arc_save(s, w, q, lam, &B);
            int step = info->steps;
            double lc = bk_arc_bisect_limit(s, nl, &c, q, &A, sigma_prev, dl_prev, o, &a, step, info, &best, lam);
            bk_critical_point *cp = bk_run_insert_critical(info, info->ncritical);
            if (!cp) {
                snprintf(info->message, sizeof info->message, "out of memory");
                goto done;
            }
            cp->limit = 1;
            cp->step = step;
            cp->lam = lc;
            bk_sensor_displacements(m, isfinite(best.lam) ? best.q : B.q, cp);
            if (out->console) {
                fprintf(out->console, "%s: limit point at load factor %.6g (between steps %d and %d)", m->name, lc,
                        step - 1, step);
                if (cp->nsensor)
                    fprintf(out->console, ", sensor %s displacement [%.6g, %.6g, %.6g] m", m->sensors[0].name,
                            cp->u[0][0], cp->u[0][1], cp->u[0][2]);
                fprintf(out->console, "\n");
            }
            if (log)
                fprintf(log, "  limit point: load factor %.6g between steps %d and %d\n", lc, step - 1, step);
            /* a stability event of the same step is this limit point */
            if (info->nstability > 0 && info->stability[info->nstability - 1].step == step)
                info->stability[info->nstability - 1].lam_critical = lc;
            claimed = step;
            bk_arc_restore(s, w, q, &lam, &B);
            if ((st = bk_arc_tangent(s, nl, &c, q, lam, 0, &tWt)) != BK_NL_OK) {
                snprintf(info->message, sizeof info->message, "arc-length: no tangent at step %d (%s)", info->steps,
                         bk_nl_why(st));
                goto done;
            }
        }
        after_switch = 0;
        if (info->steps >= o->max_steps) {
            snprintf(info->message, sizeof info->message,
                     "arc-length: the load-factor target %.6g was not reached within static.max_steps = %d steps; "
                     "the path is kept up to step %d, load factor %.6g, largest sensor displacement %.6g m",
                     target, o->max_steps, info->steps, lam, bk_max_sensor_displacement(m, q));
            goto done;
        }
        /* the step: predictor along the oriented tangent, bordered Newton, cut-backs */
        bk_arc_save(s, w, q, lam, &A);
        int cuts = 0;
        for (;;) {
            double dls = dl;
            if (switching) {
                /* branch switch: the predictor along the null vector of the
                 * tangent past the bifurcation, the load factor kept; the
                 * sphere about the last equilibrium meets the secondary branch */
                memcpy(tprim, c.t, (size_t)ne * sizeof *tprim);
                bk_branch_direction(s, stab, &c, &tWt);
                dls = fmax(dl, 1e-2 * m->length_scale);
            }
            st = bk_arc_step(s, nl, &c, q, lam, switching ? 1.0 : sigma, tWt, dls, o, &a, info->steps + 1, info,
                          switching ? 0.0 : 1.0);
            /* a step is accepted only at an admissible state (no element inverted) */
            if (st == BK_NL_OK && !switching && !bk_checks_admissible(chk, s, q, inadm, sizeof inadm)) {
                double l0 = lam;
                bk_arc_restore(s, w, q, &l0, &A);
                st = NEWTON_INADMISSIBLE;
            }
            if (switching && st == BK_NL_OK) {
                /* on the secondary branch the step is across the primary tangent */
                double tt = 0.0, dd = 0.0, td = 0.0;
                for (int j = 0; j < s->nfree; ++j) {
                    double dj = q[fdof[j]] - A.q[fdof[j]];
                    tt += W[j] * tprim[j] * tprim[j], dd += W[j] * dj * dj, td += W[j] * tprim[j] * dj;
                }
                if (tt > 0.0 && dd > 0.0 && fabs(td) > 0.9 * sqrt(tt * dd))
                    bk_warn(info, out->console, m->name, "the branch switch at step %d (load factor %.6g) came back "
                            "to the primary branch (the eigenvector nearest zero is not the buckling mode?)",
                            info->steps, lam);
                dl = dls;
                if (out->console)
                    fprintf(out->console, "%s: branch switch at step %d (load factor %.6g) onto the secondary branch "
                            "along the null vector of the tangent\n", m->name, info->steps, lam);
            }
            if (switching && st != BK_NL_OK && st != BK_NL_INTERRUPTED) {
                if (switch_mult > 1)
                    bk_warn(info, out->console, m->name, "the branch switch at step %d (load factor %.6g) failed (%s): "
                            "the path goes on along the primary branch; the bifurcation is multiple (%d eigenvalues "
                            "crossed zero together, e.g. a section symmetric in both bending planes), so its "
                            "secondary branches form a family and the switch has no single branch to follow: break "
                            "the symmetry (e.g. a rectangle with b != h)", info->steps, lam, bk_nl_why(st),
                            switch_mult);
                else
                    bk_warn(info, out->console, m->name, "the branch switch at step %d (load factor %.6g) failed (%s): "
                            "the path goes on along the primary branch", info->steps, lam, bk_nl_why(st));
                switching = 0;
                if ((st = bk_arc_tangent(s, nl, &c, q, lam, 0, &tWt)) != BK_NL_OK) {
                    snprintf(info->message, sizeof info->message, "arc-length: no tangent at step %d (%s)",
                             info->steps, bk_nl_why(st));
                    goto done;
                }
                continue;
            }
            if (st == BK_NL_OK || st == BK_NL_INTERRUPTED)
                break;
            if (cuts >= o->max_cutbacks) {
                char what[600];
                if (st == NEWTON_INADMISSIBLE)
                    snprintf(what, sizeof what, "the equilibrium reached is not physical: %s", inadm);
                else
                    bk_static_diagnose(what, sizeof what, st, &a, info->steps, info->negative_eigenvalues);
                snprintf(info->message, sizeof info->message,
                         "arc-length failed at step %d from load factor %.6g (arc length %.3e): %s; residual %.3e "
                         "(tolerance %.3e) after %d iterations, %d cut-backs; the path is kept up to step %d",
                         info->steps + 1, lam, dl, what, a.rnorm, a.rtol_abs, a.iters, cuts, info->steps);
                goto done;
            }
            cuts++;
            info->cutbacks++;
            calm = 0;
            dl *= 0.5;
            if (log)
                fprintf(log, "  cut-back at load factor %.6g (%s): new arc length %.3g\n", lam, bk_static_why(st), dl);
            if ((st = bk_arc_tangent(s, nl, &c, q, lam, 0, &tWt)) != BK_NL_OK) {
                snprintf(info->message, sizeof info->message, "arc-length: no tangent at step %d (%s)",
                         info->steps, bk_nl_why(st));
                goto done;
            }
        }
        if (st == BK_NL_INTERRUPTED) {
            info->interrupted = a.signo;
            snprintf(info->message, sizeof info->message,
                     "interrupted by %s during step %d from load factor %.6g; the %d converged steps are kept",
                     bk_interrupt_name(a.signo), info->steps + 1, lam, info->steps);
            goto done;
        }
        if (switching) {
            switching = 0;
            switched = 1;
            after_switch = 1;           /* no limit point between the branches */
        }
        double lam_new = c.sp.lam;
        int reached = (lam - target) * (lam_new - target) <= 0.0 && lam_new > lam;
        if (reached && lam_new != target) {
            /* land on the target by load control from the arc point */
            bk_arc_save(s, w, q, lam_new, &B);
            memcpy(w->qsave, A.q, (size_t)nd * sizeof *q);
            a.id++;
            int lst = bk_static_newton(s, nl, w, q, target, lam, &a, o, m->length_scale, info->steps + 1, NULL);
            info->newton_iterations += a.iters;
            if (lst == NEWTON_OK)
                lam_new = target;
            else
                bk_arc_restore(s, w, q, &lam_new, &B);
        }
        dl_prev = dl;
        sigma_prev = sigma;
        have_dir = 1;
        lam = lam_new;
        info->steps++;
        info->load_factor = lam;
        bk_output_forces(out, s, info->steps, lam, q, NULL, NULL, w->nu);
        bk_output_step(out, info->steps, lam, q);
        bk_interactions_accept(s, q, &(bk_path){.factor = lam, .x = lam});
        bk_checks_state(chk, s, q, "load factor", lam, info, out->console);
        if (log)
            fprintf(log, "  step %d: load factor %.6g, arc length %.3g, %d iterations, residual %.3e\n", info->steps,
                    lam, dl, a.iters, a.rnorm);
        if (have_stab) {
            /* the matrix at this equilibrium, for the check and the next
             * step's tangent alike (the Lee frame assembled it twice): the
             * tangent's work, not the check's (stability_s) */
            assembled = bk_static_residual(s, w, q, w->nu, lam, 1) == 0;
            bk_static_probe_stability(stab, s, w, q, lam, assembled, &sres);
            bk_static_accept_stability(stab, &sres, lam, out, info, log, &prev_lam, 1, NAN, w->stability_csv);
        }
        /* a change of the negative-eigenvalue count in the last step without
         * a limit point: a bifurcation candidate (its load factor from the
         * bisection on the inertia of the interpolated tangent, sensors
         * interpolated); kept unless a limit point is within ARC_NEAR steps
         * (the count flickers while the smallest eigenvalue hovers about zero
         * on the flat top of a limit point); not the change of a branch switch */
        if (info->nstability > 0 && info->stability[info->nstability - 1].step == info->steps &&
            claimed != info->steps && !after_switch) {
            const bk_stability_event *ev = &info->stability[info->nstability - 1];
            if (ncand == cand_cap) {
                candidate *more = realloc(cand, (size_t)(cand_cap = cand_cap ? 2 * cand_cap : 8) * sizeof *cand);
                if (!more) {
                    snprintf(info->message, sizeof info->message, "out of memory");
                    goto done;
                }
                cand = more;
            }
            memset(&cand[ncand], 0, sizeof cand[ncand]);
            bk_critical_point *cp = &cand[ncand++].cp, ca, cb;
            double f = isfinite(ev->lam_critical) && lam != A.lam ? (ev->lam_critical - A.lam) / (lam - A.lam) : 1.0;
            bk_sensor_displacements(m, A.q, &ca);
            bk_sensor_displacements(m, q, &cb);
            cp->limit = 0;
            cp->step = info->steps;
            cp->lam = ev->lam_critical;
            cp->nsensor = cb.nsensor;
            for (int k = 0; k < cb.nsensor; ++k)
                for (int i = 0; i < 3; ++i)
                    cp->u[k][i] = ca.u[k][i] + f * (cb.u[k][i] - ca.u[k][i]);
            cand[ncand - 1].neg[0] = ev->neg_before, cand[ncand - 1].neg[1] = ev->neg_after;
            claimed = info->steps;
            if (o->branch_switch && !switched && ev->neg_after > ev->neg_before) {
                switching = 1;          /* the next step switches branch */
                switch_mult = ev->neg_after - ev->neg_before;
            }
        }
        bk_output_progress(out, fmin(fabs(lam / target), 1.0), info->steps, lam, dl, a.iters, a.rnorm);
        if (reached && !switching) {    /* (a pending branch switch goes on from the target) */
            rc = 0;
            goto done;
        }
        if (o->max_displacement > 0.0 && bk_max_sensor_displacement(m, q) >= o->max_displacement) {
            if (out->console)
                fprintf(out->console, "%s: arc-length stopped at the displacement limit %.6g m (step %d, load "
                        "factor %.6g)\n", m->name, o->max_displacement, info->steps, lam);
            rc = 0;
            goto done;
        }
        /* a closed loop: back at a visited point of the path (arc_path) */
        {
            bk_critical_point cp;
            bk_sensor_displacements(m, q, &cp);
            const double *ul = path.u + (size_t)(path.n - 1) * 3 * path.ns;
            for (int k = 0; k < 3 * path.ns; ++k)
                pu[k] = cp.u[k / 3][k % 3], pdu[k] = pu[k] - ul[k];
            int kb = -1;
            double db = INFINITY;
            for (int k = 0; k + 1 < path.n - 1; ++k) {
                double dist, len;
                if (k + 1 >= path.nq || !bk_arc_path_near(&path, k, pu, lam, pdu, lam - path.lam[path.n - 1]))
                    continue;
                bk_arc_path_distance(&path, s, &c, m->length_scale * m->length_scale, k, q, lam, &dist, &len);
                double tol = 0.25 * fmax(dl, len), went = path.arc[path.n - 1] + dl - path.arc[k + 1];
                if (dist < tol && went > 4.0 * tol && dist < db)
                    kb = k, db = dist;
            }
            if (kb >= 0) {
                int o2 = snprintf(info->message, sizeof info->message,
                                  "arc-length: a closed loop: at step %d (load factor %.6g) the path came back to "
                                  "where it was between steps %d and %d (load factor %.6g to %.6g",
                                  info->steps, lam, kb, kb + 1, path.lam[kb], path.lam[kb + 1]);
                if (path.ns > 0 && o2 > 0 && (size_t)o2 < sizeof info->message)
                    o2 += snprintf(info->message + o2, sizeof info->message - (size_t)o2,
                                   ", sensor %s displacement [%.6g, %.6g, %.6g] m", m->sensors[0].name, pu[0], pu[1],
                                   pu[2]);
                if (o2 > 0 && (size_t)o2 < sizeof info->message)
                    snprintf(info->message + o2, sizeof info->message - (size_t)o2,
                             "; distance %.3e, arc length %.3e); the target %.6g is not on this path", db, dl, target);
                goto done;
            }
            if (bk_arc_path_push(&path, m, q, lam, path.arc[path.n - 1] + dl) != 0) {
                snprintf(info->message, sizeof info->message, "out of memory");
                goto done;
            }
        }
        /* the next arc length from the iteration count */
        double f = sqrt((double)o->arc_iterations / (a.iters > 1 ? a.iters : 1));
        f = fmin(fmax(f, 0.5), 2.0);
        if (calm < 2) {
            f = fmin(f, 1.0);
            calm++;
        }
        dl = fmin(dl * f, fmax(8.0 * dl0, 0.05 * m->length_scale));
    }
done:
    /* the bifurcations: candidates away from every limit point, merged by
     * step; a change taken back within ARC_NEAR steps (0 -> 1 -> 0) is the
     * flicker of an eigenvalue about zero and no bifurcation */
    for (int k = 0; k + 1 < ncand; ++k)
        if (!cand[k].gone && cand[k].neg[0] == cand[k + 1].neg[1] && cand[k].neg[1] == cand[k + 1].neg[0] &&
            cand[k + 1].cp.step - cand[k].cp.step <= ARC_NEAR)
            cand[k].gone = cand[k + 1].gone = 1;
    for (int k = 0; k < ncand; ++k) {
        const bk_critical_point *ck = &cand[k].cp;
        int near = cand[k].gone;
        for (int j = 0; j < info->ncritical; ++j)
            near |= info->critical[j].limit && abs(info->critical[j].step - ck->step) <= ARC_NEAR;
        if (near)
            continue;
        int at = info->ncritical;
        while (at > 0 && info->critical[at - 1].step > ck->step)
            at--;
        bk_critical_point *slot = bk_run_insert_critical(info, at);
        if (!slot)
            break;
        *slot = *ck;
        if (out->console)
            fprintf(out->console, "%s: bifurcation at load factor %.6g (between steps %d and %d: negative tangent "
                    "eigenvalues %d -> %d)\n", m->name, ck->lam, ck->step - 1, ck->step, cand[k].neg[0],
                    cand[k].neg[1]);
    }
    free(cand);
    free(W), free(fdof), free(c.rl), free(c.t), free(c.tmp), free(c.fol), free(tprim);
    bk_arc_path_free(&path);
    free(A.q), free(A.nu), free(B.q), free(B.nu), free(best.q), free(best.nu);
    return rc;
}

int bk_solve_continuation(bk_system *s, double *q, bk_output *out, bk_run_info *info, FILE *log)
{
    static_run R;
    int rc = 1;
    if (bk_static_begin(&R, s, q, out, info, log, 0, 1) == 0)
        rc = arc_length(s, &R.nl, &R.w, q, out, info, log, &R.stab, R.have_stab, &R.chk);
    bk_static_end(&R, info, rc);
    return rc;
}

static int runs_continuation(const bk_model *m)
{
    return m->analysis == BK_ANALYSIS_STATIC && m->stat.method == BK_METHOD_ARC_LENGTH;
}

/* The path's end is not known (the arc length decides); room for the steps. */
static void plan_continuation(const bk_model *m, bk_output_plan *p)
{
    p->room = m->stat.load_steps * (1 + 2 * m->stat.cycles) + 4;
    p->stability = m->stat.stability;
}

const bk_analysis_module bk_analysis_continuation = {"continuation", runs_continuation, bk_solve_continuation,
                                                     plan_continuation};
