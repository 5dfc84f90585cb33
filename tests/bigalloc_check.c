/* bigalloc_check.c -- harness of tests/test_bigalloc.py: the large arrays of
 * runtime/base/bigalloc.c hold what malloc's, calloc's and realloc's blocks
 * hold, and (where the kernel offers transparent huge pages) are backed by
 * them once touched.
 *
 * usage: bigalloc_check MIB [heap]
 * With heap: first bk_big_heap (as the solver's main does; advised_rss_kb: the
 * resident kB of what it advised, right after it), then 256 small
 * blocks of 4000 bytes written and read (small_bad; small_huge_kb: the
 * AnonHugePages of the mappings that hold them; small_eligible: how many of
 * them lie where huge pages may back them; heap: 1 when bk_big_heap advised
 * the heap).  Then it allocates blocks of MIB MiB with bk_big_malloc, bk_big_calloc and
 * bk_big_realloc (a small block grown to MIB MiB, and a large one shrunk to
 * a quarter), writes and reads a pattern in each, and prints key=value
 * lines: bad (bytes that differ from what was written, or a calloc byte not
 * zero, or a realloc'd byte not kept), huge_kb (AnonHugePages of the
 * mappings that hold the blocks, /proc/self/smaps; -1 when unreadable),
 * thp (the kernel's mode: always, madvise or never; "none" when unknown). */
#define _DEFAULT_SOURCE /* ssize_t, read, close */
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/bigalloc.h"

static unsigned char pat(size_t i)
{
    return (unsigned char)(i * 2654435761u >> 13);
}

/* From /proc/self/smaps, for the n blocks: *kb, the AnonHugePages (kB) of the
 * mappings that overlap one of them, and *whole, how many lie whole in a
 * mapping that may be backed by huge pages (its THPeligible line: the advice
 * is in effect; whether a whole page was free when it was touched is the
 * kernel's); both -1 when unreadable. */
static void smaps(const void *const *blocks, const size_t *sizes, int n, long *kb, int *whole)
{
    *kb = *whole = -1;
    FILE *f = fopen("/proc/self/smaps", "r");
    if (!f)
        return;
    *kb = *whole = 0;
    char line[512];
    unsigned long a = 0, b = 0;
    int inside = 0;
    while (fgets(line, sizeof line, f)) {
        unsigned long x, y;
        long v;
        if (sscanf(line, "%lx-%lx ", &x, &y) == 2) {    /* a mapping's first line (a field's: "Name: ...") */
            a = x, b = y, inside = 0;
            for (int k = 0; k < n; ++k) {
                unsigned long lo = (unsigned long)blocks[k], hi = lo + sizes[k];
                if (lo < b && hi > a)
                    inside = 1;
            }
        } else if (inside && sscanf(line, "AnonHugePages: %ld kB", &v) == 1)
            *kb += v;
        else if (sscanf(line, "THPeligible: %ld", &v) == 1 && v)
            for (int k = 0; k < n; ++k)
                *whole += (unsigned long)blocks[k] >= a && (unsigned long)blocks[k] + sizes[k] <= b;
    }
    fclose(f);
}

/* The resident kB of the mappings advised for huge pages (smaps VmFlags
 * "hg"), read with read(2) into static memory: no heap block is touched by
 * the reading; -1 when unreadable. */
static long advised_rss_kb(void)
{
    static char text[1 << 20];
    int fd = open("/proc/self/smaps", O_RDONLY);
    if (fd < 0)
        return -1;
    size_t n = 0;
    ssize_t r;
    while (n < sizeof text - 1 && (r = read(fd, text + n, sizeof text - 1 - n)) > 0)
        n += (size_t)r;
    close(fd);
    text[n] = '\0';
    long total = 0, rss = 0, v;
    for (char *line = text; *line; ) {
        char *end = strchr(line, '\n');
        if (end)
            *end = '\0';
        if (sscanf(line, "Rss: %ld kB", &v) == 1)
            rss = v;
        else if (strncmp(line, "VmFlags:", 8) == 0 && strstr(line, " hg"))
            total += rss;
        line = end ? end + 1 : line + strlen(line);
    }
    return total;
}

int main(int argc, char **argv)
{
    if (argc != 2 && !(argc == 3 && strcmp(argv[2], "heap") == 0)) {
        fprintf(stderr, "usage: %s MIB [heap]\n", argv[0]);
        return 2;
    }
    if (argc == 3) {
        void *head = bk_big_heap();
        const long untouched = advised_rss_kb();     /* before any block is taken from the heap */
        enum { NSMALL = 256, SMALL = 4000 };
        static unsigned char *small[NSMALL];
        static size_t small_size[NSMALL];
        long small_bad = 0;
        for (int k = 0; k < NSMALL; ++k) {
            if (!(small[k] = malloc(SMALL)))
                return 1;
            small_size[k] = SMALL;
            for (size_t i = 0; i < SMALL; ++i)
                small[k][i] = pat(i + (size_t)k);
        }
        for (int k = 0; k < NSMALL; ++k)
            for (size_t i = 0; i < SMALL; ++i)
                small_bad += small[k][i] != pat(i + (size_t)k);
        long kb;
        int whole;
        smaps((const void *const *)small, small_size, NSMALL, &kb, &whole);
        printf("heap=%d\nadvised_rss_kb=%ld\nsmall_bad=%ld\nsmall_huge_kb=%ld\nsmall_eligible=%d\n", head != NULL,
               untouched, small_bad, kb, whole);
        for (int k = 0; k < NSMALL; ++k)
            free(small[k]);
        free(head);
    }
    const size_t n = (size_t)atol(argv[1]) << 20;
    long bad = 0;
    unsigned char *m = bk_big_malloc(n), *c = bk_big_calloc(n / 8, 8), *r = bk_big_realloc(NULL, 4096);
    unsigned char *s = bk_big_malloc(n);
    if (!m || !c || !r || !s) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    for (size_t i = 0; i < 4096; ++i)
        r[i] = pat(i);
    r = bk_big_realloc(r, n);                       /* grown: the first 4096 bytes kept */
    for (size_t i = 0; i < n; ++i)
        s[i] = pat(i + 7);
    s = bk_big_realloc(s, n / 4);                   /* shrunk: the first quarter kept */
    if (!r || !s) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    for (size_t i = 0; i < 4096; ++i)
        bad += r[i] != pat(i);
    for (size_t i = 0; i < n / 4; ++i)
        bad += s[i] != pat(i + 7);
    for (size_t i = 0; i < n; ++i)
        bad += c[i] != 0;
    for (size_t i = 0; i < n; ++i)
        m[i] = pat(i), c[i] = pat(i + 1), r[i] = pat(i + 2);
    for (size_t i = 0; i < n; ++i)
        bad += (m[i] != pat(i)) + (c[i] != pat(i + 1)) + (r[i] != pat(i + 2));
    const void *blocks[3] = {m, c, r};
    const size_t sizes[3] = {n, n, n};
    char mode[16] = "none";
    FILE *f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
    if (f) {
        char l[128];
        if (fgets(l, sizeof l, f)) {
            char *a = strchr(l, '['), *b = a ? strchr(a, ']') : NULL;
            if (a && b && b - a - 1 < (long)sizeof mode)
                memcpy(mode, a + 1, (size_t)(b - a - 1)), mode[b - a - 1] = 0;
        }
        fclose(f);
    }
    long kb;
    int whole;
    smaps(blocks, sizes, 3, &kb, &whole);
    printf("bad=%ld\nhuge_kb=%ld\nthp=%s\n", bad, kb, mode);
    free(m);
    free(c);
    free(r);
    free(s);
    return 0;
}
