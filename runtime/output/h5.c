/* h5.c -- results.h5 (see h5.h). */
#include "output/h5.h"

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

/* A chunked dataset of rows of `width` cells (width 0: one cell a row, 1-d),
 * extensible in rows; 0 on failure. */
static hid_t make_dataset(hid_t where, const char *name, hid_t type, hsize_t width, hsize_t chunk_rows)
{
    int rank = width ? 2 : 1;
    hsize_t dims[2] = {0, width}, maxd[2] = {H5S_UNLIMITED, width}, chunk[2] = {chunk_rows, width};
    hid_t space = H5Screate_simple(rank, dims, maxd);
    hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
    hid_t ds = -1;
    if (space >= 0 && plist >= 0 && H5Pset_chunk(plist, rank, chunk) >= 0)
        ds = H5Dcreate2(where, name, type, space, H5P_DEFAULT, plist, H5P_DEFAULT);
    if (plist >= 0)
        H5Pclose(plist);
    if (space >= 0)
        H5Sclose(space);
    return ds >= 0 ? ds : 0;
}

/* Appends rows [n, width] (width 0: 1-d) of buf to ds, which holds `have` rows. */
static int append(hid_t ds, hid_t memtype, hsize_t have, hsize_t n, hsize_t width, const void *buf)
{
    if (n == 0)
        return 0;
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
    hid_t ds = sp >= 0 ? H5Dcreate2(where, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
    if (ds >= 0) {
        rc = n == 0 || H5Dwrite(ds, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) >= 0 ? 0 : -1;
        H5Dclose(ds);
    }
    if (sp >= 0)
        H5Sclose(sp);
    return rc;
}

static const char *field_name(int role)
{
    switch (role) {
    case BK_FIELD_POSITION: return "r";
    case BK_FIELD_R_X: return "r_x";
    case BK_FIELD_R_Y: return "r_y";
    case BK_FIELD_R_Z: return "r_z";
    case BK_FIELD_R_YY: return "r_yy";
    case BK_FIELD_R_YZ: return "r_yz";
    case BK_FIELD_R_ZZ: return "r_zz";
    case BK_FIELD_QUATERNION: return "p";
    case BK_FIELD_MULTIPLIER: return "lambda";
    default: return "";
    }
}

/* /dofs: per DOF its node (numbered in the order the elements first reach
 * them; a node's fields run until a field role repeats), beam (sections
 * records; "" for bodies outside a beam), first element, field and component. */
static int write_dofs(bk_h5 *h)
{
    const bk_model *m = h->m;
    size_t nd = (size_t)m->ndof;
    int *node = malloc((nd + 1) * sizeof *node), *elem = malloc((nd + 1) * sizeof *elem);
    char *beam = calloc(nd + 1, BK_H5_STR), *field = calloc(nd + 1, 8), *comp = calloc(nd + 1, 2);
    int rc = -1;
    if (!node || !elem || !beam || !field || !comp)
        goto out;
    for (size_t d = 0; d < nd; ++d)
        node[d] = elem[d] = -1;
    const char *beam_of_none = "";
    int nnode = 0;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = bk_elem_type(m, e);
        const char *bname = beam_of_none;
        for (int k = 0; k < m->nsection; ++k)
            if (m->sections[k].elem == e) {
                bname = m->sections[k].beam;
                break;
            }
        unsigned seen = 0;            /* the roles of the node being walked */
        int cur = -1;                 /* its number */
        for (int k = 0; k < et->nfield; ++k) {
            int role = et->field_role[k];
            if (cur < 0 || (seen >> role & 1u)) {
                seen = 0;
                int d0 = m->elems[e].dofs[et->field_dof[k]];
                cur = node[d0] >= 0 ? node[d0] : nnode++;
            }
            seen |= 1u << role;
            const char *cn = role == BK_FIELD_QUATERNION ? "wxyz" : "xyz";
            for (int c = 0; c < et->field_dim[k]; ++c) {
                int d = m->elems[e].dofs[et->field_dof[k] + c];
                if (elem[d] >= 0)
                    continue;
                elem[d] = e;
                node[d] = role == BK_FIELD_MULTIPLIER ? -1 : cur;
                snprintf(beam + (size_t)d * BK_H5_STR, BK_H5_STR, "%s", bname);
                snprintf(field + (size_t)d * 8, 8, "%s", field_name(role));
                if (role != BK_FIELD_MULTIPLIER && c < (int)strlen(cn))
                    comp[(size_t)d * 2] = cn[c];
            }
        }
    }
    hid_t g = H5Gcreate2(h->file, "dofs", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    hid_t s64 = str_type(), s8 = H5Tcopy(H5T_C_S1), s2 = H5Tcopy(H5T_C_S1);
    if (g >= 0 && s64 >= 0 && s8 >= 0 && s2 >= 0 && H5Tset_size(s8, 8) >= 0 && H5Tset_size(s2, 2) >= 0 &&
        whole(g, "node", H5T_STD_I32LE, H5T_NATIVE_INT, nd, node) == 0 &&
        whole(g, "element", H5T_STD_I32LE, H5T_NATIVE_INT, nd, elem) == 0 &&
        whole(g, "beam", s64, s64, nd, beam) == 0 && whole(g, "field", s8, s8, nd, field) == 0 &&
        whole(g, "component", s2, s2, nd, comp) == 0)
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
    free(node);
    free(elem);
    free(beam);
    free(field);
    free(comp);
    return rc;
}

/* ---- the tables' mirror (csvrow.h bk_rowsink), on the solve thread ---- */

static size_t cell_size(int type)
{
    return type == 3 ? BK_H5_STR : 8;
}

/* Room for one more row of t in the set being filled: its buffer grows to
 * BK_H5_ROWS rows, then the set is handed over.  Before the first row's types
 * are known a row takes the most room a row can (every cell a string). */
static int table_room(bk_h5 *h, bk_h5_table *t)
{
    if (t->nbuf[h->cur] < t->cap[h->cur])
        return 0;
    if (t->cap[h->cur] >= BK_H5_ROWS) {
        bk_h5_flush(h);
        if (t->nbuf[h->cur] < t->cap[h->cur])
            return 0;
    }
    const int k = h->cur;
    int cap = t->cap[k] ? 2 * t->cap[k] : 64;
    size_t rowb = t->rowbytes ? t->rowbytes : (size_t)t->ncol * BK_H5_STR;
    unsigned char *b = realloc(t->buf[k], (size_t)cap * rowb);
    if (!b) {
        h->oom = 1;
        return -1;
    }
    t->buf[k] = b;
    t->cap[k] = cap;
    return 0;
}

/* Waits until the thread has done everything handed over. */
static void settle_thread(bk_h5 *h)
{
    for (int k = 0; k < 2; ++k)
        if (h->ticket[k] > 0) {
            bk_filewriter_wait(&h->fw, h->ticket[k]);
            h->ticket[k] = 0;
        }
}

/* A table seen for the first time: its name and columns from the registry
 * (the thread is idle meanwhile: it reads the list of tables). */
static bk_h5_table *new_table(bk_h5 *h, FILE *fp)
{
    settle_thread(h);
    if (h->ntab == h->captab) {
        int cap = h->captab ? 2 * h->captab : 8;
        bk_h5_table *nt = realloc(h->tab, (size_t)cap * sizeof *nt);
        if (!nt) {
            h->oom = 1;
            return NULL;
        }
        h->tab = nt;
        h->captab = cap;
    }
    bk_h5_table *t = &h->tab[h->ntab++];
    memset(t, 0, sizeof *t);
    t->fp = fp;
    const bk_table *rt = bk_tables_of(h->tables, fp);
    if (!rt || !rt->header)
        return t;                         /* (ncol 0: never mirrored) */
    snprintf(t->name, sizeof t->name, "%s", rt->name);
    char *dot = strstr(t->name, ".csv");
    if (dot)
        *dot = 0;
    int ncol = 1;
    for (const char *p = rt->header; *p && *p != '\n'; ++p)
        ncol += *p == ',';
    t->col = calloc((size_t)ncol, sizeof *t->col);
    if (!t->col) {
        h->oom = 1;
        return t;
    }
    const char *p = rt->header;
    for (int c = 0; c < ncol; ++c) {
        size_t len = strcspn(p, ",\n");
        snprintf(t->col[c].name, sizeof t->col[c].name, "%.*s", (int)(len < 63 ? len : 63), p);
        p += len + (p[len] == ',');
    }
    t->ncol = ncol;
    return t;
}

static void *sink_begin(void *ctx, FILE *fp)
{
    bk_h5 *h = ctx;
    if (!h->open)
        return NULL;
    bk_h5_table *t = NULL;
    for (int k = 0; k < h->ntab && !t; ++k)
        if (h->tab[k].fp == fp)
            t = &h->tab[k];
    if (!t && !(t = new_table(h, fp)))
        return NULL;
    if (t->ncol == 0 || table_room(h, t) != 0)
        return NULL;
    t->field = 0;
    t->row = t->buf[h->cur] + (size_t)t->nbuf[h->cur] * t->stride;   /* (stride 0 before the first row) */
    t->set = h->cur;
    return t;
}

/* Column c's type set (the first row's) and its offset in a row. */
static void settle(bk_h5_table *t, int c, int type)
{
    bk_h5_col *col = &t->col[c];
    if (col->type)
        return;
    col->type = type;
    col->off = c ? t->col[c - 1].off + cell_size(t->col[c - 1].type) : 0;
    if (c == t->ncol - 1)
        t->rowbytes = col->off + cell_size(type);
}

static void blank(bk_h5_table *t, int c)
{
    bk_h5_col *col = &t->col[c];
    unsigned char *b = t->row + col->off;
    if (col->type == 1) {
        double v = NAN;
        memcpy(b, &v, 8);
    } else if (col->type == 2)
        memset(b, 0, 8);
    else
        memset(b, 0, BK_H5_STR);
}

/* The cell of the row being given in the next column for a value of this
 * type; NULL (the cell blank) past the last column or when the column's type
 * (its first row's) is another. */
static unsigned char *cell(bk_h5_table *t, int type)
{
    if (t->field >= t->ncol)
        return NULL;
    const int c = t->field++;
    settle(t, c, type);
    if (t->col[c].type != type) {
        blank(t, c);
        return NULL;
    }
    return t->row + t->col[c].off;
}

static void sink_num(void *tab, double v)
{
    unsigned char *p = cell(tab, 1);
    if (p)
        memcpy(p, &v, 8);
}

static void sink_int(void *tab, long v)
{
    unsigned char *p = cell(tab, 2);
    int64_t w = v;
    if (p)
        memcpy(p, &w, 8);
}

static void sink_str(void *tab, const char *s)
{
    unsigned char *p = cell(tab, 3);
    if (p)
        strncpy((char *)p, s, BK_H5_STR);     /* null-padded, cut at 64 bytes */
}

static void sink_end(void *tab)
{
    bk_h5_table *t = tab;
    for (; t->field < t->ncol; ++t->field) {   /* a short row: the rest blank (no type yet: float64) */
        settle(t, t->field, 1);
        blank(t, t->field);
    }
    if (t->stride == 0)                        /* the first row: its layout is every row's */
        t->stride = t->rowbytes;
    t->nbuf[t->set]++;
}

/* ---- the thread: every HDF5 call ---- */

static void make_file(bk_h5 *h)
{
    const bk_model *m = h->m;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);       /* failures are reported by return codes, once */
    hid_t f = H5Fcreate(h->path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (f < 0) {
        fail(h, errno ? strerror(errno) : "HDF5 cannot create it");
        return;
    }
    h->file = f;
    const hsize_t nd = (hsize_t)m->ndof;
    hid_t tg = H5Gcreate2(f, "tables", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    h->tables_group = tg >= 0 ? tg : 0;
    int ok = tg >= 0 && attr_str(f, "scene", m->name) == 0 &&
             attr_str(f, "analysis", bk_analysis_name(m->analysis)) == 0 &&
             attr_str(f, "time_name", bk_model_in_time(m) ? "time" : "load_factor") == 0 &&
             attr_str(f, "units", "SI: m, kg, s, N, Pa, J; time in s; load factor 0 to 1; angles in rad "
                                  "unless a column says deg") == 0 &&
             attr_int(f, "format", 1) == 0 && attr_int(f, "ndof", m->ndof) == 0 && write_dofs(h) == 0 &&
             (h->ds_step = make_dataset(f, "step", H5T_STD_I64LE, 0, CHUNK_ROWS(8))) != 0 &&
             (h->ds_time = make_dataset(f, "time", H5T_IEEE_F64LE, 0, CHUNK_ROWS(8))) != 0 &&
             (h->ds_q = make_dataset(f, "q", H5T_IEEE_F64LE, nd, CHUNK_ROWS(8 * nd))) != 0 &&
             (!h->with_qd || (h->ds_qd = make_dataset(f, "qd", H5T_IEEE_F64LE, nd, CHUNK_ROWS(8 * nd))) != 0) &&
             H5Fflush(f, H5F_SCOPE_LOCAL) >= 0;
    if (!ok)
        fail(h, "HDF5 failed to lay out the file");
}

static void write_set(bk_h5 *h, int k)
{
    if (h->failed || !h->file)
        return;
    hsize_t nd = (hsize_t)h->ndof, n = (hsize_t)h->nbuf[k], have = (hsize_t)h->nstate;
    if (append(h->ds_step, H5T_NATIVE_LONG, have, n, 0, h->step[k]) != 0 ||
        append(h->ds_time, H5T_NATIVE_DOUBLE, have, n, 0, h->time[k]) != 0 ||
        append(h->ds_q, H5T_NATIVE_DOUBLE, have, n, nd, h->q[k]) != 0 ||
        (h->with_qd && append(h->ds_qd, H5T_NATIVE_DOUBLE, have, n, nd, h->qd[k]) != 0)) {
        fail(h, "HDF5 failed to append the states");
        return;
    }
    h->nstate += (long)n;
    hid_t s64 = str_type();
    if (s64 < 0) {
        fail(h, "HDF5 failed to make a string type");
        return;
    }
    for (int j = 0; j < h->ntab; ++j) {
        bk_h5_table *t = &h->tab[j];
        if (t->ncol == 0 || t->nbuf[k] == 0)
            continue;
        if (!t->ds) {
            /* the row's compound type: a member per column, named by the header */
            hid_t ct = H5Tcreate(H5T_COMPOUND, t->rowbytes);
            int ok = ct >= 0;
            for (int c = 0; c < t->ncol && ok; ++c)
                ok = H5Tinsert(ct, t->col[c].name, t->col[c].off,
                               t->col[c].type == 1 ? H5T_NATIVE_DOUBLE : t->col[c].type == 2 ? H5T_NATIVE_INT64 : s64)
                     >= 0;
            if (ok && (t->ds = make_dataset(h->tables_group, t->name, ct, 0, CHUNK_ROWS(t->rowbytes))) != 0)
                t->type = ct;
            else if (ct >= 0)
                H5Tclose(ct);
        }
        if (!t->ds || append(t->ds, t->type, (hsize_t)t->nrow, (hsize_t)t->nbuf[k], 0, t->buf[k]) != 0) {
            fail(h, "HDF5 failed to append a table's rows");
            break;
        }
        t->nrow += t->nbuf[k];
    }
    H5Tclose(s64);
    if (!h->failed && H5Fflush(h->file, H5F_SCOPE_LOCAL) < 0)
        fail(h, "HDF5 failed to flush the file");
}

static void close_file(bk_h5 *h)
{
    hid_t ids[] = {h->ds_step, h->ds_time, h->ds_q, h->ds_qd, h->tables_group};
    for (size_t k = 0; k < sizeof ids / sizeof *ids; ++k)
        if (ids[k] > 0)
            H5Oclose(ids[k]);
    for (int k = 0; k < h->ntab; ++k) {
        if (h->tab[k].ds > 0)
            H5Dclose(h->tab[k].ds);
        if (h->tab[k].type > 0)
            H5Tclose(h->tab[k].type);
    }
    if (h->file > 0 && H5Fclose(h->file) < 0)
        fail(h, "HDF5 failed to close the file");
    h->file = 0;
}

static void run_job(const void *arg, FILE *unused)
{
    (void)unused;
    const bk_h5_job *j = arg;
    if (j->what == 0)
        make_file(j->h);
    else if (j->what == 1)
        write_set(j->h, j->set);
    else
        close_file(j->h);
}

/* ---- the solve thread's side ---- */

int bk_h5_open(bk_h5 *h, const bk_model *m, const char *dir, const bk_tables *tables, FILE *err)
{
    memset(h, 0, sizeof *h);
    h->m = m;
    h->tables = tables;
    h->ndof = m->ndof;
    h->with_qd = bk_model_in_time(m);
    h->qd_step = -1;
    h->sink = (bk_rowsink){h, sink_begin, sink_num, sink_int, sink_str, sink_end};
    snprintf(h->path, sizeof h->path, "%s/results.h5", dir);
    size_t nd = (size_t)m->ndof;
    /* the states' buffers: 1 MB of rows per set (at least 16, at most BK_H5_ROWS) */
    h->cap = (int)fmax(16.0, fmin((double)BK_H5_ROWS, (double)(1 << 20) / (8.0 * (double)(nd + 1))));
    int ok = 1;
    for (int k = 0; k < 2; ++k) {
        h->step[k] = malloc((size_t)h->cap * sizeof *h->step[k]);
        h->time[k] = malloc((size_t)h->cap * sizeof *h->time[k]);
        h->q[k] = malloc((size_t)h->cap * nd * sizeof *h->q[k] + 1);
        h->qd[k] = h->with_qd ? malloc((size_t)h->cap * nd * sizeof *h->qd[k] + 1) : NULL;
        ok = ok && h->step[k] && h->time[k] && h->q[k] && (!h->with_qd || h->qd[k]);
    }
    h->qd_last = h->with_qd ? malloc(nd * sizeof *h->qd_last + 1) : NULL;
    if (!ok || (h->with_qd && !h->qd_last) || bk_filewriter_open(&h->fw, 1, 1) != 0) {
        fprintf(err, "error: %s: out of memory\n", h->path);
        h->open = 1;                          /* (bk_h5_close frees) */
        h->failed = 1;
        snprintf(h->failure, sizeof h->failure, "out of memory");
        return -1;
    }
    h->job[0] = (bk_h5_job){h, 0, 0};
    h->job[1] = (bk_h5_job){h, 1, 0};
    h->job[2] = (bk_h5_job){h, 1, 1};
    h->job[3] = (bk_h5_job){h, 2, 0};
    h->open = 1;
    bk_filewriter_call(&h->fw, run_job, &h->job[0]);
    return 0;
}

void bk_h5_velocity(bk_h5 *h, int step, const double *qd)
{
    if (!h->open || !h->with_qd || !qd)
        return;
    memcpy(h->qd_last, qd, (size_t)h->ndof * sizeof *qd);
    h->qd_step = step;
}

void bk_h5_state(bk_h5 *h, int step, double t, const double *q)
{
    if (!h->open)
        return;
    if (h->nbuf[h->cur] == h->cap)
        bk_h5_flush(h);
    const int s = h->cur;
    size_t nd = (size_t)h->ndof, k = (size_t)h->nbuf[s];
    h->step[s][k] = step;
    h->time[s][k] = t;
    memcpy(h->q[s] + k * nd, q, nd * sizeof *q);
    if (h->with_qd) {
        if (h->qd_step == step)
            memcpy(h->qd[s] + k * nd, h->qd_last, nd * sizeof *q);
        else
            for (size_t i = 0; i < nd; ++i)
                h->qd[s][k * nd + i] = NAN;
    }
    h->qd_step = -1;
    h->nbuf[s]++;
}

void bk_h5_flush(bk_h5 *h)
{
    if (!h->open)
        return;
    const int k = h->cur;
    h->ticket[k] = bk_filewriter_call(&h->fw, run_job, &h->job[1 + k]);
    h->cur = k ^ 1;
    if (h->ticket[h->cur] > 0)            /* the other set: written by now? */
        bk_filewriter_wait(&h->fw, h->ticket[h->cur]);
    h->ticket[h->cur] = 0;
    h->nbuf[h->cur] = 0;
    for (int j = 0; j < h->ntab; ++j)
        h->tab[j].nbuf[h->cur] = 0;
}

int bk_h5_close(bk_h5 *h, FILE *err)
{
    int rc = 0;
    if (h->open) {
        if (h->fw.ready) {
            bk_h5_flush(h);
            bk_filewriter_call(&h->fw, run_job, &h->job[3]);
        }
        bk_filewriter_close(&h->fw);      /* (drains: the file is closed) */
        h->open = 0;
        if (!h->failed && h->oom)
            fail(h, "out of memory for the rows (some are missing)");
        if (h->failed) {
            if (err)
                fprintf(err, "error: %s: cannot write: %s\n", h->path, h->failure);
            rc = -1;
        }
    }
    for (int k = 0; k < h->ntab; ++k) {
        free(h->tab[k].buf[0]);
        free(h->tab[k].buf[1]);
        free(h->tab[k].col);
    }
    free(h->tab);
    for (int k = 0; k < 2; ++k) {
        free(h->step[k]);
        free(h->time[k]);
        free(h->q[k]);
        free(h->qd[k]);
    }
    free(h->qd_last);
    const bk_tables *tables = h->tables;
    memset(h, 0, sizeof *h);
    h->tables = tables;
    return rc;
}
