/* precreate.c -- the files of a run created ahead by a helper thread
 * (precreate.h). */
#define _GNU_SOURCE              /* sched_getcpu, pthread_attr_setaffinity_np */
#include "precreate.h"

#include <errno.h>
#include <fcntl.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A slot's state (under mu). */
enum {
    S_NONE,      /* a named slot not wanted                                  */
    S_WANTED,    /* to be created: by the helper, or by the caller first      */
    S_BUSY,      /* the helper is creating it                                 */
    S_READY,     /* the helper created it (fd, or err)                        */
    S_OUT,       /* the caller's: a named file taken, a spare not yet renamed */
    S_DONE       /* renamed, removed, or no longer wanted                     */
};

#define HELPER_STACK (64 << 10)

static char *slot_path(const bk_precreate *p, int k)
{
    return p->path + (size_t)k * p->pathlen;
}

int bk_precreate_init(bk_precreate *p, const char *dir, int nnamed, int nspare)
{
    memset(p, 0, sizeof *p);
    p->nnamed = nnamed;
    p->nspare = nspare;
    p->n = nnamed + nspare;
    /* the paths in one block of the size they need (fixed 1 kB paths were
     * 20 kB of fresh pages, a fault each: 1-2 us here) */
    p->dirlen = strlen(dir);
    p->pathlen = p->dirlen + BK_PRECREATE_NAME + 2;
    p->path = malloc((size_t)(p->n > 0 ? p->n : 1) * p->pathlen);
    p->state = calloc(3 * (size_t)(p->n > 0 ? p->n : 1), sizeof *p->state);
    if (!p->path || !p->state)
        return -1;
    p->fd = p->state + p->n;
    p->err = p->fd + p->n;
    for (int k = 0; k < p->n; ++k) {
        p->fd[k] = -1;
        p->path[(size_t)k * p->pathlen] = 0;
    }
    for (int k = nnamed; k < p->n; ++k) {
        snprintf(slot_path(p, k), p->pathlen, "%s/.bk-spare-%02d", dir, k - nnamed);
        p->state[k] = S_WANTED;
    }
    if (pthread_mutex_init(&p->mu, NULL) != 0)
        return -1;
    p->ready = 1;
    return 0;
}

void bk_precreate_want(bk_precreate *p, int k, const char *dir, const char *name)
{
    if (k < 0 || k >= p->nnamed || !p->state)
        return;
    snprintf(slot_path(p, k), p->pathlen, "%s/%s", dir, name);   /* (dir: bk_precreate_init's) */
    p->state[k] = S_WANTED;
}

/* The next slot to create, now S_BUSY (spares first: a run's first frame needs
 * one soon, its tables are written at its end), or -1. */
static int next_slot(bk_precreate *p)
{
    for (int j = 0; j < p->n; ++j) {
        int k = (j + p->nnamed) % p->n;
        if (p->state[k] == S_WANTED) {
            p->state[k] = S_BUSY;
            return k;
        }
    }
    return -1;
}

static void *helper_main(void *arg)
{
    bk_precreate *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        int k = next_slot(p);
        pthread_mutex_unlock(&p->mu);
        if (k < 0)
            break;
        int fd = open(slot_path(p, k), O_WRONLY | O_CREAT | O_TRUNC, 0666);
        int e = fd < 0 ? errno : 0;
        pthread_mutex_lock(&p->mu);
        p->fd[k] = fd;
        p->err[k] = e;
        p->state[k] = S_READY;
        pthread_mutex_unlock(&p->mu);
    }
    return NULL;
}

void bk_precreate_start(bk_precreate *p)
{
    if (!p->ready || p->threaded)
        return;
    pthread_attr_t at;
    if (pthread_attr_init(&at) != 0)
        return;
    /* its stack from the heap: half the cost of a mapped one (25 against
     * 50 us for a process's first thread); it calls no more than open() */
    p->stack = aligned_alloc(4096, HELPER_STACK);
    if (!p->stack || pthread_attr_setstack(&at, p->stack, HELPER_STACK) != 0) {
        pthread_attr_destroy(&at);
        return;
    }
    /* on another core than this one: a new thread may otherwise start on the
     * caller's core and hold it for the files it creates (up to a millisecond
     * here) */
    cpu_set_t set;
    int cpu = sched_getcpu();
    if (cpu >= 0 && sched_getaffinity(0, sizeof set, &set) == 0 && CPU_ISSET(cpu, &set) && CPU_COUNT(&set) > 1) {
        CPU_CLR(cpu, &set);
        pthread_attr_setaffinity_np(&at, sizeof set, &set);
    }
    p->threaded = pthread_create(&p->thread, &at, helper_main, p) == 0;
    pthread_attr_destroy(&at);
}

int bk_precreate_named(bk_precreate *p, int k)
{
    if (k < 0 || k >= p->nnamed || !p->ready) {
        errno = EINVAL;
        return -1;
    }
    for (;;) {
        pthread_mutex_lock(&p->mu);
        int s = p->state[k];
        if (s == S_READY || s == S_WANTED)
            p->state[k] = S_OUT;
        int fd = p->fd[k], e = p->err[k];
        pthread_mutex_unlock(&p->mu);
        if (s == S_READY) {
            errno = e;
            return fd;
        }
        if (s == S_WANTED)               /* not reached by the helper: created here */
            return open(slot_path(p, k), O_WRONLY | O_CREAT | O_TRUNC, 0666);
        if (s != S_BUSY) {               /* not wanted, or taken before */
            errno = EINVAL;
            return -1;
        }
        sched_yield();                   /* the helper is creating it: a few us */
    }
}

FILE *bk_precreate_stream(bk_precreate *p, int *slot)
{
    *slot = -1;
    if (!p || !p->ready)
        return NULL;
    int fd = -1, k = p->nnamed;
    pthread_mutex_lock(&p->mu);
    for (; k < p->n && fd < 0; ++k)
        if (p->state[k] == S_READY) {
            p->state[k] = p->fd[k] < 0 ? S_DONE : S_OUT;   /* (one not created: written directly) */
            fd = p->fd[k];
            if (fd >= 0)
                break;
        }
    pthread_mutex_unlock(&p->mu);
    if (fd < 0)
        return NULL;
    FILE *fp = fdopen(fd, "w");
    if (!fp) {                           /* (out of memory) the spare is removed at the end */
        close(fd);
        return NULL;
    }
    *slot = k;
    return fp;
}

int bk_precreate_rename(bk_precreate *p, int slot, const char *path)
{
    if (slot < p->nnamed || slot >= p->n) {
        errno = EINVAL;
        return -1;
    }
    int rc = rename(slot_path(p, slot), path), e = errno;
    if (rc != 0)
        unlink(slot_path(p, slot));
    pthread_mutex_lock(&p->mu);
    p->state[slot] = S_DONE;
    pthread_mutex_unlock(&p->mu);
    errno = e;
    return rc;
}

void bk_precreate_end(bk_precreate *p, int discard)
{
    if (p->ready) {
        pthread_mutex_lock(&p->mu);
        for (int k = 0; k < p->n; ++k)
            if (p->state[k] == S_WANTED)
                p->state[k] = S_DONE;    /* the helper stops after the file it is creating */
        pthread_mutex_unlock(&p->mu);
        if (p->threaded)
            pthread_join(p->thread, NULL);
        for (int k = 0; k < p->n; ++k) {
            int spare = k >= p->nnamed;
            if (p->state[k] == S_READY && p->fd[k] >= 0) {
                close(p->fd[k]);
                if (spare || discard)
                    unlink(slot_path(p, k));
            } else if (p->state[k] == S_OUT && spare) {
                unlink(slot_path(p, k));      /* given out, never named: its write failed */
            }
        }
        pthread_mutex_destroy(&p->mu);
    }
    free(p->path);
    free(p->state);
    free(p->stack);
    memset(p, 0, sizeof *p);
}
