/* overlap.h -- do parts of the beams pass through one another (or a beam
 * through itself) although nothing keeps them apart?  Without [[beam_contact]]
 * the solver lets a tendon finger curl past a full turn through its own body;
 * this check flags such a state (checks.c calls it at every output state).
 *
 * Each element's centreline is sampled at BK_OVERLAP_SEG + 1 points; a
 * broad phase (assembly/contact_broad.h: a spatial hash of the boxes, inflated
 * by the sections' half-heights, of runs of consecutive elements no longer
 * than their section) finds the candidate element pairs,
 * and two segments overlap when their distance is below the sum of their
 * half-heights r_a + r_b (a rectangle's h / 2, a circle's radius: the default
 * radius of [[beam_contact]]).  Elements that were within 2 (r_a + r_b) of
 * each other in the reference configuration are neighbours (along a beam, the
 * links at a joint, stacked layers) and not compared: links that fold about a
 * joint overlap near it in a model whose links share a plane; for that reason
 * two beams joined by constraints (directly or through others: the links of
 * a mechanism, gen/scene/build.py joined_groups) are not compared with each
 * other at all, only each with itself and with the other beams.  The first overlap is reported once
 * (beams, arc lengths, distance, time or load factor).  Off when an
 * interaction keeps the sections apart (beam contact).  Cost: linear in the elements per check, plus the sort of the
 * broad phase. */
#ifndef BK_OVERLAP_H
#define BK_OVERLAP_H

#include <stdio.h>

#include "assembly/contact_broad.h"
#include "model/model.h"
#include "output/run_info.h"

#define BK_OVERLAP_SEG 4

typedef struct bk_overlap {
    int n;                   /* elements sampled (model sections), 0: the check is off */
    int reported;
    double *ref, *cur;       /* [n][BK_OVERLAP_SEG + 1][3] reference and current samples (owned) */
    bk_box *box;             /* [n] the elements' boxes (owned) */
    int nchunk, *chunk;      /* runs of elements: chunk c is chunk[c] .. chunk[c + 1] - 1 (owned) */
    bk_box *cbox;            /* [nchunk] their boxes, for the broad phase (owned) */
    int *pairs, cap;         /* the broad phase's pairs (owned) */
    int *beam;               /* [n] the element's beam as a number (equal names, equal numbers; owned) */
    double *crmin;           /* [nchunk] the least half-height in chunk c (owned) */
    unsigned char *cord;     /* [nchunk] 1: its elements' s0 and s1 never decrease (owned) */
} bk_overlap;

/* Off (n = 0) for a system with an interaction that keeps the sections apart
 * (beam contact: interaction.h keeps_apart) or fewer than two elements.
 * Returns 0, or -1 when out of memory. */
struct bk_system;
int bk_overlap_init(bk_overlap *o, const struct bk_system *s);
void bk_overlap_free(bk_overlap *o);

/* Checks the state q at load factor / time t (`what`: "load factor", "t ="):
 * on the first overlap a warning on the console and in summary.json. */
void bk_overlap_check(bk_overlap *o, const bk_model *m, const double *q, const char *what, double t,
                      bk_run_info *info, FILE *console);

#endif
