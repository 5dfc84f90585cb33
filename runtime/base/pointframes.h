/* pointframes.h -- a time series of point clouds for ParaView: one
 * STEM_NNNNNN.vtp per frame (the points as vertices with a force vector, a
 * normal force and a set number) and STEM.pvd, the collection of the frames so
 * far (rewritten at most once a second, and by bk_point_frames_free).  The
 * caller's visitor writes its points once per pass:
 *   pass 0 counts them into *n; pass 1 writes each position "x y z\n"; pass 2
 *   each force "fx fy fz\n"; pass 3 each normal force; pass 4 each set number.
 * Used by the contact interactions (assembly/contact_output.c,
 * beam_contact_frames.c). */
#ifndef BK_POINTFRAMES_H
#define BK_POINTFRAMES_H

#include <stdio.h>

typedef struct bk_point_frames {
    const char *stem;                /* the files' name before _NNNNNN.vtp / .pvd (not owned) */
    char dir[1024];                  /* where they are */
    int nframe, cap;                 /* frames written, room for */
    int *frames;                     /* [cap] their numbers */
    double *times;                   /* [cap] their times or load factors */
    double t_pvd;                    /* wall clock of the last STEM.pvd */
} bk_point_frames;

typedef void (*bk_point_visit)(void *ctx, int pass, FILE *f, int *n);

/* Frame number `frame` at time (or load factor) t in dir: 0, or -1 with a
 * message on err. */
int bk_point_frames_write(bk_point_frames *pf, const char *dir, int frame, double t, bk_point_visit visit, void *ctx,
                          FILE *err);
/* STEM.pvd of the frames so far: 0, or -1. */
int bk_point_frames_pvd(bk_point_frames *pf);
/* Completes the collection (when frames were written) and frees the lists. */
void bk_point_frames_free(bk_point_frames *pf);

#endif
