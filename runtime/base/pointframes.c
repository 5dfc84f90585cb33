/* pointframes.c -- ParaView point-cloud frames and their collection (see
 * pointframes.h). */
#include "base/pointframes.h"

#include <stdlib.h>

#include "base/clock.h"

int bk_point_frames_write(bk_point_frames *pf, const char *dir, int frame, double t, bk_point_visit visit, void *ctx,
                          FILE *err)
{
    char path[1200];
    if (pf->nframe == pf->cap) {
        const int cap = pf->cap ? 2 * pf->cap : 64;
        int *nf = realloc(pf->frames, (size_t)cap * sizeof *nf);
        if (nf)
            pf->frames = nf;
        double *nt = realloc(pf->times, (size_t)cap * sizeof *nt);
        if (nt)
            pf->times = nt;
        if (!nf || !nt)
            return -1;
        pf->cap = cap;
    }
    snprintf(pf->dir, sizeof pf->dir, "%s", dir);
    snprintf(path, sizeof path, "%s/%s_%06d.vtp", dir, pf->stem, frame);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(err, "error: %s: cannot write\n", path);
        return -1;
    }
    int n = 0;
    visit(ctx, 0, f, &n);
    fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "<PolyData>\n<Piece NumberOfPoints=\"%d\" NumberOfVerts=\"%d\">\n<Points>\n"
            "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n", n, n);
    static const char *const arrays[] = {
        "</DataArray>\n</Points>\n<PointData Vectors=\"force\" Scalars=\"normal_force\">\n"
        "<DataArray type=\"Float64\" Name=\"force\" NumberOfComponents=\"3\" format=\"ascii\">\n",
        "</DataArray>\n<DataArray type=\"Float64\" Name=\"normal_force\" format=\"ascii\">\n",
        "</DataArray>\n<DataArray type=\"Int32\" Name=\"set\" format=\"ascii\">\n"};
    for (int pass = 1; pass <= 4; ++pass) {
        visit(ctx, pass, f, &n);
        if (pass < 4)
            fputs(arrays[pass - 1], f);
    }
    fputs("</DataArray>\n</PointData>\n<Verts>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n", f);
    for (int k = 0; k < n; ++k)
        fprintf(f, "%d\n", k);
    fputs("</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n", f);
    for (int k = 0; k < n; ++k)
        fprintf(f, "%d\n", k + 1);
    fputs("</DataArray>\n</Verts>\n</Piece>\n</PolyData>\n</VTKFile>\n", f);
    if (fclose(f) != 0) {
        fprintf(err, "error: %s: cannot write\n", path);
        return -1;
    }
    pf->frames[pf->nframe] = frame;
    pf->times[pf->nframe++] = t;
    if (pf->nframe == 1 || bk_clock_s() - pf->t_pvd >= 1.0)
        return bk_point_frames_pvd(pf);
    return 0;
}

int bk_point_frames_pvd(bk_point_frames *pf)
{
    char path[1200];
    pf->t_pvd = bk_clock_s();
    snprintf(path, sizeof path, "%s/%s.pvd", pf->dir, pf->stem);
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n", f);
    for (int k = 0; k < pf->nframe; ++k)
        fprintf(f, "<DataSet timestep=\"%.17g\" file=\"%s_%06d.vtp\"/>\n", pf->times[k], pf->stem, pf->frames[k]);
    fputs("</Collection>\n</VTKFile>\n", f);
    return fclose(f) == 0 ? 0 : -1;
}

void bk_point_frames_free(bk_point_frames *pf)
{
    if (pf->nframe > 0)
        bk_point_frames_pvd(pf);         /* the collection complete (a failure was reported with the frames) */
    free(pf->frames);
    free(pf->times);
    pf->frames = NULL;
    pf->times = NULL;
    pf->nframe = pf->cap = 0;
}
