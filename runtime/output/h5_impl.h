/* h5_impl.h -- what the two halves of results.h5 share: h5.c (the solve
 * thread: rows kept in two sets of buffers) and h5_file.c (the HDF5 thread:
 * every HDF5 call). */
#ifndef BK_H5_IMPL_H
#define BK_H5_IMPL_H

#include "output/h5.h"

/* A job of the HDF5 thread (bk_filewriter_make): arg a bk_h5_job. */
void bk_h5_run_job(const void *arg, FILE *unused);

#endif
