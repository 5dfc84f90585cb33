/* beam_contact_frames.c -- the beam contact interaction's ParaView frames:
 * beam_contacts_NNNNNN.vtp with every frame and their collection
 * beam_contacts.pvd (see bc_frame). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/beam_contact_impl.h"

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

static void frame_visit(void *ctx, int pass, FILE *f, int *n)
{
    frame_pairs *fp = ctx;
    fp->pass = pass, fp->f = f, fp->n = 0;
    bc_each_pair(fp->w, fp->m, frame_pair, NULL, fp);
    if (pass == 0)
        *n = fp->n;
}

/* beam_contacts_NNNNNN.vtp: per pair of segments within the barrier's reach
 * or rubbing, its two closest points as vertices with the force on each beam
 * there (N, a vector for glyphs: equal and opposite), the normal force and
 * the contact set; beam_contacts.pvd lists them with their times
 * (base/pointframes.h). */
int bc_frame(void *self, const bk_system *s, const char *dir, int frame, double t, const double *q, FILE *err)
{
    bc_work *w = self;
    bc_points(w, s, q, 0, w->X);
    frame_pairs fp = {.w = w, .m = s->m};
    return bk_point_frames_write(&w->pf, dir, frame, t, frame_visit, &fp, err);
}
