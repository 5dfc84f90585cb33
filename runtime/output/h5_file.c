/* h5_file.c -- results.h5: every HDF5 call, made by the HDF5 thread (see h5.h). */
#include "output/h5_impl.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <hdf5.h>

#include "assembly/system.h"

_Static_assert(sizeof(hid_t) == sizeof(bk_h5_id), "hid_t is not 64 bits: HDF5 older than 1.10");

/* Chunks of about CHUNK_BYTES: a chunk is made (zeroed, written whole) as soon
 * as a row of it is, so a short run's file and time stay small with small
 * chunks, and a long run's writes are a chunk or more at a time. */
#define CHUNK_BYTES (32 << 10)
#define CHUNK_CACHE 2
#define CHUNK_ROWS(rowbytes) ((hsize_t)fmax(1.0, floor((double)CHUNK_BYTES / (double)(rowbytes))))

/* The first failure is kept (reported by bk_h5_close). */
static int fail(bk_h5 *h, const char *what)
{
    if (!h->failed) {
        h->failed = 1;
        snprintf(h->failure, sizeof h->failure, "%s", what);
    }
    return -1;
}

/* A group without modification times (a run's file is the same bytes each
 * time); -1 on failure. */
static hid_t make_group(hid_t where, const char *name)
{
    hid_t pl = H5Pcreate(H5P_GROUP_CREATE);
    hid_t g = pl >= 0 && H5Pset_obj_track_times(pl, 0) >= 0 ? H5Gcreate2(where, name, H5P_DEFAULT, pl, H5P_DEFAULT)
                                                           : -1;
    if (pl >= 0)
        H5Pclose(pl);
    return g;
}

/* A dataset of rows of `width` cells (width 0: one cell a row, 1-d): chunked
 * and extensible in rows from 0 (fixed 0), or contiguous of `fixed` rows when
 * they are all known (the run's last rows); 0 on failure. */
static hid_t make_dataset(hid_t where, const char *name, hid_t type, hsize_t width, hsize_t chunk_rows, hsize_t fixed)
{
    int rank = width ? 2 : 1;
    hsize_t dims[2] = {fixed, width}, maxd[2] = {fixed ? fixed : H5S_UNLIMITED, width}, chunk[2] = {chunk_rows, width};
    hid_t space = H5Screate_simple(rank, dims, maxd);
    hid_t plist = H5Pcreate(H5P_DATASET_CREATE), access = H5Pcreate(H5P_DATASET_ACCESS);
    hid_t ds = -1;
    /* a chunk cache of CHUNK_CACHE chunks: a chunk is written as soon as it
     * is full (by the thread, beside the solve), not all at the file's close */
    if (space >= 0 && plist >= 0 && access >= 0 && (fixed || H5Pset_chunk(plist, rank, chunk) >= 0) &&
        H5Pset_obj_track_times(plist, 0) >= 0 &&
        (fixed || H5Pset_chunk_cache(access, 521, CHUNK_CACHE * chunk_rows * H5Tget_size(type) * (width ? width : 1),
                                     1.0) >= 0))
        ds = H5Dcreate2(where, name, type, space, H5P_DEFAULT, plist, access);
    if (access >= 0)
        H5Pclose(access);
    if (plist >= 0)
        H5Pclose(plist);
    if (space >= 0)
        H5Sclose(space);
    return ds >= 0 ? ds : 0;
}

/* Appends rows [n, width] (width 0: 1-d) of buf to ds, which holds `have`
 * rows (fixed: ds is contiguous of exactly these rows, written whole). */
static int append(hid_t ds, hid_t memtype, hsize_t have, hsize_t n, hsize_t width, const void *buf, int fixed)
{
    if (n == 0)
        return 0;
    if (fixed)
        return H5Dwrite(ds, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0 ? 0 : -1;
    int rank = width ? 2 : 1;
    hsize_t size[2] = {have + n, width}, start[2] = {have, 0}, count[2] = {n, width};
    if (H5Dset_extent(ds, size) < 0)
        return -1;
    hid_t fs = H5Dget_space(ds);
    hid_t ms = H5Screate_simple(rank, count, NULL);
    int rc = -1;
    if (fs >= 0 && ms >= 0 && H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
        H5Dwrite(ds, memtype, ms, fs, H5P_DEFAULT, buf) >= 0)
        rc = 0;
    if (ms >= 0)
        H5Sclose(ms);
    if (fs >= 0)
        H5Sclose(fs);
    return rc;
}

static hid_t str_type(void)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    if (t >= 0 && (H5Tset_size(t, BK_H5_STR) < 0 || H5Tset_strpad(t, H5T_STR_NULLPAD) < 0)) {
        H5Tclose(t);
        return -1;
    }
    return t;
}

static int attr_str(hid_t obj, const char *name, const char *value)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    hid_t sp = H5Screate(H5S_SCALAR);
    int rc = -1;
    if (t >= 0 && sp >= 0 && H5Tset_size(t, strlen(value) > 0 ? strlen(value) : 1) >= 0) {
        hid_t a = H5Acreate2(obj, name, t, sp, H5P_DEFAULT, H5P_DEFAULT);
        if (a >= 0) {
            rc = H5Awrite(a, t, value) >= 0 ? 0 : -1;
            H5Aclose(a);
        }
    }
    if (sp >= 0)
        H5Sclose(sp);
    if (t >= 0)
        H5Tclose(t);
    return rc;
}

static int attr_int(hid_t obj, const char *name, long value)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    int rc = -1;
    long long v = value;
    hid_t a = sp >= 0 ? H5Acreate2(obj, name, H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT) : -1;
    if (a >= 0) {
        rc = H5Awrite(a, H5T_NATIVE_LLONG, &v) >= 0 ? 0 : -1;
        H5Aclose(a);
    }
    if (sp >= 0)
        H5Sclose(sp);
    return rc;
}

/* A whole 1-d dataset of n cells. */
static int whole(hid_t where, const char *name, hid_t ftype, hid_t mtype, hsize_t n, const void *buf)
{
    hid_t sp = H5Screate_simple(1, &n, NULL);
    int rc = -1;
    hid_t pl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t ds = sp >= 0 && pl >= 0 && H5Pset_obj_track_times(pl, 0) >= 0
                   ? H5Dcreate2(where, name, ftype, sp, H5P_DEFAULT, pl, H5P_DEFAULT) : -1;
    if (pl >= 0)
        H5Pclose(pl);
    if (ds >= 0) {
        rc = n == 0 || H5Dwrite(ds, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0 ? 0 : -1;
        H5Dclose(ds);
    }
    if (sp >= 0)
        H5Sclose(sp);
    return rc;
}

/* /dofs (h5_whole.c bk_h5_dofs). */
static int write_dofs(bk_h5 *h)
{
    const size_t nd = (size_t)h->m->ndof;
    bk_h5_dofs d;
    int rc = -1;
    if (bk_h5_dofs_make(h->m, &d) != 0)
        goto out;
    hid_t g = make_group(h->file, "dofs");
    hid_t s64 = str_type(), s8 = H5Tcopy(H5T_C_S1), s2 = H5Tcopy(H5T_C_S1);
    if (g >= 0 && s64 >= 0 && s8 >= 0 && s2 >= 0 && H5Tset_size(s8, 8) >= 0 && H5Tset_size(s2, 2) >= 0 &&
        whole(g, "node", H5T_STD_I32LE, H5T_NATIVE_INT, nd, d.node) == 0 &&
        whole(g, "element", H5T_STD_I32LE, H5T_NATIVE_INT, nd, d.elem) == 0 &&
        whole(g, "beam", s64, s64, nd, d.beam) == 0 && whole(g, "field", s8, s8, nd, d.field) == 0 &&
        whole(g, "component", s2, s2, nd, d.comp) == 0)
        rc = 0;
    if (s2 >= 0)
        H5Tclose(s2);
    if (s8 >= 0)
        H5Tclose(s8);
    if (s64 >= 0)
        H5Tclose(s64);
    if (g >= 0)
        H5Gclose(g);
out:
    bk_h5_dofs_free(&d);
    return rc;
}

/* ---- the thread: every HDF5 call ---- */

static void make_file(bk_h5 *h)
{
    if (h->file || h->failed)
        return;                                  /* (made for the thread's rows: bk_h5_write_thread_rows) */
    const bk_model *m = h->m;
    /* HDF5 is started and ended on this thread (H5close: the last job): its
     * exit handler would make per-thread state for the main thread at exit */
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);       /* failures are reported by return codes, once */
    hid_t f = H5Fcreate(h->path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (f < 0) {
        fail(h, errno ? strerror(errno) : "HDF5 cannot create it");
        return;
    }
    h->file = f;
    hid_t tg = make_group(f, "tables");
    h->tables_group = tg >= 0 ? tg : 0;
    int ok = tg >= 0 && attr_str(f, "scene", m->name) == 0 &&
             attr_str(f, "analysis", bk_analysis_name(m->analysis)) == 0 &&
             attr_str(f, "time_name", h->with_qd ? "time" : "load_factor") == 0 &&
             attr_str(f, "units", BK_H5_UNITS) == 0 &&
             attr_int(f, "format", 1) == 0 && attr_int(f, "ndof", m->ndof) == 0 && write_dofs(h) == 0;
    if (!ok)
        fail(h, "HDF5 failed to lay out the file");
}

/* The states' datasets at their first rows: contiguous when these are the
 * last (fixed: their number), else chunked; 0 or -1. */
static int make_states(bk_h5 *h, hsize_t fixed)
{
    const hsize_t nd = (hsize_t)h->ndof;
    hid_t f = h->file;
    return (h->ds_step = make_dataset(f, "step", H5T_STD_I64LE, 0, CHUNK_ROWS(8), fixed)) != 0 &&
           (h->ds_time = make_dataset(f, "time", H5T_IEEE_F64LE, 0, CHUNK_ROWS(8), fixed)) != 0 &&
           (h->ds_q = make_dataset(f, "q", H5T_IEEE_F64LE, nd, CHUNK_ROWS(8 * nd), fixed)) != 0 &&
           (!h->with_qd || (h->ds_qd = make_dataset(f, "qd", H5T_IEEE_F64LE, nd, CHUNK_ROWS(8 * nd), fixed)) != 0)
               ? 0 : -1;
}

/* n rows of t appended to its dataset (made at its first rows: of exactly n
 * rows when fixed); 0, or -1 (h->failed). */
static int table_rows(bk_h5 *h, bk_h5_table *t, hid_t s64, const unsigned char *rows, long n, int fixed)
{
    if (n == 0)
        return 0;
    if (!t->ds) {
        /* the row's compound type: a member per column, named by the header */
        hid_t ct = H5Tcreate(H5T_COMPOUND, t->rowbytes);
        int ok = ct >= 0;
        for (int c = 0; c < t->ncol && ok; ++c)
            ok = H5Tinsert(ct, t->col[c].name, t->col[c].off,
                           t->col[c].type == 1 ? H5T_NATIVE_DOUBLE : t->col[c].type == 2 ? H5T_NATIVE_INT64 : s64)
                 >= 0;
        if (ok && (t->ds = make_dataset(h->tables_group, t->name, ct, 0, CHUNK_ROWS(t->rowbytes),
                                      fixed ? (hsize_t)n : 0)) != 0)
            t->type = ct;
        else if (ct >= 0)
            H5Tclose(ct);
    }
    if (!t->ds || append(t->ds, t->type, (hsize_t)t->nrow, (hsize_t)n, 0, rows, fixed) != 0)
        return fail(h, "HDF5 failed to append a table's rows");
    t->nrow += n;
    return 0;
}

/* The thread's rows of t are in the file: a row it is giving (its fields may
 * come in two chunks of the queue) moves to the start. */
static void thread_rows_written(bk_h5_table *t)
{
    if (t->ct.row && t->ct.row != t->tbuf) {
        memmove(t->tbuf, t->ct.row, t->stride);   /* (stride 0: the first row, at the start already) */
        t->ct.row = t->tbuf;
    }
    t->ntb = 0;
}

void bk_h5_write_thread_rows(bk_h5 *h, bk_h5_table *t)
{
    if (!h->file && !h->failed) {                /* no set handed over yet */
        make_file(h);
        h->tlib = 1;
    }
    if (!h->failed && h->file) {
        hid_t s64 = str_type();
        if (s64 < 0)
            fail(h, "HDF5 failed to make a string type");
        else {
            table_rows(h, t, s64, t->tbuf, t->ntb, 0);
            H5Tclose(s64);
        }
    }
    thread_rows_written(t);                      /* (dropped after a failure: reported at the close) */
}

static void write_set(bk_h5 *h, int k)
{
    if (h->failed || !h->file)
        return;
    hsize_t nd = (hsize_t)h->ndof, n = (hsize_t)h->nbuf[k], have = (hsize_t)h->nstate;
    /* the run's last rows, for datasets not yet made: all their rows (none
     * left: chunked and empty, as before any) */
    const int last = h->flush[k] == 2;
    const int fixed = last && !h->ds_step && n > 0;
    if (!h->ds_step && make_states(h, fixed ? n : 0) != 0) {
        fail(h, "HDF5 failed to lay out the states");
        return;
    }
    if (append(h->ds_step, H5T_NATIVE_LONG, have, n, 0, h->step[k], fixed) != 0 ||
        append(h->ds_time, H5T_NATIVE_DOUBLE, have, n, 0, h->time[k], fixed) != 0 ||
        append(h->ds_q, H5T_NATIVE_DOUBLE, have, n, nd, h->q[k], fixed) != 0 ||
        (h->with_qd && append(h->ds_qd, H5T_NATIVE_DOUBLE, have, n, nd, h->qd[k], fixed) != 0)) {
        fail(h, "HDF5 failed to append the states");
        return;
    }
    h->nstate += (long)n;
    hid_t s64 = str_type();
    if (s64 < 0) {
        fail(h, "HDF5 failed to make a string type");
        return;
    }
    for (int j = 0; j < h->ntab && !h->failed; ++j) {
        bk_h5_table *t = h->tab[j];
        const long nb = t->nbuf[k], nt = t->threaded ? t->ntb : 0;
        if (t->ncol == 0 || nb + nt == 0)
            continue;
        /* the set's rows, then the thread's (a table mirrored by the thread
         * from the queue's start: csvrow.h), in one piece when all are known */
        const int tfixed = last && !t->ds && !(nb && nt);
        if (table_rows(h, t, s64, t->buf[k], nb, tfixed) != 0 || table_rows(h, t, s64, t->tbuf, nt, tfixed) != 0)
            break;
        if (nt)
            thread_rows_written(t);
    }
    H5Tclose(s64);
    if (!h->failed && h->flush[k] == 1 && H5Fflush(h->file, H5F_SCOPE_LOCAL) < 0)
        fail(h, "HDF5 failed to flush the file");
}

static void close_file(bk_h5 *h)
{
    hid_t ids[] = {h->ds_step, h->ds_time, h->ds_q, h->ds_qd, h->tables_group};
    for (size_t k = 0; k < sizeof ids / sizeof *ids; ++k)
        if (ids[k] > 0)
            H5Oclose(ids[k]);
    for (int k = 0; k < h->ntab; ++k) {
        if (h->tab[k]->ds > 0)
            H5Dclose(h->tab[k]->ds);
        if (h->tab[k]->type > 0)
            H5Tclose(h->tab[k]->type);
    }
    if (h->file > 0 && H5Fclose(h->file) < 0)
        fail(h, "HDF5 failed to close the file");
    h->file = 0;
}

void bk_h5_run_job(const void *arg, FILE *unused)
{
    (void)unused;
    const bk_h5_job *j = arg;
    if (j->what == 0)
        make_file(j->h);
    else if (j->what == 1)
        write_set(j->h, j->set);
    else if (j->what == 2)
        close_file(j->h);
    else {
        H5close();                                /* (started on this thread: make_file) */
    }
}

