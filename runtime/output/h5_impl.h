/* h5_impl.h -- what the parts of results.h5 share: h5.c (the solve thread:
 * rows kept in two sets of buffers), h5_file.c (the HDF5 thread: every HDF5
 * call) and h5_whole.c (a short run's file in one piece, without HDF5). */
#ifndef BK_H5_IMPL_H
#define BK_H5_IMPL_H

#include "output/h5.h"

/* A job of the HDF5 thread (bk_filewriter_make): arg a bk_h5_job. */
void bk_h5_run_job(const void *arg, FILE *unused);

/* The root group's attribute "units". */
#define BK_H5_UNITS "SI: m, kg, s, N, Pa, J; time in s; load factor 0 to 1; angles in rad unless a column says deg"

/* /dofs: per DOF its node (numbered in the order the elements first reach
 * them; a node's fields run until a field role repeats; -1 for multipliers),
 * beam (sections records; "" for bodies outside a beam; BK_H5_STR bytes),
 * first element, field (8 bytes) and component (2 bytes). */
typedef struct bk_h5_dofs {
    int *node, *elem;         /* owned: [ndof] */
    char *beam, *field, *comp;   /* owned: [ndof] strings of BK_H5_STR, 8, 2 bytes */
} bk_h5_dofs;
int bk_h5_dofs_make(const bk_model *m, bk_h5_dofs *d);   /* 0, or -1 out of memory (d freed) */
void bk_h5_dofs_free(bk_h5_dofs *d);

/* The thread's rows of t (h5.h bk_h5_table.tbuf) appended to its dataset, the
 * file made first if no set was handed over yet (h->tlib); on the thread, at a
 * row's start (none is being given).  Afterwards t holds none: written, or
 * dropped after a failure (h->failed, reported by bk_h5_close). */
void bk_h5_write_thread_rows(bk_h5 *h, bk_h5_table *t);

/* The whole file from set k when every row is in it (no set handed to the
 * thread before): 0 written, -1 it could not be (h->failed, failure), 1 left
 * to the library (no states, out of memory, a compound too large, a column
 * name twice). */
int bk_h5_write_whole(bk_h5 *h, int k);

#endif
