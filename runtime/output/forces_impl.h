/* forces_impl.h -- what the reactions (forces.c) and the section forces
 * (sections.c) share (private to output/): the kinds of DOF and the force and
 * moment of a generalized force at a DOF, and the row-by-row product of the
 * element matrices. */
#ifndef BK_FORCES_IMPL_H
#define BK_FORCES_IMPL_H

#include "output/forces.h"

enum { K_NONE = 0, K_POS = 1, K_GRAD = 2, K_QUAT = 3 };

/* Section records from which the section forces are computed on the threads
 * (bk_forces_sections); fewer: serially, in the first thread slot only. */
#define BK_SECTIONS_PAR_MIN 256

/* A state handed to the rows' writer thread for its section forces and rows
 * (forces.h sw; sections.c): BK_SECTIONS_JOBS of them in turn, each the
 * caller's again once its last call has returned (the job's, or one after a
 * frame that reads its values there). */
#define BK_SECTIONS_JOBS 4
typedef struct bk_sections_job {
    bk_forces *f;
    bk_system *s;            /* (the thread reads its model, maxdof and interactions only) */
    int step;
    double x;
    double *q, *qd, *qdd;    /* owned: [ndof] each (qd, qdd: dynamics) */
    int dyn;                 /* 1: qd and qdd hold the state's (dynamics) */
    double *sec, *ssec, *spos;   /* owned: the values made there (as f->sec, f->ssec, f->spos) */
    long ticket;             /* the last call using it (0: none) */
} bk_sections_job;
/* Frees f's jobs and the thread's scratch (sections.c; the thread is done with them). */
void bk_forces_sections_free(bk_forces *f);

/* F, M (about x0) of the generalized force value r at global DOF d (forces.h). */
void bk_forces_map_dof(const bk_forces *f, const double *q, int d, double r, const double *x0, double *F, double *M);
/* y[i] (+)= sum_j A[i n + j] v[j] over the n rows of A (n x n, row-major),
 * from y[i] or, with from_zero, from 0 (forces.c). */
void bk_forces_rows_times(int n, const double *restrict A, const double *restrict v, double *restrict y,
                          int from_zero);
/* Rows of sections.csv of one output step (sections.c). */
void bk_forces_sections(bk_forces *f, bk_system *s, int step, double x, const double *q, const double *qd,
                        const double *qdd);

/* joints.csv (joint_out.c): opened when the model has a joint with an axis
 * (called for an analysis whose states form a path; 0, or -1 with a message
 * on err); a row per such joint at each output step
 * after the reactions (f->last); the "joints" member of summary.json (peak
 * |effort| and its time, with a trailing comma). */
int bk_joints_open(bk_forces *f, const bk_model *m, const char *dir, bk_tables *ts, FILE *err);
void bk_joints_step(bk_forces *f, int step, double x, const double *q, const double *qd);
void bk_joints_summary(const bk_forces *f, FILE *fp);

#endif
