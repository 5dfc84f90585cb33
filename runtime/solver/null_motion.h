/* null_motion.h -- names the motion a singular Newton matrix leaves free: an
 * approximate null vector by inverse iteration on the matrix with its free
 * diagonal shifted by 1e-9 of its largest entry, read as the nodes that move
 * and how (translation along a direction, rotation about an axis, a section
 * vector changing), or as constraint rows that are redundant. */
#ifndef BK_NULL_MOTION_H
#define BK_NULL_MOTION_H

#include <stddef.h>

#include "assembly/system.h"
#include "linalg/linsolve.h"

/* Into buf (size n): "free motion: ..." naming at most three nodes; ls is
 * refactored (its factors are lost); Ax is not changed.  Returns 0, or -1 when
 * it could not tell (out of memory, the shifted matrix singular too: buf
 * empty). */
int bk_null_motion(const bk_system *s, const double *Ax, const double *q, bk_linsolver *ls, char *buf, size_t n);

#endif
