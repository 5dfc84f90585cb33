/* beam_contact_frames.c -- the beam contact interaction's ParaView frames:
 * beam_contacts_NNNNNN.vtp with every frame and their collection
 * beam_contacts.pvd (see bc_frame). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/beam_contact_impl.h"
#include "base/clock.h"

typedef struct frame_pairs {
    const bc_work *w;
    const bk_model *m;
    FILE *f;
    int pass, n;                     /* pass 0: count; 1: positions; 2: forces; 3: normal forces; 4: sets */
} frame_pairs;

/* Each pair with a force gives two vertices: its closest point on the first
 * segment with the force there, and on the second with its opposite. */
static void frame_pair(void *ctx, seg_pair *sp)
{
    frame_pairs *fp = ctx;
    double fa[3], fn, ft;
    if (bc_pair_force(fp->w, fp->m, sp, fa, &fn, &ft) <= 0.0)
        return;
    for (int side = 0; side < 2; ++side) {
        const double u = side == 0 ? sp->sg : sp->tau, sign = side == 0 ? 1.0 : -1.0;
        const double *a = sp->pts[2 * side], *b = sp->pts[2 * side + 1];
        switch (fp->pass) {
        case 0:
            fp->n++;
            break;
        case 1:
            fprintf(fp->f, "%.9g %.9g %.9g\n", a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1]),
                    a[2] + u * (b[2] - a[2]));
            break;
        case 2:
            fprintf(fp->f, "%.9g %.9g %.9g\n", sign * fa[0], sign * fa[1], sign * fa[2]);
            break;
        case 3:
            fprintf(fp->f, "%.9g\n", fn);
            break;
        default:
            fprintf(fp->f, "%d\n", sp->c);
        }
    }
}

/* beam_contacts_NNNNNN.vtp: per pair of segments within the barrier's reach
 * or rubbing, its two closest points as vertices with the force on each beam
 * there (N, a vector for glyphs: equal and opposite), the normal force and
 * the contact set; beam_contacts.pvd lists them with their times (rewritten
 * at most once a second, and when the run ends). */
int bc_frame(void *self, const bk_system *s, const char *dir, int frame, double t, const double *q, FILE *err)
{
    bc_work *w = self;
    char path[1200];
    if (w->nframe == w->capframe) {
        const int cap = w->capframe ? 2 * w->capframe : 64;
        int *nf = realloc(w->frames, (size_t)cap * sizeof *nf);
        if (nf)
            w->frames = nf;
        double *nt = realloc(w->times, (size_t)cap * sizeof *nt);
        if (nt)
            w->times = nt;
        if (!nf || !nt)
            return -1;
        w->capframe = cap;
    }
    snprintf(w->dir, sizeof w->dir, "%s", dir);
    snprintf(path, sizeof path, "%s/beam_contacts_%06d.vtp", dir, frame);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(err, "error: %s: cannot write\n", path);
        return -1;
    }
    bc_points(w, s, q, 0, w->X);
    frame_pairs fp = {.w = w, .m = s->m, .f = f};
    bc_each_pair(w, s->m, frame_pair, NULL, &fp);
    fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "<PolyData>\n<Piece NumberOfPoints=\"%d\" NumberOfVerts=\"%d\">\n<Points>\n"
            "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n", fp.n, fp.n);
    static const char *const arrays[] = {
        "</DataArray>\n</Points>\n<PointData Vectors=\"force\" Scalars=\"normal_force\">\n"
        "<DataArray type=\"Float64\" Name=\"force\" NumberOfComponents=\"3\" format=\"ascii\">\n",
        "</DataArray>\n<DataArray type=\"Float64\" Name=\"normal_force\" format=\"ascii\">\n",
        "</DataArray>\n<DataArray type=\"Int32\" Name=\"set\" format=\"ascii\">\n"};
    for (fp.pass = 1; fp.pass <= 4; ++fp.pass) {
        bc_each_pair(w, s->m, frame_pair, NULL, &fp);
        if (fp.pass < 4)
            fputs(arrays[fp.pass - 1], f);
    }
    fputs("</DataArray>\n</PointData>\n<Verts>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n", f);
    for (int k = 0; k < fp.n; ++k)
        fprintf(f, "%d\n", k);
    fputs("</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n", f);
    for (int k = 0; k < fp.n; ++k)
        fprintf(f, "%d\n", k + 1);
    fputs("</DataArray>\n</Verts>\n</Piece>\n</PolyData>\n</VTKFile>\n", f);
    if (fclose(f) != 0) {
        fprintf(err, "error: %s: cannot write\n", path);
        return -1;
    }
    w->frames[w->nframe] = frame;
    w->times[w->nframe++] = t;
    if (w->nframe == 1 || bk_clock_s() - w->t_pvd >= 1.0)
        return bc_pvd(w);
    return 0;
}

int bc_pvd(bc_work *w)
{
    char path[1200];
    w->t_pvd = bk_clock_s();
    snprintf(path, sizeof path, "%s/beam_contacts.pvd", w->dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n", f);
    for (int k = 0; k < w->nframe; ++k)
        fprintf(f, "<DataSet timestep=\"%.17g\" file=\"beam_contacts_%06d.vtp\"/>\n", w->times[k], w->frames[k]);
    fputs("</Collection>\n</VTKFile>\n", f);
    return fclose(f) == 0 ? 0 : -1;
}
