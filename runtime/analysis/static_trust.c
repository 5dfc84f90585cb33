/* static_trust.c -- the trust-region globalization of a static Newton solve
 * (static.globalization = "trust_region"; static_problem.h).
 *
 * Near-mechanisms -- slack cables, ropes, chains, EI/(EA L^2) far below 1e-8 --
 * defeat plain Newton at any load increment: the linearized step follows the
 * soft bending motion along straight lines, stretches the stiff axis by its
 * square, and the next residual is orders of magnitude larger.  With loads
 * that have a potential (dead forces and gravity) the total potential energy
 *     Pi(q) = U(q) - lam fext . q
 * is a merit function: each correction is solved with a Levenberg-Marquardt
 * shift of the tangent, (K + mu diag|K|) dx = -r on the free unknowns, and
 * taken when it lowers Pi.  The ratio rho of the actual to the predicted
 * decrease of Pi (the quadratic model along the step, pred = -a r.dx (1 - a/2),
 * which holds for the Newton step and bounds the shifted one) adapts mu: a
 * step that raises Pi (or is not a descent direction, where the shifted
 * tangent is still indefinite) is rejected and mu grown 8 times, a poor one
 * (rho < 1/4) accepted and mu grown 4 times, a good one (rho > 3/4) accepted
 * and mu shrunk 4 times, to 0 below MU_OFF: close to the solution it is
 * Newton's method with its quadratic rate.  When the predicted decrease is
 * below the energy's round-off (PI_ROUND_OFF of |Pi|) the step is taken as
 * Newton's: the residual test decides convergence there. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/static_problem.h"
#include "assembly/system.h"

#define MU_START 1e-4       /* the shift after the first rejected step */
#define MU_OFF 1e-8         /* below: no shift */
#define PI_ROUND_OFF 1e-9   /* relative resolution of the energy comparison */

int bk_static_trust_refusal(const bk_system *s, char *msg, size_t n)
{
    /* the potential below counts the elements' strain energy and the dead
     * loads' work: every interaction (loads with amplitudes, follower loads,
     * contact, ...) has forces outside it */
    if (bk_constraints_nonlinear(s) > 0) {
        snprintf(msg, n, "static.globalization = \"trust_region\" needs loads with a potential (dead forces and "
                 "gravity): the scene has joints nonlinear in the unknowns (their multipliers are not in the "
                 "energy)");
        return 1;
    }
    int k = 0;
    while (k < s->ninter && bk_interaction_depends(s, k) == 0)
        ++k;                         /* (one that adds no force: the loads of dead loads alone) */
    if (k == s->ninter)
        return 0;
    snprintf(msg, n, "static.globalization = \"trust_region\" needs loads with a potential (dead forces and "
             "gravity): the scene has the interaction \"%s\" (loads with amplitudes, follower, distributed and "
             "tendon loads, moments on sections, contact, springs, actuators: forces the energy does not count)",
             s->inter[k].ops->name);
    return 1;
}

/* Pi(q) = U(q) - lam fext . q */
static double potential(const bk_system *s, const work *w, const double *q, double lam)
{
    double pi = bk_strain_energy(s, q);
    for (int i = 0; i < s->m->ndof; ++i)
        pi -= lam * w->fext[i] * q[i];
    return pi;
}

void bk_static_trust_shift(const bk_system *s, double mu, double *Ax)
{
    if (!(mu > 0.0))
        return;
    for (int j = 0; j < s->nfree; ++j)
        for (int k = s->Ap[j]; k < s->Ap[j + 1]; ++k)
            if (s->Ai[k] == j) {
                Ax[k] += mu * fabs(Ax[k]);
                break;
            }
}

double bk_static_trust_step(static_problem *p, const double *dx, double a)
{
    const bk_system *s = p->s;
    work *w = p->w;
    double d0 = 0.0;
    for (int i = 0; i < s->nfree; ++i)
        d0 += w->r[i] * dx[i];
    const double pi0 = potential(s, w, p->q, p->lam);
    bk_static_step_to(s, w, p->q, w->nu, dx, a, w->qtrial, w->nutrial);
    const double pit = potential(s, w, w->qtrial, p->lam);
    const double pred = -a * d0 * (1.0 - 0.5 * a);
    if (fabs(pred) < PI_ROUND_OFF * fabs(pi0) && isfinite(pit)) {
        p->mu = p->mu < MU_OFF ? 0.0 : 0.25 * p->mu;
        return a;
    }
    if (!(d0 < 0.0) || !isfinite(pit) || !(pit < pi0)) {
        p->mu = p->mu > 0.0 ? 8.0 * p->mu : MU_START;
        return 0.0;                      /* rejected: the same state, a larger shift */
    }
    const double rho = (pi0 - pit) / pred;
    if (rho < 0.25)
        p->mu = p->mu > 0.0 ? 4.0 * p->mu : MU_START;
    else if (rho > 0.75)
        p->mu = p->mu < MU_OFF ? 0.0 : 0.25 * p->mu;
    return a;
}
