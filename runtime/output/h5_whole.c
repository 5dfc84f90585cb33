/* h5_whole.c -- results.h5 of a run whose rows all came at its end, made in one
 * piece without the HDF5 library (h5_plain.h), with the same groups,
 * datasets, types and attributes as the library makes (h5_file.c); and the
 * /dofs arrays both take. */
#include "output/h5_impl.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "assembly/system.h"
#include "base/bigalloc.h"
#include "output/h5_plain.h"

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

void bk_h5_dofs_free(bk_h5_dofs *d)
{
    free(d->node);
    free(d->elem);
    free(d->beam);
    free(d->field);
    free(d->comp);
    memset(d, 0, sizeof *d);
}

int bk_h5_dofs_make(const bk_model *m, bk_h5_dofs *d)
{
    size_t nd = (size_t)m->ndof;
    d->node = malloc((nd + 1) * sizeof *d->node);
    d->elem = malloc((nd + 1) * sizeof *d->elem);
    d->beam = bk_big_calloc(nd + 1, BK_H5_STR);   /* (10,000 elements: 7.7 MB) */
    d->field = calloc(nd + 1, 8);
    d->comp = calloc(nd + 1, 2);
    if (!d->node || !d->elem || !d->beam || !d->field || !d->comp) {
        bk_h5_dofs_free(d);
        return -1;
    }
    int *node = d->node, *elem = d->elem;
    for (size_t k = 0; k < nd; ++k)
        node[k] = elem[k] = -1;
    /* each element's beam: that of its first section (one pass: a search per
     * element was quadratic, 36 ms of a 10,000-element run) */
    const char **beam_of = calloc((size_t)m->nelem + 1, sizeof *beam_of);
    if (!beam_of) {
        bk_h5_dofs_free(d);
        return -1;
    }
    for (int k = m->nsection - 1; k >= 0; --k)
        if (m->sections[k].elem >= 0 && m->sections[k].elem < m->nelem)
            beam_of[m->sections[k].elem] = m->sections[k].beam;
    int nnode = 0;
    for (int e = 0; e < m->nelem; ++e) {
        const bk_element *et = bk_elem_type(m, e);
        const char *bname = beam_of[e] ? beam_of[e] : "";
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
                int q = m->elems[e].dofs[et->field_dof[k] + c];
                if (elem[q] >= 0)
                    continue;
                elem[q] = e;
                node[q] = role == BK_FIELD_MULTIPLIER ? -1 : cur;
                /* (null-padded, cut to leave the terminator, as snprintf did:
                 * snprintf here took 25 ms of the writer thread at 10,000 elements) */
                strncpy(d->beam + (size_t)q * BK_H5_STR, bname, BK_H5_STR - 1);
                strncpy(d->field + (size_t)q * 8, field_name(role), 7);
                if (role != BK_FIELD_MULTIPLIER && c < (int)strlen(cn))
                    d->comp[(size_t)q * 2] = cn[c];
            }
        }
    }
    free(beam_of);
    return 0;
}

static const bk_h5p_type I32 = {BK_H5P_I32, 4, 0, 0, 0, 0, 0}, I64 = {BK_H5P_I64, 8, 0, 0, 0, 0, 0},
                         F64 = {BK_H5P_F64, 8, 0, 0, 0, 0, 0}, S64 = {BK_H5P_STR, BK_H5_STR, BK_H5P_NULLPAD, 0, 0, 0, 0},
                         S8 = {BK_H5P_STR, 8, BK_H5P_NULLTERM, 0, 0, 0, 0}, S2 = {BK_H5P_STR, 2, BK_H5P_NULLTERM, 0, 0, 0, 0};

/* /tables: a dataset per table with rows in set k; its address, 0 when out of
 * memory or a table has a column name twice (left to the library). */
static uint64_t tables_group(bk_h5p *p, const bk_h5 *h, int k)
{
    int n = 0, ok = 1;
    const char **names = calloc((size_t)h->ntab + 1, sizeof *names);
    uint64_t *addrs = calloc((size_t)h->ntab + 1, sizeof *addrs);
    ok = names && addrs;
    for (int j = 0; j < h->ntab && ok; ++j) {
        const bk_h5_table *t = h->tab[j];
        /* a table mirrored by the thread: all its rows are the thread's (h5.h) */
        const unsigned char *rows = t->threaded ? t->tbuf : t->buf[k];
        const long nrow = t->threaded ? t->ntb : t->nbuf[k];
        if (t->ncol == 0 || nrow == 0)
            continue;
        const char **mn = malloc((size_t)t->ncol * sizeof *mn);
        size_t *off = malloc((size_t)t->ncol * sizeof *off);
        const bk_h5p_type **mt = malloc((size_t)t->ncol * sizeof *mt);
        if ((ok = mn && off && mt)) {
            for (int c = 0; c < t->ncol; ++c) {
                for (int b = 0; b < c; ++b)       /* (a name twice: HDF5's refusal, reported by the library) */
                    if (strcmp(t->col[b].name, t->col[c].name) == 0)
                        ok = 0;
                mn[c] = t->col[c].name;
                off[c] = t->col[c].off;
                mt[c] = t->col[c].type == 1 ? &F64 : t->col[c].type == 2 ? &I64 : &S64;
            }
            bk_h5p_type row = {BK_H5P_COMPOUND, t->rowbytes, 0, t->ncol, mn, off, mt};
            uint64_t dims[1] = {(uint64_t)nrow};
            names[n] = t->name;
            if (ok)
                addrs[n++] = bk_h5p_dataset(p, &row, 1, dims, rows);
        }
        free(mn);
        free(off);
        free(mt);
    }
    uint64_t a = ok ? bk_h5p_group(p, n, names, addrs, 0, NULL) : 0;
    free(names);
    free(addrs);
    return a;
}

/* 0 written; -1 it could not be (h->failure); 1 not made this way (no
 * states, out of memory, a type too large for a message, a column name
 * twice): the library makes it (or reports why it cannot). */
int bk_h5_write_whole(bk_h5 *h, int k)
{
    const bk_model *m = h->m;
    const uint64_t n = (uint64_t)h->nbuf[k], nd = (uint64_t)h->ndof;
    if (n == 0)
        return 1;                     /* (no states: the library's empty extensible datasets) */
    bk_h5_dofs d;
    if (bk_h5_dofs_make(m, &d) != 0)
        return 1;
    bk_h5p p;
    bk_h5p_begin(&p);
    uint64_t one[1] = {nd}, rows[1] = {n}, mat[2] = {n, nd}, da[5], ra[6] = {0};
    const char *dn[] = {"node", "element", "beam", "field", "component"};
    da[0] = bk_h5p_dataset(&p, &I32, 1, one, d.node);
    da[1] = bk_h5p_dataset(&p, &I32, 1, one, d.elem);
    da[2] = bk_h5p_dataset(&p, &S64, 1, one, d.beam);
    da[3] = bk_h5p_dataset(&p, &S8, 1, one, d.field);
    da[4] = bk_h5p_dataset(&p, &S2, 1, one, d.comp);
    const char *rn[] = {"tables", "dofs", "step", "time", "q", "qd"};
    ra[0] = tables_group(&p, h, k);
    ra[1] = bk_h5p_group(&p, 5, dn, da, 0, NULL);
    ra[2] = bk_h5p_dataset(&p, &I64, 1, rows, h->step[k]);
    ra[3] = bk_h5p_dataset(&p, &F64, 1, rows, h->time[k]);
    ra[4] = bk_h5p_dataset(&p, &F64, 2, mat, h->q[k]);
    if (h->with_qd)
        ra[5] = bk_h5p_dataset(&p, &F64, 2, mat, h->qd[k]);
    const bk_h5p_attr at[] = {{"scene", m->name, 0},
                              {"analysis", bk_analysis_name(m->analysis), 0},
                              {"time_name", h->with_qd ? "time" : "load_factor", 0},
                              {"units", BK_H5_UNITS, 0},
                              {"format", NULL, 1},
                              {"ndof", NULL, m->ndof}};
    uint64_t root = bk_h5p_group(&p, h->with_qd ? 6 : 5, rn, ra, 6, at);
    if (ra[0] == 0 || bk_h5p_finish(&p, root) != 0) {
        bk_h5p_free(&p);
        bk_h5_dofs_free(&d);
        return 1;                     /* (the library makes it) */
    }
    int fd = open(h->path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    int e = fd < 0 ? errno : bk_h5p_write(&p, fd);
    if (fd >= 0 && close(fd) != 0 && !e)
        e = errno;
    bk_h5p_free(&p);
    bk_h5_dofs_free(&d);              /* (written from in place: bk_h5p_write) */
    if (e && !h->failed) {
        h->failed = 1;
        snprintf(h->failure, sizeof h->failure, "%s", strerror(e));
    }
    return e ? -1 : 0;
}
