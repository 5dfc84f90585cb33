/* bigalloc.h -- allocation of the arrays that grow with the model (the Newton
 * matrix's values and pattern, the band factors' storage, the output's buffers
 * of a frame or a step's rows), and the layout of per-thread scratch.
 *
 * Each is malloc, calloc or realloc, after which the kernel is asked
 * (madvise MADV_HUGEPAGE, Linux) to back the block's whole 2 MiB pages with
 * transparent huge pages when they are first touched.  The first touch of a
 * 4 kB page is a page fault; in a virtual machine a fault can cost 10 us (11
 * us measured on one), and a 10,000-element static run took 68,500 faults
 * without the advice and 31,000 with it.  A 2 MiB page takes one fault for
 * 512 small ones.  Blocks below BK_BIG_BYTES, and systems without the advice (or
 * with transparent huge pages off: madvise fails and is ignored), get plain
 * pages; the contents and results are the same either way.
 *
 * Sizes and directions:
 *   bk_big_malloc   in: bytes.  Out: a block as malloc's (NULL when out of memory).
 *   bk_big_calloc   in: n, size.  Out: a zeroed block of n * size bytes, as calloc's.
 *   bk_big_realloc  in: p (NULL or a block from any of these or malloc), bytes.
 *                   Out: as realloc's; the advice covers the new block.
 *   bk_big_advise   in: p (NULL or a block of `bytes` from aligned_alloc, say,
 *                   not yet touched).  Out: p, with the advice given.
 * Every block is freed with free().
 *
 * Per-thread scratch (one slot a thread in one array, slot t at t * stride):
 *   bk_thread_stride  in: n (doubles a slot needs), nthreads.  Out: the stride
 *                     in doubles: n, and BK_THREAD_GAP bytes more when there is
 *                     more than one thread.  With the slots adjacent, the
 *                     second of 2 threads evaluated the 10,000-element
 *                     assembly's lane groups in 14 us instead of 6 (its slot
 *                     1.5 kB from the first's; the other core's prefetching
 *                     into the same lines, by the look of it): the slowdown
 *                     shrank as the gap grew and was gone from 32 kB on.  The
 *                     gap is never touched (no memory is used for it). */
#ifndef BK_BIGALLOC_H
#define BK_BIGALLOC_H

#include <stddef.h>

/* Smallest block given the advice: two huge pages (a smaller block holds at
 * most one whole 2 MiB page at an unknown offset). */
#define BK_BIG_BYTES ((size_t)4 << 20)

/* Bytes between two threads' scratch slots: twice the gap that was enough. */
#define BK_THREAD_GAP ((size_t)64 << 10)

static inline size_t bk_thread_stride(size_t n, int nthreads)
{
    return nthreads > 1 ? n + BK_THREAD_GAP / sizeof(double) : n;
}

/* The process's small blocks on huge pages too (called first thing in main):
 * glibc's heap made to grow BK_HEAP_PAD at a time and to keep what is freed,
 * blocks below BK_HEAP_MMAP taken from it, and the heap advised as above from
 * the first 2 MiB boundary past every page touched so far (a range with one
 * small page in it gets small pages only).  A small run touched 200 fresh 4 kB pages at 10
 * us each on a virtual machine (its model, system and output buffers); a huge
 * page's first touch costs 0.12-0.18 ms there.  Returns the block that fills
 * the heap up to that boundary (never touched; the caller frees it at the
 * end), or NULL when the heap is not glibc's (valgrind, sanitizers) or the
 * advice is not to be had. */
#define BK_HEAP_PAD ((size_t)8 << 20)
#define BK_HEAP_MMAP ((size_t)32 << 20)
void *bk_big_heap(void);

void *bk_big_malloc(size_t bytes);
void *bk_big_calloc(size_t n, size_t size);
void *bk_big_realloc(void *p, size_t bytes);
void *bk_big_advise(void *p, size_t bytes);

#endif
