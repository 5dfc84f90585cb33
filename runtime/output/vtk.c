/* vtk.c -- ParaView output: one XML UnstructuredGrid (.vtu) per written step and
 * a .pvd collection listing them with their times (rewritten at most every
 * BK_PVD_INTERVAL seconds of wall time while frames come, and at the end, so
 * that a run killed outright still leaves a readable collection, short of the
 * frames of its last half second; an interrupted run lists them all); modal analyses add one
 * mode_NN.vtu per mode and their collection modes.pvd (time value = mode number).
 *
 * Every element contributes, at NX stations along its axis, a ring of points
 * around its cross-section (8 for a rectangle, 12 for a circle) joined by
 * quads, and a polyline along the centreline.  Continuum (ANCF) elements place
 * the ring with their own interpolation, so the section shows its actual
 * deformation; beams with a section frame place it with d1, d2; the cable,
 * which has none, sweeps a section normal to its axis.  Point data:
 * displacement (m); cell data: strain energy density of the element (J/m^3).
 * Mode files: the points of the base state displaced by the scaled mode, point
 * data displacement (the scaled mode, m) and mode_shape (the mode normalized to
 * a largest point translation of 1), field data MODE, FREQUENCY_HZ, OMEGA and
 * MODE_SCALE (m).
 */
#include "output/vtk.h"
#include "base/bigalloc.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "assembly/system.h"

#include "output/forces.h"
#include "output/vtk_collection.h"
#include "output/vtk_geometry.h"

#define BK_PVD_INTERVAL 0.5

int bk_vtk_open(bk_vtk *v, const bk_model *m, const char *dir, int every, int capacity, int expected)
{
    memset(v, 0, sizeof *v);
    v->m = m;
    v->every = every;
    snprintf(v->dir, sizeof v->dir, "%s", dir);
    if (every <= 0)
        return 0;
    v->t_pvd = bk_clock_s();            /* the first collection once frames have come for BK_PVD_INTERVAL */
    v->expected = expected;
    v->cap = capacity > 16 ? capacity : 16;
    v->times = malloc((size_t)v->cap * sizeof *v->times);
    v->frames = malloc((size_t)v->cap * sizeof *v->frames);
    v->npts = bk_vtk_npoints(m);
    bk_vtk_frame_cells(m, &v->ncell, &v->nconn);
    size_t np = (size_t)v->npts;
    v->ref = bk_big_malloc((3 * np + 1) * sizeof *v->ref);
    v->pts = bk_big_malloc((3 * np + 1) * sizeof *v->pts);
    v->ntopo = bk_vtk_topology(m, NULL);
    v->topo = bk_big_malloc(v->ntopo);
    if (!v->times || !v->frames || !v->ref || !v->pts || !v->topo)
        return -1;
    bk_vtk_frame_points(m, m->q0, NULL, 0, v->ref, 1);
    bk_vtk_topology(m, v->topo);
    /* the appended arrays of the largest frame (a mode's: points, displacement,
     * mode shape; a step's: points, displacement, four section arrays, the
     * cells' energy density), the cells block and the XML around them */
    v->frame_bytes = 7 * (8 + 3 * np * sizeof(double)) + 8 + (size_t)v->ncell * sizeof(double) + v->ntopo + 16384;
    return 0;
}

/* The inputs of a frame made by the writer's thread, copied when it is handed
 * over (the solve goes on with its own): the field data, the coordinates (and
 * a mode frame's q +- eps phi with its view), the section forces and stress
 * resultants of its step (when it has them), and the thread's scratch for the
 * points. */
#define BK_VTK_MAX_FIELDS 5
typedef struct bk_vtk_job {
    const bk_vtk *v;         /* read-only while the thread runs: m, npts, ref, topo */
    int nfield;
    const char *const *fname;            /* static names */
    double fval[BK_VTK_MAX_FIELDS];
    double *q, *qp, *qm;     /* m->ndof each */
    int is_mode;             /* a mode frame: qp, qm and */
    double eps, norm, scale; /*   its view (mode_view) */
    double *sec, *ssec;      /* 12 per element; 6 maxsample per element */
    int with_sec, with_ssec, maxsample;
    const double *sec_live, *ssec_live;   /* or NULL: the section forces are read there when the frame
                              * is made (made by this thread before: forces.h bk_forces_frame_sections) */
    double *pts;             /* 3 npts */
} bk_vtk_job;

/* Frames of up to BK_VTK_BACKGROUND_MAX bytes go to the background writer
 * from the second frame of a run on that is expected to have at least
 * BK_VTK_BACKGROUND_MIN frames (from the first when the run's frames are known
 * in advance, v->expected): the thread, its buffers' first use and the wait
 * for the last frame at the end cost about as much as 5-8 frames written
 * directly.  frac: the fraction of the run done at this frame (load factor,
 * time or mode over its end), which with the frames so far gives the
 * expected number; <= 0 when unknown (arc-length, load cycles: the writer
 * starts at the third frame).  If it cannot be made, frames are written
 * directly, as they are without memory for the frames' inputs. */
#define BK_VTK_BACKGROUND_MIN 8
static void maybe_background(bk_vtk *v, double frac)
{
    if (v->background || v->tried_background || v->frame_bytes > BK_VTK_BACKGROUND_MAX)
        return;
    if (v->expected < BK_VTK_BACKGROUND_MIN) {
        if (v->written < (frac > 0.0 ? 1 : 2))
            return;
        if (frac > 0.0 && (v->written + 1) < BK_VTK_BACKGROUND_MIN * frac)
            return;                          /* a short run (asked again at its next frame) */
    }
    v->tried_background = 1;
    if (v->ext) {                        /* the output's writer (results.h5's thread) */
        if (v->ext->cap < v->frame_bytes || !bk_filewriter_start(v->ext))
            return;
        v->wp = v->ext;
    } else if (bk_filewriter_open(&v->fw, v->frame_bytes, 1) == 0)
        v->wp = &v->fw;
    else {
        bk_filewriter_close(&v->fw);
        return;
    }
    v->background = 1;
    const bk_model *m = v->m;
    size_t nq = (size_t)m->ndof, ne = (size_t)m->nelem, ns = 6 * (size_t)(v->maxsample > 0 ? v->maxsample : 1) * ne;
    size_t each = 3 * nq + 12 * ne + ns + 3 * (size_t)v->npts + 1;
    v->jobs = calloc(BK_FILEWRITER_BUFFERS, sizeof *v->jobs);
    double *mem = v->jobs ? bk_big_malloc(BK_FILEWRITER_BUFFERS * each * sizeof *mem) : NULL;
    if (!mem) {
        free(v->jobs);
        v->jobs = NULL;
        return;
    }
    for (int b = 0; b < BK_FILEWRITER_BUFFERS; ++b) {
        bk_vtk_job *j = &v->jobs[b];
        j->v = v;
        j->q = mem + (size_t)b * each;
        j->qp = j->q + nq;
        j->qm = j->qp + nq;
        j->sec = j->qm + nq;
        j->ssec = j->sec + 12 * ne;
        j->pts = j->ssec + ns;
    }
}

/* The first file written here that failed is kept. */
static void record_failure(bk_vtk *v, const char *path, int err)
{
    if (v->failed)
        return;
    v->failed = 1;
    v->errno_ = err ? err : EIO;
    snprintf(v->failed_path, sizeof v->failed_path, "%s", path);
}

int bk_vtk_finish(bk_vtk *v, FILE *err)
{
    int bad = v->background && bk_filewriter_drain(v->wp) != 0;
    const char *path = NULL;
    int e = 0;
    if (v->failed == 1) {
        path = v->failed_path, e = v->errno_;
        v->failed = 2;                    /* reported */
    } else if (bad && v->wp->failed == 1) {
        path = v->wp->failed_path, e = v->wp->errno_;
        v->wp->failed = 2;
    }
    if (err && path)
        fprintf(err, "error: %s: cannot write: %s\n", path, strerror(e));
    return bad || v->failed ? -1 : 0;
}

void bk_vtk_close(bk_vtk *v)
{
    if (v->background && v->wp == &v->fw)
        bk_filewriter_close(&v->fw);     /* (a shared writer is its owner's to close) */
    v->background = 0;
    if (v->jobs)
        free(v->jobs[0].q);              /* the block of every job's arrays */
    free(v->jobs);
    v->jobs = NULL;
    free(v->times);
    free(v->frames);
    free(v->ref);
    free(v->pts);
    free(v->topo);
    free(v->iobuf);
    v->iobuf = NULL;
    v->times = NULL;
    v->frames = NULL;
    v->ref = v->pts = NULL;
    v->topo = NULL;
}

/* A collection DIR/NAME (vtk_collection.h); its failure recorded. */
static int write_collection(bk_vtk *v, const char *dir, const char *name, int n, const double *t, const int *id,
                            const char *file_fmt)
{
    char path[1216];
    int e = 0;
    if (bk_vtk_collection(dir, name, n, t, id, file_fmt, path, sizeof path, &e) == 0)
        return 0;
    record_failure(v, path, e);
    return -1;
}

static int write_pvd(bk_vtk *v)
{
    if (v->background)                   /* the frames it lists first (a failed one: bk_vtk_finish) */
        bk_filewriter_drain(v->wp);
    return write_collection(v, v->dir, "results.pvd", v->nframe, v->times, v->frames, "step_%06d.vtu");
}

/* modes.pvd: mode_NN.vtu of modes 1..nmode, the mode number as the time value
 * (ParaView's animation steps through the modes). */
static int write_modes_pvd(bk_vtk *v)
{
    if (v->background)                   /* the frames it lists first (a failed one: bk_vtk_finish) */
        bk_filewriter_drain(v->wp);
    return write_collection(v, v->dir, "modes.pvd", v->nmode, NULL, NULL, "mode_%02d.vtu");
}


/* One XML UnstructuredGrid file: field data (name, value pairs), points,
 * point data (displacement; mode_shape for modes), cell data (strain energy
 * density, step frames only), cells.  The arrays are appended raw binary
 * (little endian, a UInt64 byte count before each), which ParaView reads and
 * which is written ~10 times faster than ASCII; the XML header names every
 * array with its offset into the appended block. */
static void put_u64(FILE *fp, uint64_t n)
{
    fwrite(&n, sizeof n, 1, fp);
}

static void vtu_contents(const bk_vtk *v, FILE *fp, int nfield, const char *const *fname, const double *fval,
                         const double *q, const mode_view *mv, const double *sec, const double *ssec, int maxsample,
                         double *pts, int par)
{
    const bk_model *m = v->m;
    const long npts = v->npts, ncell = v->ncell, nconn = v->nconn;
    int npass = mv ? 3 : 2;
    /* byte sizes of the appended arrays, in the order they are written */
    const uint64_t sz_pts = (uint64_t)npts * 3 * sizeof(double), sz_cell = (uint64_t)ncell * sizeof(double);
    const size_t isz = bk_vtk_index_size(npts);
    const char *itype = isz == sizeof(int32_t) ? "Int32" : "Int64";
    const uint64_t sz_conn = (uint64_t)nconn * isz, sz_off = (uint64_t)ncell * isz;
    uint64_t off = 0;
    fprintf(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <FieldData>\n");
    for (int f = 0; f < nfield; ++f)
        fprintf(fp, "      <DataArray type=\"Float64\" Name=\"%s\" NumberOfTuples=\"1\" format=\"ascii\">%.17g</DataArray>\n",
                fname[f], fval[f]);
    fprintf(fp, "    </FieldData>\n    <Piece NumberOfPoints=\"%ld\" NumberOfCells=\"%ld\">\n", npts, ncell);
    fprintf(fp, "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" "
                "offset=\"%llu\"/>\n      </Points>\n", (unsigned long long)off);
    off += 8 + sz_pts;
    fprintf(fp, "      <PointData Vectors=\"displacement\">\n        <DataArray type=\"Float64\" Name=\"displacement\" "
                "NumberOfComponents=\"3\" format=\"appended\" offset=\"%llu\"/>\n", (unsigned long long)off);
    off += 8 + sz_pts;
    if (mv) {
        fprintf(fp, "        <DataArray type=\"Float64\" Name=\"mode_shape\" NumberOfComponents=\"3\" "
                    "format=\"appended\" offset=\"%llu\"/>\n", (unsigned long long)off);
        off += 8 + sz_pts;
    }
    /* section forces (N, Q2, Q3) and moments (T, M2, M3), linear along each element
     * between its end values (sections.csv) */
    for (int a = 0; sec && a < 2; ++a) {
        fprintf(fp, "        <DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"3\" "
                    "format=\"appended\" offset=\"%llu\"/>\n", a ? "section_moment" : "section_force",
                (unsigned long long)off);
        off += 8 + sz_pts;
    }
    /* the elements' own stress resultants at their sample points, piecewise linear between them */
    for (int a = 0; sec && ssec && a < 2; ++a) {
        fprintf(fp, "        <DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"3\" "
                    "format=\"appended\" offset=\"%llu\"/>\n", a ? "section_moment_stress" : "section_force_stress",
                (unsigned long long)off);
        off += 8 + sz_pts;
    }
    fprintf(fp, "      </PointData>\n");
    if (!mv) {
        fprintf(fp, "      <CellData Scalars=\"strain_energy_density\">\n        <DataArray type=\"Float64\" "
                    "Name=\"strain_energy_density\" format=\"appended\" offset=\"%llu\"/>\n      </CellData>\n",
                (unsigned long long)off);
        off += 8 + sz_cell;
    }
    fprintf(fp, "      <Cells>\n        <DataArray type=\"%s\" Name=\"connectivity\" format=\"appended\" "
                "offset=\"%llu\"/>\n", itype, (unsigned long long)off);
    off += 8 + sz_conn;
    fprintf(fp, "        <DataArray type=\"%s\" Name=\"offsets\" format=\"appended\" offset=\"%llu\"/>\n",
            itype, (unsigned long long)off);
    off += 8 + sz_off;
    fprintf(fp, "        <DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"%llu\"/>\n"
                "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _",
            (unsigned long long)off);
    /* points, displacements (and mode shapes): the same traversal each time; a
     * step frame's points once, its displacements from the reference points of
     * bk_vtk_open */
    const size_t n3 = 3 * (size_t)npts;
    for (int pass = 0; pass < npass; ++pass) {
        put_u64(fp, sz_pts);
        if (!mv && pass == 1)
            for (size_t i = 0; i < n3; ++i)
                pts[i] -= v->ref[i];
        else
            bk_vtk_frame_points(m, q, mv, pass, pts, par);   /* (par: on the threads) */
        fwrite(pts, sizeof(double), n3, fp);
    }
    for (int a = 0; sec && a < 2; ++a) {
        put_u64(fp, sz_pts);
        for (int e = 0; e < m->nelem; ++e) {
            int r = bk_vtk_ring_points(m, e);
            const double *v0 = sec + 12 * (size_t)e + 3 * a, *v1 = v0 + 6;
            double vals[3 * NX * (MAX_RING + 1)];
            int np = 0;
            for (int k = 0; k < NX; ++k) {
                double xi = (double)k / (NX - 1), x[3];
                for (int i = 0; i < 3; ++i)
                    x[i] = (1.0 - xi) * v0[i] + xi * v1[i];
                for (int j = 0; j <= r; ++j, ++np)
                    memcpy(vals + 3 * np, x, sizeof x);
            }
            fwrite(vals, sizeof(double), 3 * (size_t)np, fp);
        }
    }
    for (int a = 0; sec && ssec && a < 2; ++a) {
        put_u64(fp, sz_pts);
        for (int e = 0; e < m->nelem; ++e) {
            int r = bk_vtk_ring_points(m, e);
            double vals[3 * NX * (MAX_RING + 1)];
            int np = 0;
            for (int k = 0; k < NX; ++k) {
                double x[3];
                bk_vtk_stress_value(m, ssec, maxsample, e, a, (double)k / (NX - 1), x);
                for (int j = 0; j <= r; ++j, ++np)
                    memcpy(vals + 3 * np, x, sizeof x);
            }
            fwrite(vals, sizeof(double), 3 * (size_t)np, fp);
        }
    }
    if (!mv) {
        put_u64(fp, sz_cell);
        bk_vtk_energy_density(m, q, pts, par);        /* (pts: free now; nelem <= 3 npts) */
        for (int e = 0; e < m->nelem; ++e) {
            int r = bk_vtk_ring_points(m, e), nc = (NX - 1) * r + 1;
            double vals[(NX - 1) * MAX_RING + 1];
            for (int c = 0; c < nc; ++c)
                vals[c] = pts[e];
            fwrite(vals, sizeof *vals, (size_t)nc, fp);
        }
    }
    fwrite(v->topo, 1, v->ntopo, fp);     /* cells: the same for every frame (bk_vtk_topology) */
    fprintf(fp, "\n  </AppendedData>\n</VTKFile>\n");
}

/* A frame of job (bk_filewriter_make: called by the writer's thread). */
static void frame_job(const void *job, FILE *fp)
{
    const bk_vtk_job *j = job;
    const mode_view mv = {j->qp, j->qm, j->eps, j->norm, j->scale};
    const double *sec = j->sec_live ? j->sec_live : j->sec, *ssec = j->sec_live ? j->ssec_live : j->ssec;
    vtu_contents(j->v, fp, j->nfield, j->fname, j->fval, j->q, j->is_mode ? &mv : NULL, j->with_sec ? sec : NULL,
                 j->with_ssec ? ssec : NULL, j->maxsample, j->pts, 0);
}

/* A call that does nothing: its return marks the frames before it as made. */
static void nothing(const void *arg, FILE *unused)
{
    (void)arg;
    (void)unused;
}

/* The frame file `path`: its inputs copied for the background writer's thread,
 * which makes, creates and writes it; or made and written here (here: the
 * run's last frame; no writer, a large frame, or every buffer still taken: the
 * thread is busy with other work, e.g. results.h5's HDF5 start of 5-10 ms, and
 * writing the frame here takes 0.1-0.3 ms where waiting took up to that long). */
static int write_vtu(bk_vtk *v, const char *path, int nfield, const char *const *fname, const double *fval,
                     const double *q, const mode_view *mv, int with_sec, int maxsample, int here)
{
    const double *sec = NULL, *ssec = NULL;
    v->written++;
    const int b = !here && v->background && v->jobs && nfield <= BK_VTK_MAX_FIELDS ? bk_filewriter_slot(v->wp, 0) : -1;
    if (b >= 0) {
        const bk_model *m = v->m;
        const size_t nq = (size_t)m->ndof;
        bk_vtk_job *j = &v->jobs[b];
        j->nfield = nfield;
        j->fname = fname;
        memcpy(j->fval, fval, (size_t)nfield * sizeof *fval);
        memcpy(j->q, q, nq * sizeof *q);
        j->is_mode = mv != NULL;
        if (mv) {
            memcpy(j->qp, mv->qp, nq * sizeof *q);
            memcpy(j->qm, mv->qm, nq * sizeof *q);
            j->eps = mv->eps, j->norm = mv->norm, j->scale = mv->scale;
        }
        j->with_sec = j->with_ssec = with_sec;   /* (the stress arrays go with the section forces) */
        j->maxsample = maxsample;
        j->sec_live = j->ssec_live = NULL;
        /* section forces being made by this frame's thread: read there, after them */
        const int live = with_sec && bk_forces_frame_sections(v->forces, v->wp, &sec, &ssec) == 1;
        if (live) {
            j->sec_live = sec;
            j->ssec_live = ssec;
        } else if (with_sec) {
            memcpy(j->sec, sec, 12 * (size_t)m->nelem * sizeof *sec);
            memcpy(j->ssec, ssec, 6 * (size_t)maxsample * (size_t)m->nelem * sizeof *ssec);
        }
        /* queued: listed even after an earlier failure (bk_vtk_finish reports it) */
        bk_filewriter_submit_job(v->wp, b, path, frame_job, j);
        if (live)                        /* (the values kept until the frame is made) */
            bk_forces_frame_handed(v->forces, bk_filewriter_call(v->wp, nothing, NULL));
        return 0;
    }
    if (with_sec)
        bk_forces_frame_sections(v->forces, NULL, &sec, &ssec);
    if (!v->iobuf && !(v->iobuf = malloc(BK_VTK_IOBUF))) {
        record_failure(v, path, ENOMEM);
        return -1;
    }
    FILE *fp = fopen(path, "wb");
    if (!fp) {
        record_failure(v, path, errno);
        return -1;
    }
    setvbuf(fp, v->iobuf, _IOFBF, BK_VTK_IOBUF);
    vtu_contents(v, fp, nfield, fname, fval, q, mv, sec, ssec, maxsample, v->pts, 1);
    if (fclose(fp) != 0) {
        record_failure(v, path, errno);
        return -1;
    }
    return 0;
}

int bk_vtk_frame(bk_vtk *v, const bk_system *s, int step, double t, const double *q)
{
    if (v->every <= 0)
        return 0;
    if (v->calls++ % v->every != 0 && step >= 0)
        return 0;
    if (v->nframe == v->cap) {                       /* grow (rare: capacity is estimated) */
        int cap = 2 * v->cap;
        double *nt = realloc(v->times, (size_t)cap * sizeof *nt);
        if (!nt)
            return -1;
        v->times = nt;
        int *nf = realloc(v->frames, (size_t)cap * sizeof *nf);
        if (!nf)
            return -1;
        v->frames = nf;
        v->cap = cap;
    }
    int frame = step < 0 ? -step : step;
    char path[1200];
    snprintf(path, sizeof path, "%s/step_%06d.vtu", v->dir, frame);
    const int with_sec = v->forces && v->forces->sec_step == frame;
    maybe_background(v, v->end > 0.0 ? t / v->end : -1.0);    /* the analysis' plan (output.h) */
    /* the run's last frame here: the caller would wait for it at the end, while the
     * thread makes the step's rows and section forces (roll-up: 0.35 ms of waiting) */
    const int last = v->end > 0.0 && t >= v->end * (1.0 - 1e-9);
    static const char *const names[] = {"TIME"};
    if (write_vtu(v, path, 1, names, &t, q, NULL, with_sec, v->maxsample, last) != 0)
        return -1;
    if (s && bk_interactions_frame(s, v->dir, frame, t, q, stderr) != 0)     /* contact points, ... */
        return -1;
    v->times[v->nframe] = t;
    v->frames[v->nframe] = frame;
    v->nframe++;
    v->pvd_stale = 1;
    return bk_clock_s() - v->t_pvd >= BK_PVD_INTERVAL ? bk_vtk_flush(v) : 0;
}

int bk_vtk_flush(bk_vtk *v)
{
    if (v->every <= 0 || !v->pvd_stale)
        return 0;
    v->pvd_stale = 0;
    v->t_pvd = bk_clock_s();
    return write_pvd(v);
}

int bk_vtk_mode(bk_vtk *v, int mode, int nval, const char *const *names, const double *vals, double scale,
                double norm, const double *q, const double *qp, const double *qm, double eps)
{
    if (v->every <= 0)
        return 0;
    char path[1200];
    snprintf(path, sizeof path, "%s/mode_%02d.vtu", v->dir, mode);
    char caps[BK_VTK_MODE_FIELDS][BK_VTK_NAME];
    const char *fname[BK_VTK_MODE_FIELDS];
    double fval[BK_VTK_MODE_FIELDS];
    int nf = bk_vtk_mode_fields(mode, nval, names, vals, scale, caps, fname, fval);
    mode_view mv = {qp, qm, eps, norm, scale};
    maybe_background(v, v->modes > 0 ? (double)mode / v->modes : -1.0);
    if (write_vtu(v, path, nf, fname, fval, q, &mv, 0, 0, 0) != 0)
        return -1;
    if (mode > v->nmode)
        v->nmode = mode;
    return write_modes_pvd(v);
}
