/* bigalloc.c -- large arrays backed by transparent huge pages (see bigalloc.h). */
#define _DEFAULT_SOURCE /* madvise, MADV_HUGEPAGE (glibc hides them in strict C11) */
#include "base/bigalloc.h"

#include <stdint.h>
#include <stdlib.h>
#ifdef __linux__
#include <sys/mman.h>
#include <unistd.h>
#endif
#ifdef __GLIBC__
#include <malloc.h>
#endif

#define HUGE_PAGE ((uintptr_t)2 << 20)

/* The advice on the whole 2 MiB pages inside [p, p + bytes); a failure (no
 * transparent huge pages here) leaves small pages, nothing else. */
void *bk_big_advise(void *p, size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (p && bytes >= BK_BIG_BYTES) {
        const uintptr_t lo = ((uintptr_t)p + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
        const uintptr_t hi = ((uintptr_t)p + bytes) & ~(HUGE_PAGE - 1);
        if (hi > lo)
            (void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE);
    }
#else
    (void)bytes;
#endif
    return p;
}

void *bk_big_heap(void)
{
#if defined(__linux__) && defined(__GLIBC__) && defined(MADV_HUGEPAGE) && !defined(__SANITIZE_ADDRESS__) && \
    !defined(BK_PLAIN_HEAP)
    if (mallopt(M_MMAP_THRESHOLD, (int)BK_HEAP_MMAP) != 1 || mallopt(M_TRIM_THRESHOLD, (int)BK_HEAP_MMAP) != 1 ||
        mallopt(M_TOP_PAD, (int)BK_HEAP_PAD) != 1)
        return NULL;
    /* a block from the heap's top, which grows by the pad, given back to it.
     * Its allocation wrote the top's header just past its end: the advice
     * starts at the first whole 2 MiB page above that.  (From the boundary
     * inside the block, about every other run had that header's small page in
     * the first huge page's range, and the kernel then gave the whole range
     * small pages: some 150 page faults more for a small run.) */
    char *probe = malloc(HUGE_PAGE / 2);
    if (!probe)
        return NULL;
    const uintptr_t lo = ((uintptr_t)probe + HUGE_PAGE / 2 + 64 + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
    const uintptr_t hi = (uintptr_t)sbrk(0) & ~(HUGE_PAGE - 1);
    free(probe);
    if (hi <= lo || lo - (uintptr_t)probe < 64 || madvise((void *)lo, hi - lo, MADV_HUGEPAGE) != 0)
        return NULL;
    return malloc(lo - (uintptr_t)probe - 32);   /* the head below the boundary, from the same place */
#else
    return NULL;
#endif
}

void *bk_big_malloc(size_t bytes)
{
    return bk_big_advise(malloc(bytes), bytes);
}

void *bk_big_calloc(size_t n, size_t size)
{
    /* (calloc checks n * size for overflow; on success it does not overflow) */
    void *p = calloc(n, size);
    return p ? bk_big_advise(p, n * size) : NULL;
}

void *bk_big_realloc(void *p, size_t bytes)
{
    return bk_big_advise(realloc(p, bytes), bytes);
}
