/* rowqueue_check.c -- the result tables' rows handed to a writer thread
 * (csvrow.h bk_rowqueue) against the same rows printed with glibc's fprintf.
 *
 *   rowqueue_check DIR NROWS [STEP_BYTES [idle]]
 *
 * Writes NROWS random rows (integers, "%.17g" numbers, "%.Ne" and "%.Ng" with
 * random precisions, names up to 5000 bytes: longer than a string piece and
 * than a row's buffer; NaN and infinities among the numbers) into three tables
 * at once, through a queue started on a threaded writer, with a flush handed
 * over now and then; and the same rows into three other files with fprintf.
 * Prints "rows=N bytes=B chunks=C differ=D" (D: tables whose bytes differ) and
 * exits 0 only when D is 0 and more than two chunks were handed over (the rows
 * spanned chunk boundaries).  Rows are also offered now and then
 * (bk_rowqueue_offer: handed over early when the next chunk is free).  STEP_BYTES (default 0: the queue's four chunks)
 * is bk_rowqueue_start's hint: a larger one cycles through more chunks.  With
 * idle, the thread is first let finish all it was given, so that the stop
 * formats the rows not yet handed over itself (prints "local=1" when there
 * were some). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/csvrow.h"
#include "base/filewriter.h"

static uint64_t rng = 0x9e3779b97f4a7c15ULL;

static uint64_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static double value(void)
{
    const uint64_t k = next() % 64;
    if (k == 0)
        return NAN;
    if (k == 1)
        return next() & 1 ? INFINITY : -INFINITY;
    if (k == 2)
        return 0.0;
    const double m = (double)(next() >> 11) / 9007199254740992.0 - 0.5;
    return ldexp(m, (int)(next() % 200) - 100);
}

static long same(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    long n = 0, bad = !fa || !fb;
    while (!bad) {
        int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb)
            bad = 1;
        if (ca == EOF || cb == EOF)
            break;
        ++n;
    }
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return bad ? -1 : n;
}

int main(int argc, char **argv)
{
    if (argc < 3 || argc > 5 || (argc == 5 && strcmp(argv[4], "idle") != 0)) {
        fprintf(stderr, "usage: %s DIR NROWS [STEP_BYTES [idle]]\n", argv[0]);
        return 2;
    }
    const long nrows = atol(argv[2]);
    char path[3][2][1024];
    FILE *fp[3][2];
    for (int t = 0; t < 3; ++t)
        for (int v = 0; v < 2; ++v) {
            snprintf(path[t][v], sizeof path[t][v], "%s/table%d_%s.csv", argv[1], t, v ? "queued" : "printf");
            if (!(fp[t][v] = fopen(path[t][v], "w"))) {
                perror(path[t][v]);
                return 2;
            }
        }
    bk_filewriter w;
    bk_rowqueue q = {0};
    FILE *queued[3] = {fp[0][1], fp[1][1], fp[2][1]};
    if (bk_filewriter_open(&w, 1, 1) != 0 || !w.threaded || bk_rowqueue_start(&q, &w, queued, 3, argc >= 4 ? (size_t)atol(argv[3]) : 0) != 0) {
        fprintf(stderr, "no writer thread or no memory\n");
        return 2;
    }
    static char name[5001];
    for (long i = 0; i < nrows; ++i) {
        const int t = (int)(next() % 3), nf = 1 + (int)(next() % 24);
        bk_row r;
        bk_row_begin(&r, queued[t], &q);
        FILE *ref = fp[t][0];
        for (int f = 0; f < nf; ++f) {
            if (f > 0)
                fputc(',', ref);
            const int kind = (int)(next() % 8);
            if (kind == 0) {
                const long iv = (long)next() >> (next() % 63);
                bk_row_int(&r, iv);
                fprintf(ref, "%ld", iv);
            } else if (kind == 1) {
                /* mostly short names; now and then longer than a piece or a row */
                const size_t len = next() % 50 == 0 ? 1 + next() % 5000 : next() % 12;
                for (size_t c = 0; c < len; ++c)
                    name[c] = (char)('a' + next() % 26);
                name[len] = '\0';
                bk_row_str(&r, name);
                fputs(name, ref);
            } else if (kind == 2) {
                const double v = value();
                const int prec = (int)(next() % 17);
                bk_row_e(&r, v, prec);
                fprintf(ref, "%.*e", prec, v);
            } else if (kind == 3) {
                const double v = value();
                const int prec = 1 + (int)(next() % 17);
                bk_row_g(&r, v, prec);
                fprintf(ref, "%.*g", prec, v);
            } else {
                const double v = value();
                bk_row_num(&r, v);
                fprintf(ref, "%.17g", v);
            }
        }
        bk_row_end(&r);
        fputc('\n', ref);
        if (next() % 5000 == 0)
            bk_rowqueue_submit(&q, 1);
        else if (next() % 300 == 0)      /* an output step's offer: handed over when the next chunk is free */
            bk_rowqueue_offer(&q, 1000);
    }
    const long chunks = w.calls;
    printf("cycle=%d ", q.nchunk);
    if (argc == 5) {                     /* the stop on an idle thread: the last rows formatted by the caller */
        bk_filewriter_drain(&w);
        printf("local=%d ", q.pos > 0 && bk_filewriter_idle(&w));
    }
    bk_rowqueue_free(&q);
    bk_filewriter_close(&w);
    long bytes = 0;
    int differ = 0;
    for (int t = 0; t < 3; ++t) {
        for (int v = 0; v < 2; ++v)
            if (fclose(fp[t][v]) != 0)
                differ++;
        long n = same(path[t][0], path[t][1]);
        if (n < 0)
            differ++;
        else
            bytes += n;
    }
    printf("rows=%ld bytes=%ld chunks=%ld differ=%d\n", nrows, bytes, chunks, differ);
    return differ == 0 && chunks > 2 ? 0 : 1;
}
