/* vtk.h -- ParaView output (step_NNNNNN.vtu frames and results.pvd); see vtk.c. */
#ifndef BK_VTK_H
#define BK_VTK_H

#include "model.h"

struct bk_system;

typedef struct bk_vtk {
    const bk_model *m;
    char dir[1024];
    int every;               /* a frame every n-th call; 0: off */
    int calls;
    int nframe, cap;
    double *times;           /* owned */
    int *frames;             /* owned */
} bk_vtk;

/* capacity: expected number of frames (the arrays grow if exceeded). */
int bk_vtk_open(bk_vtk *v, const bk_model *m, const char *dir, int every, int capacity);
/* Writes a frame for every `every`-th call (step < 0: write unconditionally,
 * frame number -step). */
int bk_vtk_frame(bk_vtk *v, const struct bk_system *s, int step, double t, const double *q);
void bk_vtk_close(bk_vtk *v);

#endif
