/* vtk_collection.h -- a ParaView collection file (results.pvd, modes.pvd) of
 * the frames written so far (private to output/; vtk.c writes the frames). */
#ifndef BK_VTK_COLLECTION_H
#define BK_VTK_COLLECTION_H

#include <stddef.h>

/* DIR/NAME listing n files: entry k is file_fmt with id[k] (k + 1 when id is
 * NULL) at time value t[k] (k + 1 when t is NULL); written to DIR/NAME.tmp and
 * renamed, so a reader never sees half a collection.  0, or -1 with the path
 * that could not be written in failed[nfailed] and its errno in *err. */
int bk_vtk_collection(const char *dir, const char *name, int n, const double *t, const int *id, const char *file_fmt,
                      char *failed, size_t nfailed, int *err);

#endif
