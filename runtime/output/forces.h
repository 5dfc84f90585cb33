/* forces.h -- reactions at the constraints (reactions.csv, summary.json) and
 * section forces along the beams (sections.csv), per output step.
 *
 * Both come from generalized forces mapped to a force and a moment by the
 * virtual work of a rigid motion: a generalized force vector R does the work
 * F.du + M.dtheta on the rigid motion du + dtheta x (x - x0) of the DOFs it
 * acts on, with positions r moving by du + dtheta x (r - x0), position
 * gradients (ANCF slopes r_x, r_y, ...) turning, dg = dtheta x g, and
 * quaternions p = (w, v) turning, dp = 1/2 (0, dtheta) p.  So
 *   F = sum over positions R_r,   M = sum (r - x0) x R_r + sum g x R_g
 *       + sum 1/2 (w R_v - R_w v + v x R_v)   (quaternions),
 * the work-conjugate force and moment about x0.  Internal forces do no work on
 * rigid motions, so in statics the reactions balance the applied loads
 * (force and moment about any point) to the Newton tolerance.
 *
 * Reactions: per [[constraint]], R = f_int - f_ext (+ M q'' + damping +
 * rotary inertia in dynamics) at the DOFs it holds fixed, and -s G^T nu for its
 * linear constraints: the force and moment the support exerts on the
 * structure (on body a for a joint between bodies), about the constraint point
 * (a joint nonlinear in q: about its joint point on frame a, r_a + R_a c_a).
 * Section forces: at each element end, from the element's nodal forces
 * g_e = f_int,e (+ inertia, damping) - (the loads the element carries itself):
 * at the start node n = -F, m = -M (the action of the part before on the part
 * beyond is F, M), at the end node n = F, m = M, about the node; reported in
 * the orthonormal section frame there: N = n.e3, Q2 = n.e1, Q3 = n.e2,
 * T = m.e3, M2 = m.e1, M3 = m.e2 (n, m: the force and moment the part beyond
 * the section exerts on the part before it); sections.csv source "nodal".
 * After them, per element, the rows of the element's own stress resultants at
 * its sample points when its pair offers them (bk_pair.sections: generated,
 * the law's resultants of the rods, the integrated stress of the continuum
 * elements), in the same frame at each point, source the pair's label. */
#ifndef BK_FORCES_H
#define BK_FORCES_H

#include <stdio.h>

#include "base/csvrow.h"
#include "base/tables.h"

#include "assembly/system.h"

typedef struct bk_forces {
    const bk_model *m;
    FILE *reactions, *sections;   /* registered in the run's tables (tables.h), which close them */
    bk_rowqueue *rq;              /* not owned: the rows' queue to a writer thread (output.c), or NULL */
    int *fld;                     /* [4 ndof] global DOFs of the field of each DOF (-1 unused) */
    signed char *kind, *comp;     /* [ndof] 0 none, 1 position, 2 gradient, 3 quaternion; component */
    double *res, *fext, *buf;     /* [ndof], [ndof], element buffers */
    int have_fext;                /* fext holds the dead loads of unit load factor */
    int nrelem, *relem;           /* the elements with a DOF held by a reaction's constraint */
    double *rmass;                /* owned, dynamics: their mass matrices (maxdof^2 apart; bk_element_mass) */
    double (*last)[9];            /* [nreaction] force, moment, point at the last output step */
    int have_last;
    FILE *joints;                 /* joints.csv (joint_out.c), registered in the run's tables, or NULL */
    double *jstate;               /* owned: [4 nreaction] raw and unwrapped angle, peak |effort|, its time */
    int have_joints;
    double *sec;                  /* [12 nelem] N, Q2, Q3, T, M2, M3 at the start and the end of each
                                   * element at output step sec_step (for the ParaView frames) */
    int sec_step;
    int nthread;                  /* the section forces' threads (OpenMP's most; 1 serial) */
    double *sbuf;                 /* [nthread sbuf_stride] their element buffers (6 maxdof + 4 maxdof^2 each;
                                   * one slot when the section forces are serial: forces_impl.h) */
    double *sres;                 /* [nthread sres_stride] the output of a pair's sections() (9 maxsample each; idem) */
    size_t sbuf_stride, sres_stride;   /* doubles from one thread's slot to the next's (bigalloc.h) */
    double *spos;                 /* [(6 + 3 maxsample) nelem] the rows' points: the element's ends, its
                                   * sample points (sections.c) */
    int maxsample;                /* the most sample points of a pair's sections() (at least 1) */
    double *ssec;                 /* [6 maxsample nelem] N, Q2, Q3, T, M2, M3 of the element's own stress
                                   * resultants at its sample points, step sec_step (NaN: none) */
    /* The section forces handed to the rows' writer thread (sections.c): once
     * the rows queue runs there and the thread mirrors sections.csv, a small
     * model's section forces (fewer than BK_SECTIONS_PAR_MIN records) and
     * rows are made by that thread from a copy of the state, in one of
     * BK_SECTIONS_JOBS jobs; made here when that job is still in use (the
     * solve never waits for the thread). */
    struct bk_filewriter *sw;     /* that thread, or NULL: made here */
    struct bk_sections_job *sjob; /* owned: [BK_SECTIONS_JOBS] the states handed over */
    int sjobk;                    /* the next one */
    int scur;                     /* the job holding the values of sec_step (-1: sec, ssec, spos here) */
    int srows;                    /* rows of sections.csv recorded in the queue since its last hand-over */
    double *wbuf, *wsres;         /* owned: the thread's scratch (as sbuf, sres) */
} bk_forces;

/* Opens reactions.csv and, for a path (path: its kind, bk_options.h enum
 * bk_path_kind, from the analysis' plan, output.h), joints.csv and
 * sections.csv (when the model has reactions, joints and sections) in dir,
 * registered in ts.  0, or -1 with a message on err. */
int bk_forces_open(bk_forces *f, const bk_model *m, int path, const char *dir, bk_tables *ts, FILE *err);
/* Rows of reactions.csv and, when with_sections, of sections.csv for the
 * state q at x (time or load factor); qd, qdd: velocities and accelerations
 * (NULL in statics); nu: the constraint multipliers (NULL: unknown, the linear
 * constraints' reactions are NaN).  The residual at the held DOFs comes from
 * the elements that touch them only. */
void bk_forces_step(bk_forces *f, bk_system *s, int step, double x, const double *q, const double *qd,
                    const double *qdd, const double *nu, int with_sections);
/* The section forces of output step sec_step for its ParaView frame: their
 * arrays (12 values and 6 maxsample per element: sec, ssec) in *sec, *ssec.
 * by: the writer thread whose job makes the frame, or NULL (made here).  0:
 * they may be read now, until the next output step; 1: they are being made
 * by a job of `by` before the frame's (read them there), and the caller, once
 * it has handed the frame over, calls bk_forces_frame_handed with the ticket
 * of a call after it (they are kept until that returns). */
int bk_forces_frame_sections(bk_forces *f, const struct bk_filewriter *by, const double **sec, const double **ssec);
void bk_forces_frame_handed(bk_forces *f, long ticket);
/* The "reactions" and "joints" members of summary.json (with a trailing comma). */
void bk_forces_summary(const bk_forces *f, FILE *fp);
void bk_forces_close(bk_forces *f);

#endif
