/* tendons.c -- a tendon piece's length, generalized force and tangent, on
 * continuum elements (the line through the shape functions) and on rods (the
 * generated section_line()). */
#include "assembly/tendons.h"

#include <math.h>

#include "assembly/system.h"

/* 5-point Gauss-Legendre rule on [-1, 1] */
static const double GX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                             0.9061798459386640};
static const double GW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                             0.2369268850561891};

/* The tendon's line p(xi) = sum_a Nt_a(xi) r_a at the offset (dy, dz) rides on
 * the affine part of each section -- its least-squares plane fit, as a guide
 * plate glued to the section would: Nt = mean over the section of N + dy <N y>/<y^2>
 * + dz <N z>/<z^2>.  The shape functions are at most quadratic across the section
 * and the section symmetric, so mean N = N(0) + (N_yy <y^2> + N_zz <z^2>) / 2 and
 * <N y>/<y^2> = N_y, the derivatives by central differences over the half widths
 * (exact for quadratics).  Its end forces T dp/dl act on the whole end section,
 * not on one material point of a section that can deform (ancf3363, ancf3273:
 * a point force pinched the finger's tip section to 40 % of its width); for the
 * sections that stay plane (ancf3243, ancf3333) Nt is N(xi, dy, dz). */
static void tendon_shape(const bk_element *et, const double *g, const bk_tendon_piece *tp, double xi, double *Nt)
{
    const int ns = et->nshape;
    const double hy = 0.5 * g[BK_GEOM_B], hz = 0.5 * g[BK_GEOM_H];
    const double yy = g[BK_GEOM_I2] / g[BK_GEOM_A], zz = g[BK_GEOM_I1] / g[BK_GEOM_A];
    double N0[BK_MAX_SHAPE], Nyp[BK_MAX_SHAPE], Nym[BK_MAX_SHAPE], Nzp[BK_MAX_SHAPE], Nzm[BK_MAX_SHAPE];
    et->shape(g, xi, 0.0, 0.0, N0);
    et->shape(g, xi, hy, 0.0, Nyp);
    et->shape(g, xi, -hy, 0.0, Nym);
    et->shape(g, xi, 0.0, hz, Nzp);
    et->shape(g, xi, 0.0, -hz, Nzm);
    for (int a = 0; a < ns; ++a) {
        double ny = (Nyp[a] - Nym[a]) / (2.0 * hy), nyy = (Nyp[a] - 2.0 * N0[a] + Nym[a]) / (hy * hy);
        double nz = (Nzp[a] - Nzm[a]) / (2.0 * hz), nzz = (Nzp[a] - 2.0 * N0[a] + Nzm[a]) / (hz * hz);
        Nt[a] = N0[a] + 0.5 * (nyy * yy + nzz * zz) + tp->dy * ny + tp->dz * nz;
    }
}

/* dNt/dxi at xi (five-point stencil, exact for the polynomial shape functions). */
static void tendon_slope(const bk_element *et, const double *g, const bk_tendon_piece *tp, double xi, double *Nx)
{
    static const double off[4] = {-2.0, -1.0, 1.0, 2.0}, cf[4] = {1.0, -8.0, 8.0, -1.0};
    const double hs = 1e-2;
    double Nt[BK_MAX_SHAPE];
    for (int a = 0; a < et->nshape; ++a)
        Nx[a] = 0.0;
    for (int k = 0; k < 4; ++k) {
        tendon_shape(et, g, tp, xi + off[k] * hs, Nt);
        for (int a = 0; a < et->nshape; ++a)
            Nx[a] += cf[k] * Nt[a] / (12.0 * hs);
    }
}

/* The line's tangent p_xi at xi: through the shape functions (Nx, when not
 * NULL, gets their slopes) or section_line(). */
static void tangent(const bk_element *et, const double *g, const bk_tendon_piece *tp, double xi, const double *qe,
                    double *Nx, double *px)
{
    if (!(et->caps & BK_CAP_SECTION_FIELD)) {
        const double a[2] = {tp->dy, tp->dz};
        et->section_line(g, xi, qe, a, NULL, px, NULL, NULL);
        return;
    }
    double Nl[BK_MAX_SHAPE];
    double *N = Nx ? Nx : Nl;
    tendon_slope(et, g, tp, xi, N);
    px[0] = px[1] = px[2] = 0.0;
    for (int a = 0; a < et->nshape; ++a)
        for (int k = 0; k < 3; ++k)
            px[k] += N[a] * qe[et->shape_dof[a] + k];
}

/* Rod piece at one point: Q -= wT dt^T u, K -= wT (dt^T (I - u u^T) dt / |t| + H(u)). */
static void rod_point(int nd, double wT, double len, const double *u, const double *dt, const double *H, double *Q,
                      double *K)
{
    for (int i = 0; i < nd; ++i)
        Q[i] -= wT * (u[0] * dt[i] + u[1] * dt[nd + i] + u[2] * dt[2 * nd + i]);
    if (!K)
        return;
    for (int i = 0; i < nd; ++i) {
        const double ui = u[0] * dt[i] + u[1] * dt[nd + i] + u[2] * dt[2 * nd + i];
        for (int j = 0; j < nd; ++j) {
            const double uj = u[0] * dt[j] + u[1] * dt[nd + j] + u[2] * dt[2 * nd + j];
            const double dd = dt[i] * dt[j] + dt[nd + i] * dt[nd + j] + dt[2 * nd + i] * dt[2 * nd + j];
            K[i * nd + j] -= wT * ((dd - ui * uj) / len + H[i * nd + j]);
        }
    }
}

/* Tendon piece: Q = -T dl/dq, K = dQ/dq = -T d2l/dq2, l = integral over the
 * piece of |p_xi|. */
void bk_tendon_piece_load(const bk_model *m, const bk_tendon_piece *tp, double T, const double *qe, double *dt,
                          double *H, double *Q, double *K)
{
    const bk_element *et = bk_elem_type(m, tp->elem);
    const double *g = m->geoms[m->elems[tp->elem].geom];
    const int ns = et->nshape, nd = et->ndof, rod = !(et->caps & BK_CAP_SECTION_FIELD);
    const double half = 0.5 * (tp->xi1 - tp->xi0);
    const double a[2] = {tp->dy, tp->dz};
    double Nx[BK_MAX_SHAPE];
    for (int p = 0; p < 5; ++p) {
        double xi = tp->xi0 + half * (1.0 + GX[p]), wt = GW[p] * half, px[3];
        if (rod)        /* the tangent with its Jacobian; with K, again for the Hessian along u */
            et->section_line(g, xi, qe, a, NULL, px, dt, NULL);
        else
            tangent(et, g, tp, xi, qe, Nx, px);
        double len = sqrt(px[0] * px[0] + px[1] * px[1] + px[2] * px[2]);
        if (!(len > 0.0))
            continue;
        double u[3] = {px[0] / len, px[1] / len, px[2] / len};
        if (rod) {
            if (K)
                et->section_line(g, xi, qe, a, u, px, dt, H);
            rod_point(nd, T * wt, len, u, dt, H, Q, K);
            continue;
        }
        for (int a = 0; a < ns; ++a)
            for (int k = 0; k < 3; ++k) {
                int row = et->shape_dof[a] + k;
                Q[row] -= T * wt * Nx[a] * u[k];
                if (K)
                    for (int b = 0; b < ns; ++b)
                        for (int l = 0; l < 3; ++l)
                            K[row * nd + et->shape_dof[b] + l] -=
                                T * wt * Nx[a] * Nx[b] * ((k == l ? 1.0 : 0.0) - u[k] * u[l]) / len;
            }
    }
}

double bk_tendon_piece_length(const bk_model *m, const bk_tendon_piece *tp, const double *qe)
{
    const bk_element *et = bk_elem_type(m, tp->elem);
    const double *g = m->geoms[m->elems[tp->elem].geom];
    const double half = 0.5 * (tp->xi1 - tp->xi0);
    double len = 0.0;
    for (int p = 0; p < 5; ++p) {
        double xi = tp->xi0 + half * (1.0 + GX[p]), px[3];
        tangent(et, g, tp, xi, qe, NULL, px);
        len += GW[p] * half * sqrt(px[0] * px[0] + px[1] * px[1] + px[2] * px[2]);
    }
    return len;
}
