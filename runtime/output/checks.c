/* checks.c -- plausibility of converged states (see checks.h). */
#include "output/checks.h"

#include <math.h>
#include <stdlib.h>

#define TWO_PI_3 2.0943951023931954923

int bk_checks_init(bk_checks *c, const bk_system *s)
{
    const bk_model *m = s->m;
    int nqp = 1;
    for (int k = 0; k < m->npair; ++k)
        if (m->pairs[k]->invariants && m->pairs[k]->nqp > nqp)
            nqp = m->pairs[k]->nqp;
    c->inv = malloc((size_t)(3 * nqp) * sizeof *c->inv);
    c->qe = malloc((size_t)(s->maxdof > 0 ? s->maxdof : 1) * sizeof *c->qe);
    c->inverted = c->volume = c->strain = c->far = 0;
    const int ov = bk_overlap_init(&c->overlap, s);
    if (!c->inv || !c->qe || ov != 0) {
        bk_checks_free(c);
        return -1;
    }
    return 0;
}

void bk_checks_free(bk_checks *c)
{
    free(c->inv);
    free(c->qe);
    c->inv = c->qe = NULL;
    bk_overlap_free(&c->overlap);
}

void bk_principal_from_invariants(double I1, double I2, double I3, double *x)
{
    /* roots of x^3 - I1 x^2 + I2 x - I3 = 0, all real: with x = y + I1/3,
     * y^3 + a y + b = 0 and the trigonometric solution */
    double s = I1 / 3.0;
    double a = I2 - I1 * I1 / 3.0;
    double b = -2.0 * I1 * I1 * I1 / 27.0 + I1 * I2 / 3.0 - I3;
    if (!(a < 0.0)) {
        x[0] = x[1] = x[2] = s;
        return;
    }
    double r = 2.0 * sqrt(-a / 3.0);
    double arg = 3.0 * b / (a * r);
    arg = arg > 1.0 ? 1.0 : arg < -1.0 ? -1.0 : arg;
    double th = acos(arg) / 3.0;
    double y0 = r * cos(th), y1 = r * cos(th - TWO_PI_3), y2 = r * cos(th - 2.0 * TWO_PI_3);
    double lo = fmin(y0, fmin(y1, y2)), hi = fmax(y0, fmax(y1, y2));
    x[0] = s + lo;
    x[2] = s + hi;
    x[1] = s + (y0 + y1 + y2 - lo - hi);
}

/* The largest displacement of a node (position fields) against the model's size. */
static void far_check(bk_checks *c, const bk_system *s, const double *q, const char *what, double t,
                      bk_run_info *info, FILE *console)
{
    const bk_model *m = s->m;
    double umax = 0.0;
    int ebig = -1;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = bk_elem_type(m, e);
        const int *d = m->elems[e].dofs;
        for (int f = 0; f < et->nfield; ++f) {
            if (et->field_role[f] != BK_FIELD_POSITION)
                continue;
            const int k0 = et->field_dof[f];
            double u2 = 0.0;
            for (int k = 0; k < 3; ++k)
                u2 += (q[d[k0 + k]] - m->q0[d[k0 + k]]) * (q[d[k0 + k]] - m->q0[d[k0 + k]]);
            if (u2 > umax * umax)
                umax = sqrt(u2), ebig = e;
        }
    }
    if (ebig < 0 || !(umax > BK_FAR_FACTOR * m->length_scale))
        return;
    c->far = 1;
    double pos[3] = {NAN, NAN, NAN};
    bk_eval_point(m, q, ebig, 0.5, pos, NULL);
    bk_warn(info, console, m->name,
            "element %d has moved %.3g m, %.0f times the model's size (%.3g m), by %s %.6g (now near (%.4g, %.4g, "
            "%.4g) m): not credible; check the units (lengths in m, E in Pa, loads in N) and whether the load is "
            "far beyond what the structure carries", ebig + 1, umax, umax / m->length_scale, m->length_scale, what,
            t, pos[0], pos[1], pos[2]);
}

void bk_checks_state(bk_checks *c, const bk_system *s, const double *q, const char *what, double t,
                     bk_run_info *info, FILE *console)
{
    const bk_model *m = s->m;
    if (!c->far)
        far_check(c, s, q, what, t, info, console);
    bk_overlap_check(&c->overlap, m, q, what, t, info, console);
    if (c->inverted && c->volume && c->strain)
        return;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        if (!p->invariants)
            continue;
        bk_gather(m, e, q, c->qe);
        p->invariants(c->qe, m->tabs[el->geom], c->inv);
        const int ranged = !c->strain && (p->green_strain_min != 0.0 || p->green_strain_max != 0.0);
        double jmin = INFINITY, jmax = -INFINITY, emin = INFINITY, emax = -INFINITY;
        for (int k = 0; k < p->nqp; ++k) {
            const double *v = c->inv + 3 * k;
            jmin = fmin(jmin, v[0]);
            jmax = fmax(jmax, v[0]);
            if (!ranged)
                continue;
            /* the eigenvalues of C lie within I1/3 -+ 2 sqrt(-(I2 - I1^2/3)/3) (the
             * trigonometric form of the roots): only when that interval leaves the
             * law's range are they computed */
            double s3 = v[1] / 3.0, a = v[2] - v[1] * v[1] / 3.0, r = a < 0.0 ? 2.0 * sqrt(-a / 3.0) : 0.0;
            double x[3] = {s3 - r, s3, s3 + r};
            if (0.5 * (x[0] - 1.0) < p->green_strain_min || 0.5 * (x[2] - 1.0) > p->green_strain_max)
                bk_principal_from_invariants(v[1], v[2], v[0] * v[0], x);
            emin = fmin(emin, 0.5 * (x[0] - 1.0));
            emax = fmax(emax, 0.5 * (x[2] - 1.0));
        }
        double pos[3] = {NAN, NAN, NAN};
        if ((!c->inverted && jmin <= 0.0) || (!c->volume && ((jmin > 0.0 && jmin < BK_J_MIN) || jmax > BK_J_MAX)) ||
            (ranged && (emin < p->green_strain_min || emax > p->green_strain_max)))
            bk_eval_point(m, q, e, 0.5, pos, NULL);       /* where, for a warning */
        if (!c->inverted && jmin <= 0.0) {
            c->inverted = 1;
            bk_warn(info, console, m->name,
                    "element %d (%s x %s) near (%.4g, %.4g, %.4g) m is inverted at %s %.6g: J = det F = %.3g <= 0 "
                    "at a quadrature point (the beam is turned inside out): the result is not physical",
                    e + 1, p->element->name, p->material, pos[0], pos[1], pos[2], what, t, jmin);
        } else if (!c->volume && ((jmin > 0.0 && jmin < BK_J_MIN) || jmax > BK_J_MAX)) {
            c->volume = 1;
            double jv = jmin < BK_J_MIN ? jmin : jmax;
            bk_warn(info, console, m->name,
                    "element %d (%s x %s) near (%.4g, %.4g, %.4g) m: volume ratio J = %.3g outside [%g, %g] at "
                    "%s %.6g: a deformation this large is unlikely to be meant",
                    e + 1, p->element->name, p->material, pos[0], pos[1], pos[2], jv, BK_J_MIN, BK_J_MAX, what, t);
        }
        if (ranged && (emin < p->green_strain_min || emax > p->green_strain_max)) {
            c->strain = 1;
            double ev = emax > p->green_strain_max ? emax : emin;
            bk_warn(info, console, m->name,
                    "element %d (%s x %s) near (%.4g, %.4g, %.4g) m: principal Green strain %.3g at %s %.6g is "
                    "outside [%g, %g], the range law %s is meant for: use a hyperelastic law for large strains",
                    e + 1, p->element->name, p->material, pos[0], pos[1], pos[2], ev, what, t,
                    p->green_strain_min, p->green_strain_max, p->material);
        }
        if (c->inverted && c->volume && c->strain)
            return;
    }
}

int bk_checks_admissible(bk_checks *c, const bk_system *s, const double *q, char *why, size_t n)
{
    const bk_model *m = s->m;
    for (int i = 0; i < m->ndof; ++i)
        if (!isfinite(q[i])) {
            snprintf(why, n, "coordinate %d is not finite", i);
            return 0;
        }
    int worst = -1;
    double jworst = INFINITY;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        if (!p->invariants)
            continue;
        bk_gather(m, e, q, c->qe);
        p->invariants(c->qe, m->tabs[el->geom], c->inv);
        for (int k = 0; k < p->nqp; ++k)
            if (!(c->inv[3 * k] > 0.0) && !(c->inv[3 * k] >= jworst)) {
                jworst = c->inv[3 * k];
                worst = e;
            }
    }
    if (worst < 0)
        return 1;
    const bk_pair *p = m->pairs[m->elems[worst].pair];
    double pos[3] = {NAN, NAN, NAN};
    bk_eval_point(m, q, worst, 0.5, pos, NULL);
    snprintf(why, n, "element %d (%s x %s) near (%.4g, %.4g, %.4g) m turned inside out: J = det F = %.3g <= 0 "
             "at a quadrature point", worst + 1, p->element->name, p->material, pos[0], pos[1], pos[2], jworst);
    return 0;
}
