/* contact_broad.h -- the broad phase of beam-to-beam contact: which of n
 * axis-aligned boxes overlap, by a spatial hash (a uniform grid whose cell is
 * the largest box's extent, so that a box covers at most 2 x 2 x 2 cells):
 * the boxes' cells are sorted by key, and only boxes sharing a cell are
 * compared.  O(n log n) for boxes of similar size (the sort); no loop over all
 * pairs. */
#ifndef BK_CONTACT_BROAD_H
#define BK_CONTACT_BROAD_H

typedef struct bk_box {
    double lo[3], hi[3];
} bk_box;

/* The pairs (i < j) of the n boxes that overlap (touching counts), sorted,
 * without repeats, into (*pairs)[2 k], (*pairs)[2 k + 1] (grown with realloc;
 * *cap pairs held).  Returns their count, or -1 when out of memory. */
int bk_broad_pairs(const bk_box *box, int n, int **pairs, int *cap);

#endif
