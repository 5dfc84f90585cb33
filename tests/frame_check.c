/* frame_check.c -- checks every generated element's section_frame() (the
 * section frame of follower loads and its Jacobian, runtime/bk_kernel.h)
 * against finite differences and against the frame built here from frame().
 * Linked with a table of the elements (frame_check_elements, written by
 * tests/test_follower_frame.py) and their generated files.
 *
 * Per element, at NSTATE random states (each a rigid motion of any size of the
 * reference element plus a perturbation, large or, every other state, small:
 * the small-angle branches of the rotation functions) and a random xi:
 *   fd       max_kj |dR_kj - dR_k/dq_j (4th-order central difference of R)| / max|dR|
 *   fd2      the same against the 2nd-order central difference with the step the
 *            runtime used before section_frame() had a Jacobian (1e-6 max(1, |q_j|))
 *   consist  max |R (with dR) - R (dR = NULL)|
 *   orth     max |R R^T - I|
 *   gs       max |R - G(d)|, G(d) the Gram-Schmidt frame of frame()'s d (e3 = d3/|d3|,
 *            e1 = d1 - (d1 . e3) e3 normalised, e2 = e3 x e1), written here
 * and, for an element with a section_line() (a line fixed in the sections at a
 * random offset a, P = pos + a1 e1 + a2 e2):
 *   line_xi  max |t - dP/dxi (4th-order central difference in xi of P from frame()
 *            and section_frame())| / max|t|
 *   line_fd  max |dt - dt/dq (4th-order central difference of t)| / max|dt|
 *   line_h   max |H - d(u . dt)/dq (4th-order central difference)| / max|H|, u random
 *   line_c   max |t, dt (with dt, H) - t, dt (without)|
 * Output: one line per element, "key=value" fields; "section_frame=none" for an
 * element without one, "section_line=none" for one without a section_line(). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bk_kernel.h"

extern const bk_element *const frame_check_elements[];
extern const int frame_check_nelements;

typedef struct rng {
    unsigned long long s;
} rng;

static double urand(rng *r) /* uniform in [-1, 1) */
{
    r->s ^= r->s << 13;
    r->s ^= r->s >> 7;
    r->s ^= r->s << 17;
    return 2.0 * ((double)(r->s >> 11) / 9007199254740992.0) - 1.0;
}

/* A random unit quaternion qr and its rotation matrix R (row-major). */
static void random_rotation(rng *r, double R[9], double qr[4])
{
    double n;
    do {
        n = 0.0;
        for (int i = 0; i < 4; ++i) {
            qr[i] = urand(r);
            n += qr[i] * qr[i];
        }
    } while (n > 1.0 || n < 1e-3);
    n = sqrt(n);
    for (int i = 0; i < 4; ++i)
        qr[i] /= n;
    double w = qr[0], x = qr[1], y = qr[2], z = qr[3];
    double M[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                   2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                   2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
    memcpy(R, M, sizeof M);
}

/* The reference element moved rigidly, then every DOF perturbed by amp x its scale. */
static void state(const bk_element *e, const double *geom, rng *r, double amp, double *q)
{
    double R[9], qr[4];
    random_rotation(r, R, qr);
    e->reference(geom, q);
    for (int f = 0; f < e->nfield; ++f) {
        double *v = q + e->field_dof[f];
        const bk_field_role role = e->field_role[f];
        double sc = 1.0;
        if (role == BK_FIELD_POSITION || bk_field_is_gradient(role)) {
            double w[3];
            for (int i = 0; i < 3; ++i)
                w[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
            for (int i = 0; i < 3; ++i)
                v[i] = w[i];
            sc = role == BK_FIELD_POSITION ? geom[BK_GEOM_L] : 1.0;
        } else if (role == BK_FIELD_QUATERNION) {
            double s = v[0], x = v[1], y = v[2], z = v[3];
            v[0] = qr[0] * s - qr[1] * x - qr[2] * y - qr[3] * z;
            v[1] = qr[0] * x + qr[1] * s + qr[2] * z - qr[3] * y;
            v[2] = qr[0] * y - qr[1] * z + qr[2] * s + qr[3] * x;
            v[3] = qr[0] * z + qr[1] * y - qr[2] * x + qr[3] * s;
        } else if (role == BK_FIELD_MULTIPLIER) {
            sc = 1e-3;
        }
        for (int i = 0; i < e->field_dim[f]; ++i)
            v[i] += amp * sc * urand(r);
    }
}

static void gram_schmidt(const double *d, double *G)
{
    double n3 = sqrt(d[6] * d[6] + d[7] * d[7] + d[8] * d[8]);
    for (int i = 0; i < 3; ++i)
        G[6 + i] = d[6 + i] / n3;
    double c = d[0] * G[6] + d[1] * G[7] + d[2] * G[8];
    for (int i = 0; i < 3; ++i)
        G[i] = d[i] - c * G[6 + i];
    double n1 = sqrt(G[0] * G[0] + G[1] * G[1] + G[2] * G[2]);
    for (int i = 0; i < 3; ++i)
        G[i] /= n1;
    G[3] = G[7] * G[2] - G[8] * G[1];
    G[4] = G[8] * G[0] - G[6] * G[2];
    G[5] = G[6] * G[1] - G[7] * G[0];
}

static const double OFF4[4] = {-2.0, -1.0, 1.0, 2.0}, CF4[4] = {1.0, -8.0, 8.0, -1.0};

/* P = pos + a1 e1 + a2 e2 at xi from frame() and section_frame(). */
static void line_point(const bk_element *e, const double *geom, double xi, const double *q, const double *a,
                       double *P)
{
    double pos[3], d[9], R[9];
    e->frame(geom, xi, q, pos, d);
    e->section_frame(geom, xi, q, R, NULL);
    for (int k = 0; k < 3; ++k)
        P[k] = pos[k] + a[0] * R[k] + a[1] * R[3 + k];
}

/* The section_line() fields of the output line (q: scratch of ndof). */
static void check_line(const bk_element *e, const double *geom, int nstate, double *q)
{
    const int n = e->ndof;
    double *dt = malloc(3 * (size_t)n * sizeof *dt), *dt0 = malloc(3 * (size_t)n * sizeof *dt0);
    double *H = malloc((size_t)n * n * sizeof *H), *dtp = malloc(3 * (size_t)n * sizeof *dtp);
    if (!dt || !dt0 || !H || !dtp) {
        printf(" line=nomem");
        free(dt), free(dt0), free(H), free(dtp);
        return;
    }
    rng r = {0xD1B54A32D192ED03ULL ^ (unsigned long long)n};
    double exi = 0.0, efd = 0.0, eh = 0.0, ec = 0.0;
    for (int s = 0; s < nstate; ++s) {
        state(e, geom, &r, s % 2 ? 1e-4 : 0.15, q);
        const double xi = 0.5 * (1.0 + 0.9 * urand(&r));
        const double a[2] = {0.4 * geom[BK_GEOM_B] * urand(&r), 0.4 * geom[BK_GEOM_H] * urand(&r)};
        const double u[3] = {urand(&r), urand(&r), urand(&r)};
        double t[3], t0[3], D[3] = {0.0, 0.0, 0.0}, big = 0.0, bigd = 0.0, bigh = 0.0, e1 = 0.0, e2 = 0.0, e3 = 0.0;
        e->section_line(geom, xi, q, a, u, t, dt, H);
        e->section_line(geom, xi, q, a, NULL, t0, dt0, NULL);
        for (int k = 0; k < 4; ++k) {
            double P[3];
            line_point(e, geom, xi + OFF4[k] * 1e-3, q, a, P);
            for (int i = 0; i < 3; ++i)
                D[i] += CF4[k] * P[i] / (12.0 * 1e-3);
        }
        for (int k = 0; k < 3; ++k) {
            big = fmax(big, fabs(t[k]));
            e1 = fmax(e1, fabs(t[k] - D[k]));
            ec = fmax(ec, fabs(t[k] - t0[k]));
        }
        for (int i = 0; i < 3 * n; ++i) {
            bigd = fmax(bigd, fabs(dt[i]));
            ec = fmax(ec, fabs(dt[i] - dt0[i]));
        }
        for (int i = 0; i < n * n; ++i)
            bigh = fmax(bigh, fabs(H[i]));
        for (int j = 0; j < n; ++j) {
            const double save = q[j], h = 2e-4 * fmax(1.0, fabs(save));
            double Dt[3] = {0.0, 0.0, 0.0}, tp[3];
            double *Du = dt0;               /* d(u . dt)/dq_j column, reusing dt0's first n entries */
            for (int i = 0; i < n; ++i)
                Du[i] = 0.0;
            for (int k = 0; k < 4; ++k) {
                q[j] = save + OFF4[k] * h;
                e->section_line(geom, xi, q, a, NULL, tp, dtp, NULL);
                for (int i = 0; i < 3; ++i)
                    Dt[i] += CF4[k] * tp[i] / (12.0 * h);
                for (int i = 0; i < n; ++i)
                    Du[i] += CF4[k] * (u[0] * dtp[i] + u[1] * dtp[n + i] + u[2] * dtp[2 * n + i]) / (12.0 * h);
            }
            q[j] = save;
            for (int i = 0; i < 3; ++i)
                e2 = fmax(e2, fabs(dt[i * n + j] - Dt[i]));
            for (int i = 0; i < n; ++i)
                e3 = fmax(e3, fabs(H[i * n + j] - Du[i]));
        }
        exi = fmax(exi, e1 / big);
        efd = fmax(efd, e2 / bigd);
        eh = fmax(eh, e3 / fmax(bigh, 1e-300));
    }
    printf(" line_xi=%.3e line_fd=%.3e line_h=%.3e line_c=%.3e", exi, efd, eh, ec);
    free(dt), free(dt0), free(H), free(dtp);
}

static int check(const bk_element *e, int nstate)
{
    const int n = e->ndof;
    double geom[BK_NGEOM] = {0.0};
    geom[BK_GEOM_L] = 0.7;
    geom[BK_GEOM_B] = 0.05;
    geom[BK_GEOM_H] = 0.03;
    geom[BK_GEOM_A] = geom[BK_GEOM_B] * geom[BK_GEOM_H];
    geom[BK_GEOM_I1] = geom[BK_GEOM_B] * pow(geom[BK_GEOM_H], 3) / 12.0;
    geom[BK_GEOM_I2] = geom[BK_GEOM_H] * pow(geom[BK_GEOM_B], 3) / 12.0;
    geom[BK_GEOM_IP] = geom[BK_GEOM_I1] + geom[BK_GEOM_I2];
    geom[BK_GEOM_SHAPE] = BK_SECTION_RECTANGLE;
    double *q = malloc((size_t)n * sizeof *q), *dR = malloc(9 * (size_t)n * sizeof *dR);
    if (!q || !dR) {
        free(q);
        free(dR);
        return -1;
    }
    rng r = {0x9E3779B97F4A7C15ULL ^ (unsigned long long)n};
    double fd = 0.0, fd2 = 0.0, consist = 0.0, orth = 0.0, gs = 0.0;
    for (int s = 0; s < nstate; ++s) {
        state(e, geom, &r, s % 2 ? 1e-4 : 0.15, q);
        double xi = 0.5 * (1.0 + urand(&r)), R[9], R0[9], pos[3], d[9], G[9];
        e->section_frame(geom, xi, q, R, dR);
        e->section_frame(geom, xi, q, R0, NULL);
        e->frame(geom, xi, q, pos, d);
        gram_schmidt(d, G);
        for (int k = 0; k < 9; ++k) {
            consist = fmax(consist, fabs(R[k] - R0[k]));
            gs = fmax(gs, fabs(R[k] - G[k]));
        }
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
                double dot = R[3 * a] * R[3 * b] + R[3 * a + 1] * R[3 * b + 1] + R[3 * a + 2] * R[3 * b + 2];
                orth = fmax(orth, fabs(dot - (a == b ? 1.0 : 0.0)));
            }
        double big = 0.0, e4 = 0.0, e2 = 0.0;
        for (int i = 0; i < 9 * n; ++i)
            big = fmax(big, fabs(dR[i]));
        for (int j = 0; j < n; ++j) {
            const double save = q[j], h = 2e-4 * fmax(1.0, fabs(save)), h2 = 1e-6 * fmax(1.0, fabs(save));
            static const double off[4] = {-2.0, -1.0, 1.0, 2.0}, cf[4] = {1.0, -8.0, 8.0, -1.0};
            double D4[9] = {0.0}, Rp[9], Rm[9];
            for (int t = 0; t < 4; ++t) {
                q[j] = save + off[t] * h;
                e->section_frame(geom, xi, q, Rp, NULL);
                for (int k = 0; k < 9; ++k)
                    D4[k] += cf[t] * Rp[k] / (12.0 * h);
            }
            q[j] = save + h2;
            e->section_frame(geom, xi, q, Rp, NULL);
            q[j] = save - h2;
            e->section_frame(geom, xi, q, Rm, NULL);
            q[j] = save;
            for (int k = 0; k < 9; ++k) {
                e4 = fmax(e4, fabs(dR[k * n + j] - D4[k]));
                e2 = fmax(e2, fabs(dR[k * n + j] - (Rp[k] - Rm[k]) / (2.0 * h2)));
            }
        }
        fd = fmax(fd, e4 / big);
        fd2 = fmax(fd2, e2 / big);
    }
    printf("element=%s states=%d fd=%.3e fd2=%.3e consist=%.3e orth=%.3e gs=%.3e", e->name, nstate, fd, fd2,
           consist, orth, gs);
    if (e->section_line)
        check_line(e, geom, nstate, q);
    else
        printf(" section_line=none");
    printf("\n");
    free(q);
    free(dR);
    return 0;
}

int main(int argc, char **argv)
{
    int nstate = argc > 1 ? atoi(argv[1]) : 20;
    for (int i = 0; i < frame_check_nelements; ++i) {
        const bk_element *e = frame_check_elements[i];
        if (!e->section_frame) {
            printf("element=%s section_frame=none\n", e->name);
            continue;
        }
        if (check(e, nstate) != 0) {
            fprintf(stderr, "frame_check: out of memory\n");
            return 1;
        }
    }
    return 0;
}
