/* contact_check.c -- the generated contact kernels (out/kernels/contact.c)
 * against central differences of themselves (gap -> gradient -> Hessian,
 * barrier and friction profile -> their derivatives) and against closed forms
 * written here independently (distances to a plane, a sphere, a line); prints
 * the largest relative errors, tests/test_contact_kernels.py asserts them. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact.h"

typedef void (*gap_fn)(const double *, const double *, double *);

static unsigned long long rng = 0x9E3779B97F4A7C15ULL;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* largest relative error of gradient and Hessian against central differences */
static void fd_gap(gap_fn f, const double *x, const double *prm, int nout, double *egrad, double *ehess)
{
    double o[16], op[16], om[16], h = 1e-6;
    f(x, prm, o);
    (void)nout;
    for (int j = 0; j < 3; ++j) {
        double xp[3], xm[3];
        memcpy(xp, x, sizeof xp);
        memcpy(xm, x, sizeof xm);
        xp[j] += h;
        xm[j] -= h;
        f(xp, prm, op);
        f(xm, prm, om);
        double d = (op[0] - om[0]) / (2 * h);
        *egrad = fmax(*egrad, fabs(d - o[1 + j]) / fmax(1.0, fabs(o[1 + j])));
        for (int i = 0; i < 3; ++i) {
            double dd = (op[1 + i] - om[1 + i]) / (2 * h);
            *ehess = fmax(*ehess, fabs(dd - o[4 + 3 * i + j]) / fmax(1.0, fabs(o[4 + 3 * i + j])));
        }
    }
}

int main(void)
{
    double eg = 0, eh = 0, eclosed = 0, esym = 0;
    for (int trial = 0; trial < 200; ++trial) {
        double x[3] = {2 * urand() - 1, 2 * urand() - 1, 2 * urand() - 1}, o[16];
        /* half-space */
        double n[3] = {urand() - 0.5, urand() - 0.5, urand() - 0.5};
        double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double ph[4] = {n[0] / nn, n[1] / nn, n[2] / nn, urand() - 0.5};
        fd_gap(bk_contact_gap_half_space, x, ph, 13, &eg, &eh);
        bk_contact_gap_half_space(x, ph, o);
        eclosed = fmax(eclosed, fabs(o[0] - (ph[0] * x[0] + ph[1] * x[1] + ph[2] * x[2] - ph[3])));
        /* sphere */
        double ps[4] = {urand() - 0.5, urand() - 0.5, urand() - 0.5, 0.1 + urand()};
        fd_gap(bk_contact_gap_sphere, x, ps, 13, &eg, &eh);
        bk_contact_gap_sphere(x, ps, o);
        double r[3] = {x[0] - ps[0], x[1] - ps[1], x[2] - ps[2]};
        eclosed = fmax(eclosed, fabs(o[0] - (sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) - ps[3])));
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                esym = fmax(esym, fabs(o[4 + 3 * i + j] - o[4 + 3 * j + i]));
        /* segment: distance to the line by the cross product, and t */
        double pg[7] = {urand() - 0.5, urand() - 0.5, urand() - 0.5, urand() + 0.5, urand() - 0.5, urand() - 0.5,
                        0.05 + 0.1 * urand()};
        fd_gap(bk_contact_gap_segment, x, pg, 14, &eg, &eh);
        bk_contact_gap_segment(x, pg, o);
        double e[3] = {pg[3] - pg[0], pg[4] - pg[1], pg[5] - pg[2]}, w[3] = {x[0] - pg[0], x[1] - pg[1], x[2] - pg[2]};
        double c[3] = {w[1] * e[2] - w[2] * e[1], w[2] * e[0] - w[0] * e[2], w[0] * e[1] - w[1] * e[0]};
        double ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
        double dist = sqrt((c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / ee);
        eclosed = fmax(eclosed, fabs(o[0] - (dist - pg[6])));
        eclosed = fmax(eclosed, fabs(o[13] - (w[0] * e[0] + w[1] * e[1] + w[2] * e[2]) / ee));
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                esym = fmax(esym, fabs(o[4 + 3 * i + j] - o[4 + 3 * j + i]));
    }
    /* barrier: derivatives by central differences, C2 at shat, growth at 0 */
    double eb = 0, shat = 1e-3;
    for (int k = 1; k < 100; ++k) {
        double s = shat * k / 100.0, h = 1e-9 * shat, b[3], bp[3], bm[3];
        bk_contact_barrier(s, shat, b);
        bk_contact_barrier(s + h, shat, bp);
        bk_contact_barrier(s - h, shat, bm);
        eb = fmax(eb, fabs((bp[0] - bm[0]) / (2 * h) - b[1]) / fmax(1e-12, fabs(b[1])));
        eb = fmax(eb, fabs((bp[1] - bm[1]) / (2 * h) - b[2]) / fmax(1e-12, fabs(b[2])));
    }
    double bl[3], bz[3];
    bk_contact_barrier(shat * (1 - 1e-9), shat, bl);
    bk_contact_barrier(1e-12 * shat, shat, bz);
    /* friction profile: derivatives, continuity at eps, f1/y regular at 0 */
    double ef = 0, eps = 1e-4;
    for (int k = 1; k < 100; ++k) {
        double y = eps * k / 100.0, h = 1e-7 * eps, f[4], fp[4], fm[4];
        bk_contact_friction(y, eps, f);
        bk_contact_friction(y + h, eps, fp);
        bk_contact_friction(y - h, eps, fm);
        ef = fmax(ef, fabs((fp[0] - fm[0]) / (2 * h) - f[1]) / fmax(1.0, fabs(f[1])));
        ef = fmax(ef, fabs((fp[2] - fm[2]) / (2 * h) - f[3]) / fmax(1.0, fabs(f[3])));
        ef = fmax(ef, fabs(f[2] - f[0] / y) / fabs(f[2]));
    }
    double fl[4], fr[4], f0[4];
    bk_contact_friction(eps * (1 - 1e-12), eps, fl);
    bk_contact_friction(eps, eps, fr);
    bk_contact_friction(0.0, eps, f0);
    /* static-to-kinetic step: h' against differences, h = 3 z^2 - 2 z^3 (closed form), C1 at eps and 2 eps */
    double et = 0;
    for (int k = 1; k < 300; ++k) {
        double y = 3.0 * eps * k / 300.0, h = 1e-7 * eps, s[2], sp[2], sm[2];
        bk_contact_transition(y, eps, s);
        bk_contact_transition(y + h, eps, sp);
        bk_contact_transition(y - h, eps, sm);
        const double z = fmin(fmax((y - eps) / eps, 0.0), 1.0);
        et = fmax(et, fabs((sp[0] - sm[0]) / (2 * h) - s[1]) * eps);
        et = fmax(et, fabs(s[0] - z * z * (3 - 2 * z)));
    }
    /* a body's frame: z = X + R0 R(p)^T (y - r): dz/dv and d2z/dv2 against differences, z = y at the reference */
    double eJ = 0, eT = 0, eref;
    {
        const double R0[9] = {0.36, 0.48, -0.8, -0.8, 0.6, 0.0, 0.48, 0.64, 0.6};   /* a rotation, row-major */
        double prm[12] = {0.3, -0.2, 0.5}, v[10] = {0.7, 0.1, -0.4, 0.25, -0.15, 0.45, 0.8, 0.3, -0.2, 0.5};
        double o[333], op[333], om[333], o0[333];
        memcpy(prm + 3, R0, sizeof R0);
        bk_contact_body_frame(v, v + 3, prm, o);
        for (int j = 0; j < 10; ++j) {
            double vp[10], vm[10], hh = 1e-6;
            memcpy(vp, v, sizeof v);
            memcpy(vm, v, sizeof v);
            vp[j] += hh;
            vm[j] -= hh;
            bk_contact_body_frame(vp, vp + 3, prm, op);
            bk_contact_body_frame(vm, vm + 3, prm, om);
            for (int k = 0; k < 3; ++k) {
                eJ = fmax(eJ, fabs((op[k] - om[k]) / (2 * hh) - o[3 + 10 * k + j]));
                for (int i = 0; i < 10; ++i)
                    eT = fmax(eT, fabs((op[3 + 10 * k + i] - om[3 + 10 * k + i]) / (2 * hh) -
                                       o[33 + 100 * k + 10 * i + j]));
            }
        }
        /* the reference: r = X, p the quaternion of R0 (trace form), any y: z = y */
        const double w = 0.5 * sqrt(1.0 + R0[0] + R0[4] + R0[8]);
        double ref[10] = {0.1, 0.9, -0.3, prm[0], prm[1], prm[2], w, (R0[7] - R0[5]) / (4 * w),
                          (R0[2] - R0[6]) / (4 * w), (R0[3] - R0[1]) / (4 * w)};
        bk_contact_body_frame(ref, ref + 3, prm, o0);
        eref = fabs(o0[0] - ref[0]) + fabs(o0[1] - ref[1]) + fabs(o0[2] - ref[2]);
    }
    /* a section's lever arm w = R(p) a (p not unit): dw/dp and sum f_i d2 w_i/dp2 against differences; w
     * against the rotation by the angle 2 atan2(|v|, s) about v/|v| (Rodrigues, written here) */
    double eLJ = 0, eLH = 0, eLc;
    {
        const double p[4] = {0.9, 0.3, -0.5, 0.4}, a[3] = {0.2, -0.7, 0.35}, f[3] = {1.3, -0.4, 2.1};
        double o[31], op[31], om[31];
        bk_contact_lever(p, a, f, o);
        for (int j = 0; j < 4; ++j) {
            double pp[4], pm[4], hh = 1e-6;
            memcpy(pp, p, sizeof p);
            memcpy(pm, p, sizeof p);
            pp[j] += hh;
            pm[j] -= hh;
            bk_contact_lever(pp, a, f, op);
            bk_contact_lever(pm, a, f, om);
            for (int i = 0; i < 3; ++i)
                eLJ = fmax(eLJ, fabs((op[i] - om[i]) / (2 * hh) - o[3 + 4 * i + j]));
            for (int k = 0; k < 4; ++k) {
                double gp = 0, gm = 0;
                for (int i = 0; i < 3; ++i)
                    gp += f[i] * op[3 + 4 * i + k], gm += f[i] * om[3 + 4 * i + k];
                eLH = fmax(eLH, fabs((gp - gm) / (2 * hh) - o[15 + 4 * k + j]));
            }
        }
        const double vn = sqrt(p[1] * p[1] + p[2] * p[2] + p[3] * p[3]), th = 2 * atan2(vn, p[0]);
        const double k[3] = {p[1] / vn, p[2] / vn, p[3] / vn}, kd = k[0] * a[0] + k[1] * a[1] + k[2] * a[2];
        const double kx[3] = {k[1] * a[2] - k[2] * a[1], k[2] * a[0] - k[0] * a[2], k[0] * a[1] - k[1] * a[0]};
        eLc = 0;
        for (int i = 0; i < 3; ++i)
            eLc = fmax(eLc, fabs(o[i] - (a[i] * cos(th) + kx[i] * sin(th) + k[i] * kd * (1 - cos(th)))));
    }
    double t1[2], t2[2];
    bk_contact_transition(eps * (1 + 1e-12), eps, t1);
    bk_contact_transition(2 * eps * (1 - 1e-12), eps, t2);
    printf("gap_grad_err=%.3e gap_hess_err=%.3e closed_err=%.3e hess_sym_err=%.3e barrier_err=%.3e "
           "barrier_at_shat=%.3e,%.3e,%.3e barrier_near_0=%.3e friction_err=%.3e friction_jump=%.3e,%.3e "
           "friction_f1y_at_0=%.17g transition_err=%.3e transition_ends=%.3e,%.3e body_J_err=%.3e body_T_err=%.3e "
           "body_ref_err=%.3e lever_J_err=%.3e lever_H_err=%.3e lever_closed_err=%.3e\n",
           eg, eh, eclosed, esym, eb, bl[0], bl[1], bl[2], bz[0], ef, fabs(fl[0] - fr[0]), fabs(fl[1] - fr[1]),
           f0[2] * eps, et, fabs(t1[0]) + fabs(t1[1]) * eps, fabs(t2[0] - 1) + fabs(t2[1]) * eps, eJ, eT, eref, eLJ, eLH,
           eLc);
    return 0;
}
