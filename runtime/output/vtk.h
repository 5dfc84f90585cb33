/* vtk.h -- ParaView output (step_NNNNNN.vtu frames and results.pvd; modal:
 * mode_NN.vtu and modes.pvd); see vtk.c. */
#ifndef BK_VTK_H
#define BK_VTK_H

#include <stdio.h>

#include "base/filewriter.h"
#include "model/model.h"

struct bk_system;
struct bk_forces;

typedef struct bk_vtk {
    const bk_model *m;
    char dir[1024];
    int every;               /* a frame every n-th call; 0: off */
    int calls;
    int nframe, cap;
    double *times;           /* owned */
    int *frames;             /* owned */
    int nmode;               /* mode files written (modes 1..nmode) */
    int pvd_stale;           /* results.pvd lacks frames written since its last write */
    double t_pvd;            /* wall clock of that write (s) */
    struct bk_forces *forces;   /* not owned, or NULL: the section forces per element end and the
                              * elements' own stress resultants at their sample points of its
                              * sec_step (forces.h bk_forces_frame_sections) */
    int maxsample;           /* sample points per element in those */
    double *ref;             /* owned: the frame points of the reference state m->q0 (3 per point) */
    double *pts;             /* owned: a frame's points (scratch, 3 per point) */
    unsigned char *topo;     /* owned: the cells block every frame appends (topology, in bk_vtk_open) */
    size_t ntopo;            /* its size in bytes */
    long npts, ncell, nconn; /* points, cells and connectivity entries of every frame */
    size_t frame_bytes;      /* the largest frame file (header allowance included) */
    char *iobuf;             /* owned, or NULL until the first frame written here: its
                              * stdio buffer (BK_VTK_IOBUF bytes: a few large writes).  On
                              * the heap: on the stack its 64 kB were 16 fresh pages at
                              * the first frame, a page fault each (10 us apiece on a
                              * virtual machine with shadow page tables: half the frame's
                              * time in a small run) */
    int written;             /* frame files so far (step and mode frames) */
    int background, tried_background;   /* 1: frames go to fw, written by its thread */
    int expected;            /* frames the run will write when known in advance (dynamics), else 0 */
    double end;              /* the path variable at the run's end (progress t / end; 0: unknown) */
    int modes;               /* mode frames the run writes (0: none) */
    bk_filewriter fw;        /* owned when background and no ext */
    bk_filewriter *ext;      /* not owned, or NULL: a writer thread to share (buffers of at least
                              * frame_bytes; the output's: results.h5's) instead of one of its own */
    bk_filewriter *wp;       /* the frames' writer when background: &fw or ext */
    struct bk_vtk_job *jobs; /* owned when background: per buffer of fw, the inputs of the
                              * frame its thread makes (NULL: frames are written here) */
    int failed;              /* a frame or collection written here could not be: 1, 2 once reported */
    int errno_;              /*   its errno */
    char failed_path[1216];  /*   its path (a collection's temporary name included) */
} bk_vtk;

/* From a run's second frame on (its third when its length is unknown, its
 * first when it is known to write many),
 * frames up to this size are made and written by a background thread
 * (filewriter.h: BK_FILEWRITER_BUFFERS buffers of a frame each; the frames'
 * inputs are copied for it; a frame that finds every one still taken is
 * written directly), larger
 * ones directly. */
#define BK_VTK_BACKGROUND_MAX ((size_t)2 << 20)

/* The buffer of a frame written on the solve thread (a few large writes). */
#define BK_VTK_IOBUF ((size_t)1 << 16)

/* capacity: room for this many frames (the arrays grow if exceeded);
 * expected: the frames the run will write when known in advance, else 0. */
int bk_vtk_open(bk_vtk *v, const bk_model *m, const char *dir, int every, int capacity, int expected);
/* Writes a frame for every `every`-th call (step < 0: write unconditionally,
 * frame number -step). */
int bk_vtk_frame(bk_vtk *v, const struct bk_system *s, int step, double t, const double *q);
/* Rewrites results.pvd when frames were written since its last write (frames
 * rewrite it at most every BK_PVD_INTERVAL s of wall time), after every frame
 * handed to the background writer is on disk; 0, or -1 on a write error (of
 * the collection or of a frame: bk_vtk_failed says which). */
int bk_vtk_flush(bk_vtk *v);
/* Waits for the frames being written; 0, or -1 when a frame or collection
 * could not be written (by the background thread or here): "error: PATH:
 * cannot write: REASON" on err for the first (once). */
int bk_vtk_finish(bk_vtk *v, FILE *err);
void bk_vtk_close(bk_vtk *v);

/* Number of points of every frame of the model. */
long bk_vtk_npoints(const bk_model *m);
/* For the mode phi given as qp = q + eps phi, qm = q - eps phi: the largest
 * linearized point translation |dx/d(eps)| over the frame points, and the
 * largest motion of a section point relative to its centreline point per unit
 * distance between them (a section rotation, in rad, or a section strain). */
void bk_vtk_mode_extent(const bk_model *m, const double *qp, const double *qm, double eps, double *translation,
                        double *rotation);
/* Writes mode_NN.vtu of mode `mode` (1, 2, ...) and rewrites modes.pvd: the
 * points of q displaced by scale * shape, shape = the linearized point motion of
 * qp/qm divided by norm (so its largest translation is 1 when norm is the
 * translation extent); field data TIME and MODE (the mode number), the nval
 * values under their names in capitals, MODE_SCALE.  Nothing when ParaView
 * output is off. */
int bk_vtk_mode(bk_vtk *v, int mode, int nval, const char *const *names, const double *vals, double scale,
                double norm, const double *q, const double *qp, const double *qm, double eps);

#endif
