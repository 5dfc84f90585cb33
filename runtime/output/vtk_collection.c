/* vtk_collection.c -- a ParaView collection file (see vtk_collection.h). */
#include "output/vtk_collection.h"

#include <errno.h>
#include <stdio.h>

static int failure(const char *path, char *failed, size_t nfailed, int *err)
{
    *err = errno;
    snprintf(failed, nfailed, "%s", path);
    return -1;
}

int bk_vtk_collection(const char *dir, const char *name, int n, const double *t, const int *id, const char *file_fmt,
                      char *failed, size_t nfailed, int *err)
{
    char path[1200], tmp[1210], file[64];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *fp = fopen(tmp, "w");
    if (!fp)
        return failure(tmp, failed, nfailed, err);
    fprintf(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n");
    for (int k = 0; k < n; ++k) {
        snprintf(file, sizeof file, file_fmt, id ? id[k] : k + 1);
        fprintf(fp, "    <DataSet timestep=\"%.17g\" part=\"0\" file=\"%s\"/>\n", t ? t[k] : (double)(k + 1),
                file);
    }
    fprintf(fp, "  </Collection>\n</VTKFile>\n");
    if (fclose(fp) != 0)
        return failure(tmp, failed, nfailed, err);
    if (rename(tmp, path) != 0)
        return failure(path, failed, nfailed, err);
    return 0;
}
