/* system_impl.h -- what the assembly's files share (private to assembly/):
 * the OpenMP switch, the serial and partition limits, the lane-kernel test
 * and the joint coordinates' equations and values. */
#ifndef BK_SYSTEM_IMPL_H
#define BK_SYSTEM_IMPL_H

#include "assembly/system.h"

#ifdef _OPENMP
#include <omp.h>
#define BK_OMP(...) _Pragma(#__VA_ARGS__)
#else
#define BK_OMP(...)
#endif


/* Smaller models are evaluated by one thread: for them the fork/join and the
 * barrier cost more than they save (and much more on a loaded machine, where
 * a descheduled thread holds up the barrier: a 32-element gef pendulum spent
 * half its time spinning in libgomp with 2 threads on 2 busy cores). */
#define BK_PAR_MIN_ELEMS 256
/* Most parts of the parallel assembly (one per thread; owner codes of a byte). */
#define BK_MAX_PARTS 250
/* Parts per thread: the threads take parts as they finish the last (dynamic
 * schedule), so a thread whose core is busy with another process does fewer
 * of them instead of holding up the others. */
#define BK_PARTS_PER_THREAD 8


/* A pair whose elements are evaluated BK_LANES per call (bk_kernel.h, "Lane kernels"). */
static inline int lane_pair(const bk_pair *p)
{
    return p->force_lanes && p->force_tangent_lanes && p->nparam <= BK_MAT_MAXPARAM;
}

static inline int joint_eq(const bk_system *s, const bk_nlcon *c, int k)
{
    return c->dof[k] >= 0 ? s->eq[c->dof[k]] : -1;
}

/* Joint coordinates x[BK_JOINT_NX] from q (constants where dof < 0; with
 * rates, 0 there). */
static inline void joint_x(const bk_nlcon *c, const double *q, int rates, double *x)
{
    for (int k = 0; k < BK_JOINT_NX; ++k)
        x[k] = c->dof[k] >= 0 ? q[c->dof[k]] : rates ? 0.0 : c->x0[k];
}

/* The CSC index of entry (row, col) of the pattern, or -1 when the pattern
 * has none (a bisection over the column's sorted rows). */
static inline int bk_find_slot(const bk_system *s, int row, int col)
{
    int lo = s->Ap[col], hi = s->Ap[col + 1];
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (s->Ai[mid] < row)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < s->Ap[col + 1] && s->Ai[lo] == row ? lo : -1;
}

/* The pattern and its scatter maps (pattern.c): made from the model and
 * s->couple; freed (and the pointers cleared). */
int bk_make_pattern(bk_system *s);
void bk_free_pattern(bk_system *s);
/* Frees the elements-at-each-DOF lists (dinc_ptr, dinc) once bk_make_parts
 * has used them: 24 MB at 100,000 elements, not kept for the run. */
void bk_free_incidence(bk_system *s);

/* Splits the element groups into parts for the parallel assembly (partition.c;
 * system.h: npart, part, pel, pmap, stage, sh_*).  Returns 0, or -1 when out
 * of memory. */
int bk_make_parts(bk_system *s);
/* Frees what bk_make_parts made (the pointers cleared, no parts shared). */
void bk_free_parts(bk_system *s);

#endif
