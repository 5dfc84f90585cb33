/* filewriter_check.c -- the writer thread's buffers taken without waiting
 * (filewriter.h bk_filewriter_slot with wait 0) and a call's state asked
 * without waiting (bk_filewriter_done), while the thread is held in a call.
 *
 *   filewriter_check DIR
 *
 * A threaded writer is given a call that blocks until a byte comes through a
 * pipe.  Meanwhile: that call is not done; every buffer
 * (BK_FILEWRITER_BUFFERS) is taken and handed over as files f0, f1, ...; one
 * more is not to be had without waiting (-1).  Then the byte is sent: the call
 * is done, a buffer is free again, and file c is written through it.  An unthreaded writer: every call is done and
 * a buffer is always free.  Prints one "NAME=VALUE" per check and exits 0 only
 * when every one holds and the files have their contents. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/filewriter.h"

static void hold(const void *arg, FILE *unused)
{
    (void)unused;
    char c;
    if (read(*(const int *)arg, &c, 1) != 1)
        fprintf(stderr, "filewriter_check: the pipe closed early\n");
}

static void text(const void *job, FILE *fp)
{
    fputs(job, fp);
}

static void nothing(const void *arg, FILE *unused)
{
    (void)arg;
    (void)unused;
}

static int has(const char *dir, const char *name, const char *want)
{
    char path[1024], got[64] = {0};
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return 0;
    size_t n = fread(got, 1, sizeof got - 1, fp);
    fclose(fp);
    return n == strlen(want) && memcmp(got, want, n) == 0;
}

static int check(const char *name, int ok, int *all)
{
    printf("%s=%d\n", name, ok);
    *all = *all && ok;
    return ok;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: filewriter_check DIR\n");
        return 2;
    }
    const char *dir = argv[1];
    char pa[1024], pc[1024];
    snprintf(pa, sizeof pa, "%s/a", dir);
    snprintf(pc, sizeof pc, "%s/c", dir);
    int fd[2];
    bk_filewriter w;
    if (pipe(fd) != 0 || bk_filewriter_open(&w, 64, 1) != 0 || !w.threaded) {
        fprintf(stderr, "filewriter_check: no pipe or no threaded writer\n");
        return 2;
    }
    int all = 1;
    long held = bk_filewriter_call(&w, hold, &fd[0]);
    check("held_not_done", bk_filewriter_done(&w, held) == 0, &all);
    /* every buffer can be taken and handed over while the thread is held */
    int got = 0;
    for (int k = 0; k < BK_FILEWRITER_BUFFERS; ++k) {
        int b = bk_filewriter_slot(&w, 0);
        if (b < 0)
            break;
        got++;
        char path[1100];
        snprintf(path, sizeof path, "%s/f%d", dir, k);
        bk_filewriter_submit_job(&w, b, path, text, k == 0 ? "first\n" : "second\n");
    }
    check("all_free", got == BK_FILEWRITER_BUFFERS, &all);
    check("none_free_without_wait", bk_filewriter_slot(&w, 0) == -1, &all);
    if (write(fd[1], "x", 1) != 1)
        return 2;
    bk_filewriter_wait(&w, held);
    check("held_done", bk_filewriter_done(&w, held) == 1, &all);
    int c = bk_filewriter_slot(&w, 1);             /* (those written by now or soon: waited for) */
    check("free_again", c >= 0, &all);
    if (c >= 0)
        bk_filewriter_submit_job(&w, c, pc, text, "third\n");
    check("drained", bk_filewriter_drain(&w) == 0, &all);
    int files = has(dir, "c", "third\n");
    for (int k = 0; k < got; ++k) {
        char name[16];
        snprintf(name, sizeof name, "f%d", k);
        files = files && has(dir, name, k == 0 ? "first\n" : "second\n");
    }
    check("files", files, &all);
    bk_filewriter_close(&w);
    close(fd[0]);
    close(fd[1]);

    bk_filewriter u;                               /* unthreaded: the work is done at once */
    if (bk_filewriter_open(&u, 64, 0) != 0)
        return 2;
    long t = bk_filewriter_call(&u, nothing, NULL);
    check("unthreaded_done", bk_filewriter_done(&u, t) == 1, &all);
    int s = bk_filewriter_slot(&u, 0);
    check("unthreaded_free", s >= 0, &all);
    if (s >= 0)
        bk_filewriter_submit_job(&u, s, pa, text, "fourth\n");
    check("unthreaded_file", has(dir, "a", "fourth\n"), &all);
    bk_filewriter_close(&u);
    return all ? 0 : 1;
}
