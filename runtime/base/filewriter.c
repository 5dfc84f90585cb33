/* filewriter.c -- whole files written by a background thread (filewriter.h). */
#include "base/filewriter.h"
#include "base/bigalloc.h"
#include "base/thread_start.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define WRITER_STACK (256 << 10)

/* path := data[len]; 0, or an errno. */
static int write_file(const char *path, const unsigned char *data, size_t len)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0)
        return errno;
    size_t done = 0;
    while (done < len) {
        ssize_t k = write(fd, data + done, len - done);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0) {
            int e = k < 0 ? errno : EIO;
            close(fd);
            return e;
        }
        done += (size_t)k;
    }
    return close(fd) != 0 ? errno : 0;
}

/* path := what make writes for job: made in buf (cap bytes) and written in
 * one piece, or, when it outgrows buf, written to the file as it is made;
 * 0, or an errno. */
static int make_file(const char *path, unsigned char *buf, size_t cap, bk_filewriter_make make, const void *job)
{
    FILE *mp = fmemopen(buf, cap, "wb");
    if (mp) {
        setvbuf(mp, NULL, _IONBF, 0);
        make(job, mp);
        long len = ftell(mp);
        int bad = ferror(mp) || len < 0 || (size_t)len >= cap;
        fclose(mp);
        if (!bad)
            return write_file(path, buf, (size_t)len);
    }
    FILE *fp = fopen(path, "wb");
    if (!fp)
        return errno;
    char iobuf[1 << 16];                 /* a few large writes instead of many small ones */
    setvbuf(fp, iobuf, _IOFBF, sizeof iobuf);
    make(job, fp);
    int bad = ferror(fp);
    if (fclose(fp) != 0 || bad)          /* (flushes iobuf before it goes out of scope) */
        return errno ? errno : EIO;
    return 0;
}

/* The first failure is kept (called with the lock held, or unthreaded). */
static void record(bk_filewriter *w, const char *path, int err)
{
    if (err == 0 || w->failed)
        return;
    w->failed = 1;
    w->errno_ = err;
    snprintf(w->failed_path, sizeof w->failed_path, "%s", path);
}

/* The thread, out of work, first naps: waits of BK_FILEWRITER_NAP_US each,
 * BK_FILEWRITER_NAPS times, in which a hand-over is found without being
 * signalled; then it sleeps until one signals it (see wake).  On a virtual
 * machine waking a sleeping thread costs the waker 20-30 us (a futex wake and
 * an interrupt to the other processor), as much as handing a frame over; a
 * run that writes an output step every millisecond or two paid it at each. */
#define BK_FILEWRITER_NAP_US 200
#define BK_FILEWRITER_NAPS 50

static void nap(bk_filewriter *w)
{
    w->idle = 1;
    for (int k = 0; k < BK_FILEWRITER_NAPS && w->count == 0 && !w->stop; ++k) {
        struct timespec ts;
        clock_gettime(CLOCK_MONOTONIC, &ts);
        ts.tv_nsec += BK_FILEWRITER_NAP_US * 1000L;
        if (ts.tv_nsec >= 1000000000L) {
            ts.tv_sec++;
            ts.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&w->cv, &w->mu, &ts);
    }
    w->idle = 2;
    while (w->count == 0 && !w->stop)
        pthread_cond_wait(&w->cv, &w->mu);
    w->idle = 0;
}

/* After a hand-over (lock held): the thread signalled when it sleeps, or when
 * the caller needs it now (urgent: it is about to wait for it, or the last
 * free buffer was taken); a napping thread finds the work itself. */
static void wake(bk_filewriter *w, int urgent)
{
    if (w->idle == 2 || (urgent && w->idle))
        pthread_cond_broadcast(&w->cv);
}

static void *writer_main(void *arg)
{
    bk_filewriter *w = arg;
    bk_thread_started();
    pthread_mutex_lock(&w->mu);
    for (;;) {
        if (w->count == 0 && !w->stop)
            nap(w);
        if (w->count == 0)
            break;
        const bk_filewriter_entry e = w->queue[w->head];
        pthread_mutex_unlock(&w->mu);
        int err = 0;
        if (e.buf >= 0)
            err = make_file(w->path[e.buf], w->buf[e.buf], w->cap, e.make, e.job);
        else
            e.make(e.job, NULL);
        pthread_mutex_lock(&w->mu);
        if (e.buf >= 0) {
            record(w, w->path[e.buf], err);
            w->state[e.buf] = 0;
        } else {
            w->ncall--;
            w->calls_done++;
        }
        w->head = (w->head + 1) % BK_FILEWRITER_QUEUE;
        w->count--;
        if (w->waiting)                  /* (the caller waits for this thread) */
            pthread_cond_broadcast(&w->cv);
    }
    pthread_mutex_unlock(&w->mu);
    return NULL;
}

/* The caller waits for the thread (lock held): woken first if idle. */
static void await(bk_filewriter *w)
{
    wake(w, 1);
    w->waiting++;
    pthread_cond_wait(&w->cv, &w->mu);
    w->waiting--;
}

int bk_filewriter_open(bk_filewriter *w, size_t cap, int threaded)
{
    memset(w, 0, sizeof *w);
    w->cap = cap;
    for (int b = 0; b < BK_FILEWRITER_BUFFERS; ++b)
        if (!(w->buf[b] = bk_big_malloc(cap > 0 ? cap : 1)))
            return -1;
    if (pthread_mutex_init(&w->mu, NULL) != 0)
        return -1;
    pthread_condattr_t ca;              /* (the naps are timed on the monotonic clock) */
    if (pthread_condattr_init(&ca) != 0) {
        pthread_mutex_destroy(&w->mu);
        return -1;
    }
    const int bad = pthread_condattr_setclock(&ca, CLOCK_MONOTONIC) != 0 || pthread_cond_init(&w->cv, &ca) != 0;
    pthread_condattr_destroy(&ca);
    if (bad) {
        pthread_mutex_destroy(&w->mu);
        return -1;
    }
    w->ready = 1;
    if (threaded)
        bk_filewriter_start(w);
    return 0;
}

int bk_filewriter_start(bk_filewriter *w)
{
    if (w->threaded || !w->ready)
        return w->threaded;
    w->threaded = bk_thread_start(&w->thread, WRITER_STACK, writer_main, w) == 0;
    return w->threaded;
}

int bk_filewriter_slot(bk_filewriter *w, int wait)
{
    pthread_mutex_lock(&w->mu);
    int b = -1;
    for (;;) {
        for (int k = 0; k < BK_FILEWRITER_BUFFERS && b < 0; ++k)
            if (w->state[k] == 0)
                b = k;
        if (b >= 0 || !w->threaded || !wait)
            break;
        await(w);
    }
    if (b >= 0)
        w->state[b] = 1;
    pthread_mutex_unlock(&w->mu);
    return b;
}

/* Queues buffer b (the caller's) for the thread, made by make(job). */
static int queue(bk_filewriter *w, int b, const char *path, bk_filewriter_make make, const void *job)
{
    pthread_mutex_lock(&w->mu);
    snprintf(w->path[b], sizeof w->path[b], "%s", path);
    w->state[b] = 2;
    w->queue[(w->head + w->count) % BK_FILEWRITER_QUEUE] = (bk_filewriter_entry){b, make, job};
    w->count++;
    int free_left = 0;
    for (int k = 0; k < BK_FILEWRITER_BUFFERS; ++k)
        free_left += w->state[k] == 0;
    wake(w, free_left == 0);
    int failed = w->failed;
    pthread_mutex_unlock(&w->mu);
    return failed ? -1 : 0;
}

/* Buffer b back to free (unthreaded: its file written here). */
static int release(bk_filewriter *w, int b)
{
    pthread_mutex_lock(&w->mu);
    w->state[b] = 0;
    pthread_mutex_unlock(&w->mu);
    return w->failed ? -1 : 0;
}

int bk_filewriter_submit_job(bk_filewriter *w, int slot, const char *path, bk_filewriter_make make, const void *job)
{
    if (slot < 0 || slot >= BK_FILEWRITER_BUFFERS || w->state[slot] != 1)
        return -1;
    if (!w->threaded) {
        record(w, path, make_file(path, w->buf[slot], w->cap, make, job));
        return release(w, slot);
    }
    return queue(w, slot, path, make, job);
}

long bk_filewriter_call(bk_filewriter *w, bk_filewriter_make fn, const void *arg)
{
    if (!w->threaded) {
        fn(arg, NULL);
        w->calls_done = ++w->calls;
        return w->calls;
    }
    pthread_mutex_lock(&w->mu);
    while (w->ncall == BK_FILEWRITER_CALLS)     /* (each frame in the queue holds a buffer: room for the calls) */
        await(w);
    w->queue[(w->head + w->count) % BK_FILEWRITER_QUEUE] = (bk_filewriter_entry){-1, fn, arg};
    w->count++;
    w->ncall++;
    long ticket = ++w->calls;
    wake(w, 0);
    pthread_mutex_unlock(&w->mu);
    return ticket;
}

void bk_filewriter_wait(bk_filewriter *w, long ticket)
{
    if (!w->threaded)
        return;
    pthread_mutex_lock(&w->mu);
    while (w->calls_done < ticket)
        await(w);
    pthread_mutex_unlock(&w->mu);
}

int bk_filewriter_done(bk_filewriter *w, long ticket)
{
    if (!w->threaded)
        return 1;
    pthread_mutex_lock(&w->mu);
    const int done = w->calls_done >= ticket;
    pthread_mutex_unlock(&w->mu);
    return done;
}

int bk_filewriter_idle(bk_filewriter *w)
{
    if (!w->threaded)
        return 1;
    pthread_mutex_lock(&w->mu);
    const int idle = w->count == 0;
    pthread_mutex_unlock(&w->mu);
    return idle;
}

int bk_filewriter_drain(bk_filewriter *w)
{
    if (!w->threaded)
        return w->failed ? -1 : 0;
    pthread_mutex_lock(&w->mu);
    while (w->count > 0)
        await(w);
    int failed = w->failed;
    pthread_mutex_unlock(&w->mu);
    return failed ? -1 : 0;
}

void bk_filewriter_close(bk_filewriter *w)
{
    if (w->threaded) {
        pthread_mutex_lock(&w->mu);
        w->stop = 1;
        pthread_cond_broadcast(&w->cv);
        pthread_mutex_unlock(&w->mu);
        pthread_join(w->thread, NULL);
        w->threaded = 0;
    }
    if (w->ready) {
        pthread_cond_destroy(&w->cv);
        pthread_mutex_destroy(&w->mu);
    }
    for (int b = 0; b < BK_FILEWRITER_BUFFERS; ++b)
        free(w->buf[b]);
    memset(w, 0, sizeof *w);
}
