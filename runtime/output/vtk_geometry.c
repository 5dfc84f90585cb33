/* vtk_geometry.c -- the points and cells of the ParaView frames: section
 * rings along each element (the continuum elements' own interpolation, else
 * the section frame, else a section normal to the axis), the mode view, the
 * elements' stress resultants along their axis, and the cell topology (see
 * vtk_geometry.h). */
#include "output/vtk_geometry.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "assembly/system.h"
#include "output/vtk.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif


/* Section shape of element e (enum bk_section_shape): an element that takes
 * one shape only has that one (the continuum elements: their box b x h); else
 * the beam's, geom[BK_GEOM_SHAPE] as the scene compiler writes it (a
 * rectangle where a hand-made model leaves it unstated). */
static int section_shape(const bk_model *m, int e)
{
    const unsigned both = BK_CAP_SECTION_RECTANGLE | BK_CAP_SECTION_CIRCLE;
    const unsigned caps = bk_elem_type(m, e)->caps & both;
    if (caps == BK_CAP_SECTION_RECTANGLE)
        return BK_SECTION_RECTANGLE;
    if (caps == BK_CAP_SECTION_CIRCLE)
        return BK_SECTION_CIRCLE;
    const double shape = m->geoms[m->elems[e].geom][BK_GEOM_SHAPE];
    return shape == (double)BK_SECTION_CIRCLE ? BK_SECTION_CIRCLE : BK_SECTION_RECTANGLE;
}

/* Points of the section ring: 8 around a rectangle, 12 around a circle. */
int bk_vtk_ring_points(const bk_model *m, int e)
{
    return section_shape(m, e) == BK_SECTION_CIRCLE ? 12 : 8;
}

/* Section point k of n in section coordinates (y along d1, z along d2); a layer of
 * a layered section (bk_kernel.h BK_GEOM_BAND_LO, _HI): the ring of its band. */
static void ring_yz(const double *g, int n, int k, double *y, double *z)
{
    if (n == 8) {
        static const double uy[8] = {-1, 0, 1, 1, 1, 0, -1, -1}, uz[8] = {-1, -1, -1, 0, 1, 1, 1, 0};
        const double lo = g[BK_GEOM_BAND_LO], hi = g[BK_GEOM_BAND_HI];
        *y = 0.5 * g[BK_GEOM_B] * uy[k];
        if (lo != 0.0 || hi != 0.0)
            *z = (lo - 0.5 + 0.5 * (uz[k] + 1.0) * (1.0 - lo - hi)) * g[BK_GEOM_H];
        else
            *z = 0.5 * g[BK_GEOM_H] * uz[k];
    } else {
        double a = 2.0 * M_PI * k / n;
        *y = 0.5 * g[BK_GEOM_B] * cos(a);
        *z = 0.5 * g[BK_GEOM_B] * sin(a);
    }
}

static void unit(double *v)
{
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (n > 0)
        for (int i = 0; i < 3; ++i)
            v[i] /= n;
}

/* Station xi of element e for coordinates q, evaluated once for all its
 * section points: a beam's centre and section frame (bk_eval_point, the
 * costly part for the rods); the continuum elements' own field is evaluated
 * at each point (field = 1). */
typedef struct station {
    const double *q;
    int e, field;
    double xi, x[3], d[9];
} station;

static void station_at(const bk_model *m, const double *q, int e, double xi, station *st)
{
    st->q = q, st->e = e, st->xi = xi;
    st->field = (m->pairs[m->elems[e].pair]->element->caps & BK_CAP_SECTION_FIELD) != 0;
    if (!st->field)
        bk_eval_point(m, q, e, xi, st->x, st->d);
}

/* Position of section point (y, z) of station st. */
static void section_point(const bk_model *m, const station *st, double y, double z, double *x)
{
    const bk_elem *el = &m->elems[st->e];
    const bk_element *et = m->pairs[el->pair]->element;
    if (st->field) {                               /* continuum: the element's own field */
        double N[BK_MAX_SHAPE];
        et->shape(m->geoms[el->geom], st->xi, y, z, N);
        for (int i = 0; i < 3; ++i)
            x[i] = 0.0;
        for (int a = 0; a < et->nshape; ++a)
            for (int i = 0; i < 3; ++i)
                x[i] += N[a] * st->q[el->dofs[et->shape_dof[a] + i]];
        return;
    }
    const double *d = st->d;
    for (int i = 0; i < 3; ++i)
        x[i] = st->x[i];
    if (isfinite(d[0]) && isfinite(d[3])) {        /* beams with a section frame */
        for (int i = 0; i < 3; ++i)
            x[i] += y * d[i] + z * d[3 + i];
        return;
    }
    /* no section frame (cable): a section normal to the axis, oriented by the global
     * axis least aligned with it */
    double t[3] = {d[6], d[7], d[8]}, a[3] = {0, 0, 0}, u[3], w[3];
    unit(t);
    int k = fabs(t[0]) < fabs(t[1]) ? (fabs(t[0]) < fabs(t[2]) ? 0 : 2) : (fabs(t[1]) < fabs(t[2]) ? 1 : 2);
    a[k] = 1.0;
    u[0] = a[1] * t[2] - a[2] * t[1], u[1] = a[2] * t[0] - a[0] * t[2], u[2] = a[0] * t[1] - a[1] * t[0];
    unit(u);
    w[0] = t[1] * u[2] - t[2] * u[1], w[1] = t[2] * u[0] - t[0] * u[2], w[2] = t[0] * u[1] - t[1] * u[0];
    for (int i = 0; i < 3; ++i)
        x[i] += y * u[i] + z * w[i];
}


/* A mode frame's point (y, z) of a station at q, q + eps phi and q - eps phi
 * (st[0], st[1], st[2]; st[0] is used by pass 0 only): pass 0 the displaced
 * point, 1 the scaled shape (displacement), 2 the shape. */
static void point_value(const bk_model *m, const station *st, const mode_view *mv, int pass, double y, double z,
                        double *out)
{
    double x[3], a[3], sh[3];
    section_point(m, &st[1], y, z, x);
    section_point(m, &st[2], y, z, a);
    for (int i = 0; i < 3; ++i)
        sh[i] = (x[i] - a[i]) / (2.0 * mv->eps * mv->norm);
    if (pass == 0) {
        section_point(m, &st[0], y, z, x);
        for (int i = 0; i < 3; ++i)
            out[i] = x[i] + mv->scale * sh[i];
    } else {
        for (int i = 0; i < 3; ++i)
            out[i] = pass == 1 ? mv->scale * sh[i] : sh[i];
    }
}

long bk_vtk_npoints(const bk_model *m)
{
    long n = 0;
    for (int e = 0; e < m->nelem; ++e)
        n += (long)NX * bk_vtk_ring_points(m, e) + NX;
    return n;
}

void bk_vtk_mode_extent(const bk_model *m, const double *qp, const double *qm, double eps, double *translation,
                        double *rotation)
{
    double tmax = 0.0, rmax = 0.0;
    for (int e = 0; e < m->nelem; ++e) {
        const double *g = m->geoms[m->elems[e].geom];
        int r = bk_vtk_ring_points(m, e);
        for (int k = 0; k < NX; ++k) {
            double xi = (double)k / (NX - 1), c[3], a[3], b[3];
            station sp, sm;
            station_at(m, qp, e, xi, &sp);
            station_at(m, qm, e, xi, &sm);
            section_point(m, &sp, 0.0, 0.0, a);
            section_point(m, &sm, 0.0, 0.0, b);
            for (int i = 0; i < 3; ++i)
                c[i] = (a[i] - b[i]) / (2.0 * eps);
            tmax = fmax(tmax, sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
            for (int j = 0; j < r; ++j) {
                double y, z, d[3];
                ring_yz(g, r, j, &y, &z);
                section_point(m, &sp, y, z, a);
                section_point(m, &sm, y, z, b);
                for (int i = 0; i < 3; ++i)
                    d[i] = (a[i] - b[i]) / (2.0 * eps);
                tmax = fmax(tmax, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
                for (int i = 0; i < 3; ++i)
                    d[i] -= c[i];
                rmax = fmax(rmax, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / sqrt(y * y + z * z));
            }
        }
    }
    *translation = tmax;
    *rotation = rmax;
}

/* The element's own stress resultants (sections.csv rows not "nodal") at xi:
 * piecewise linear between its sample points, constant beyond the outer ones;
 * a = 0: the force (N, Q2, Q3), 1: the moment (T, M2, M3); NaN without them. */
void bk_vtk_stress_value(const bk_model *m, const double *ssec, int maxsample, int e, int a, double xi, double *x)
{
    const bk_pair *p = m->pairs[m->elems[e].pair];
    const double *v = ssec + 6 * (size_t)maxsample * (size_t)e + 3 * a;
    if (!p->sections || p->nsample < 1) {
        x[0] = x[1] = x[2] = NAN;
        return;
    }
    const double *xs = p->sample_xi;
    int j = 0;
    while (j + 2 < p->nsample && xi > xs[j + 1])
        ++j;
    double t = p->nsample == 1 ? 0.0 : (xi - xs[j]) / (xs[j + 1] - xs[j]);
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    for (int i = 0; i < 3; ++i)
        x[i] = p->nsample == 1 ? v[i] : (1.0 - t) * v[6 * j + i] + t * v[6 * (j + 1) + i];
}

/* The points of a frame, in frame order (element, station, ring point; the
 * centreline point last in each ring): 3 bk_vtk_npoints doubles into x; a step
 * frame's (mv NULL) for coordinates q, else a mode frame's pass `pass`
 * (point_value). */
void bk_vtk_frame_points(const bk_model *m, const double *q, const mode_view *mv, int pass, double *x, int par)
{
    const int ne = m->nelem;
#pragma omp parallel if (par && ne >= 256)
    {
        int e0 = 0, e1 = ne;
#ifdef _OPENMP
        const int nt = omp_get_num_threads(), t = omp_get_thread_num();
        e0 = (int)((long)ne * t / nt), e1 = (int)((long)ne * (t + 1) / nt);
#endif
        long np = 0;                                 /* the points of the elements before this part's */
        for (int e = 0; e < e0; ++e)
            np += (long)NX * (bk_vtk_ring_points(m, e) + 1);
        for (int e = e0; e < e1; ++e) {
            const double *g = m->geoms[m->elems[e].geom];
            int r = bk_vtk_ring_points(m, e);
            for (int k = 0; k < NX; ++k) {
                double xi = (double)k / (NX - 1);
                station st[3];                       /* at q, and at mv's q + eps phi, q - eps phi */
                if (!mv || pass == 0)
                    station_at(m, q, e, xi, &st[0]);
                if (mv) {
                    station_at(m, mv->qp, e, xi, &st[1]);
                    station_at(m, mv->qm, e, xi, &st[2]);
                }
                for (int j = 0; j <= r; ++j) {
                    double y = 0.0, z = 0.0;
                    if (j < r)
                        ring_yz(g, r, j, &y, &z);
                    if (mv)
                        point_value(m, st, mv, pass, y, z, x + 3 * np++);
                    else
                        section_point(m, &st[0], y, z, x + 3 * np++);
                }
            }
        }
    }
}

void bk_vtk_energy_density(const bk_model *m, const double *q, double *dens, int par)
{
#pragma omp parallel for schedule(static) if (par && m->nelem >= 256)
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_pair *p = m->pairs[el->pair];
        double qe[BK_MAX_ELEMENT_DOF];
        bk_gather(m, e, q, qe);
        const double *g = m->geoms[el->geom];
        /* a layer (bk_kernel.h): its energy over its band's volume */
        dens[e] = p->energy(qe, m->tabs[el->geom], m->mats[el->mat].params) /
                  (g[BK_GEOM_L] * g[BK_GEOM_A] * (1.0 - g[BK_GEOM_BAND_LO] - g[BK_GEOM_BAND_HI]));
    }
}

/* Cells and connectivity entries of every frame of the model. */
void bk_vtk_frame_cells(const bk_model *m, long *ncell, long *nconn)
{
    *ncell = *nconn = 0;
    for (int e = 0; e < m->nelem; ++e) {
        int r = bk_vtk_ring_points(m, e);
        *ncell += (long)(NX - 1) * r + 1;
        *nconn += 4L * (NX - 1) * r + NX;
    }
}

/* Bytes of a connectivity or offset entry: Int32 while every point index and
 * offset fits (always, short of some 50 million elements), else Int64. */
size_t bk_vtk_index_size(long npts)
{
    return npts * 4 < INT32_MAX ? sizeof(int32_t) : sizeof(int64_t);
}

/* Appends index v to b as an bk_vtk_index_size entry; returns the next position. */
static unsigned char *put_index(unsigned char *b, int64_t v, size_t size)
{
    if (size == sizeof(int32_t)) {
        int32_t w = (int32_t)v;
        memcpy(b, &w, sizeof w);
    } else {
        memcpy(b, &v, sizeof v);
    }
    return b + size;
}

/* The cells block of every frame, as it is appended (byte count, connectivity;
 * byte count, offsets; byte count, types), into buf; its size in bytes (buf
 * NULL: the size only).  Point index of (element e, station k, ring point j) =
 * base_e + k (r + 1) + j; j = r is the centreline point. */
size_t bk_vtk_topology(const bk_model *m, unsigned char *buf)
{
    long ncell, nconn;
    bk_vtk_frame_cells(m, &ncell, &nconn);
    const size_t isz = bk_vtk_index_size(bk_vtk_npoints(m));
    const uint64_t sz_conn = (uint64_t)nconn * isz, sz_off = (uint64_t)ncell * isz;
    const size_t size = 3 * sizeof(uint64_t) + sz_conn + sz_off + (size_t)ncell;
    if (!buf)
        return size;
    unsigned char *b = buf;
    memcpy(b, &sz_conn, sizeof sz_conn);
    b += sizeof sz_conn;
    int64_t base = 0, nv;
    for (int e = 0; e < m->nelem; ++e) {
        int r = bk_vtk_ring_points(m, e), w = r + 1;
        int64_t conn[4 * (NX - 1) * MAX_RING + NX];
        nv = 0;
        for (int k = 0; k + 1 < NX; ++k)
            for (int j = 0; j < r; ++j) {
                int j2 = (j + 1) % r;
                conn[nv++] = base + k * w + j;
                conn[nv++] = base + k * w + j2;
                conn[nv++] = base + (k + 1) * w + j2;
                conn[nv++] = base + (k + 1) * w + j;
            }
        for (int k = 0; k < NX; ++k)
            conn[nv++] = base + k * w + r;
        for (int64_t i = 0; i < nv; ++i)
            b = put_index(b, conn[i], isz);
        base += (int64_t)NX * w;
    }
    memcpy(b, &sz_off, sizeof sz_off);
    b += sizeof sz_off;
    int64_t o = 0;
    for (int e = 0; e < m->nelem; ++e) {
        int r = bk_vtk_ring_points(m, e);
        for (int c = 0; c < (NX - 1) * r; ++c) {
            o += 4;
            b = put_index(b, o, isz);
        }
        o += NX;
        b = put_index(b, o, isz);
    }
    const uint64_t nc = (uint64_t)ncell;
    memcpy(b, &nc, sizeof nc);
    b += sizeof nc;
    for (int e = 0; e < m->nelem; ++e) {
        int r = bk_vtk_ring_points(m, e);
        memset(b, 9, (size_t)(NX - 1) * r);              /* VTK_QUAD */
        b += (size_t)(NX - 1) * r;
        *b++ = 4;                                        /* VTK_POLY_LINE */
    }
    return size;
}

int bk_vtk_mode_fields(int mode, int nval, const char *const *names, const double *vals, double scale,
                       char caps[][BK_VTK_NAME], const char **fname, double *fval)
{
    int nf = 0;
    fname[nf] = "TIME", fval[nf++] = (double)mode;
    fname[nf] = "MODE", fval[nf++] = (double)mode;
    for (int k = 0; k < nval && nf < BK_VTK_MODE_FIELDS - 1; ++k, ++nf) {
        int i = 0;
        for (; names[k][i] && i < BK_VTK_NAME - 1; ++i)
            caps[nf][i] = (char)(names[k][i] >= 'a' && names[k][i] <= 'z' ? names[k][i] - 'a' + 'A' : names[k][i]);
        caps[nf][i] = 0;
        fname[nf] = caps[nf];
        fval[nf] = vals[k];
    }
    fname[nf] = "MODE_SCALE", fval[nf++] = scale;
    return nf;
}
