/* filewriter.h -- whole files (the ParaView frames) made and written by a
 * background thread while the solve goes on, and other work handed to that
 * thread in the same order (the result tables' rows: csvrow.h).
 *
 * A file is handed over as a job: its path and a function that writes its
 * contents from inputs the caller copied into its own memory for that job's
 * buffer.  The thread makes the contents in the buffer, then creates, writes
 * and closes the file, in the order handed over, and gives the buffer back.
 * On this kind of machine making a frame takes 20-30 us and creating and
 * writing it 30-60 us, more than a small model's load step; with the thread
 * the solver's core does not wait for either.
 *
 * Sizes and directions:
 *   bk_filewriter_open    in: cap, the largest file in bytes (a larger one is
 *                         written to its file as it is made); threaded: 0 makes
 *                         every submit write at once in the caller's thread
 *                         (as when no thread could be made).  0, or -1 when out
 *                         of memory (bk_filewriter_close frees what was made).
 *   bk_filewriter_start   an unthreaded writer's thread started (from the
 *                         opener's thread, between jobs); 1 when it runs.
 *   bk_filewriter_slot    in: wait (0: none is waited for).  out: the index
 *                         (0 .. BK_FILEWRITER_BUFFERS-1) of a free buffer, now
 *                         the caller's (with wait, waits while every buffer is
 *                         being written), or -1 when none is free and wait
 *                         is 0; the caller's job memory of that index
 *                         is free to fill until it is submitted.
 *   bk_filewriter_submit_job  in: slot from bk_filewriter_slot; path; make, called
 *                         once (in the thread, or here when unthreaded) with job
 *                         and a stream to write the file's contents to.  0, or
 *                         -1 on the first failed write so far (this file's or an
 *                         earlier one's: failed_path, errno_).
 *   bk_filewriter_call    in: fn, arg: fn(arg, NULL) run by the thread after
 *                         what was handed over before (here and now when
 *                         unthreaded); no buffer.  The call's ticket (1, 2, ...;
 *                         waits while BK_FILEWRITER_CALLS calls are queued).
 *   bk_filewriter_wait    in: ticket of bk_filewriter_call: waits until that call
 *                         has returned.
 *   bk_filewriter_done    in: ticket: 1 when that call has returned (or the
 *                         writer is unthreaded), else 0; no wait.
 *   bk_filewriter_idle    1 when every file and call handed over is done (or
 *                         the writer is unthreaded), else 0; no wait.  Until
 *                         the caller hands something over, what the jobs
 *                         wrote is the caller's to read and write.
 *   bk_filewriter_drain   waits until every file and call handed over is done;
 *                         0 or -1 as above.
 *   bk_filewriter_close   drains, ends the thread, frees the buffers.
 * Handing over does not wake the thread while it naps (for 10 ms after its
 * last job it waits 0.2 ms at a time and finds new work itself): waking a
 * sleeping thread costs the caller 20-30 us on a virtual machine; only a
 * thread asleep, a caller about to wait for it, or the last free buffer
 * taken signals it (filewriter.c nap, wake).
 * No allocation after open but for a job's stream on its buffer (fmemopen).
 * The signal mask is the opener's (the solver blocks SIGINT/SIGTERM before:
 * interrupt.h). */
#ifndef BK_FILEWRITER_H
#define BK_FILEWRITER_H

#include <pthread.h>
#include <stddef.h>
#include <stdio.h>

#define BK_FILEWRITER_BUFFERS 4   /* (2 before: frames queued behind results.h5's HDF5 start, 5-10 ms,
                                   * were written on the solve thread) */
#define BK_FILEWRITER_CALLS 36    /* (a row queue's chunks, csvrow.h BK_ROWQ_CHUNKS, and results.h5's) */
#define BK_FILEWRITER_QUEUE (BK_FILEWRITER_BUFFERS + BK_FILEWRITER_CALLS)
#define BK_FILEWRITER_PATH 1200

/* Writes a file's contents to fp (the caller's inputs in job); for a call
 * (bk_filewriter_call) fp is NULL. */
typedef void (*bk_filewriter_make)(const void *job, FILE *fp);

/* A job in the queue: a file made in buffer buf, or a call (buf -1). */
typedef struct bk_filewriter_entry {
    int buf;
    bk_filewriter_make make;
    const void *job;
} bk_filewriter_entry;

typedef struct bk_filewriter {
    size_t cap;                          /* bytes per buffer */
    unsigned char *buf[BK_FILEWRITER_BUFFERS];   /* owned */
    /* per buffer: 0 free, 1 handed to the caller, 2 queued or being written */
    int state[BK_FILEWRITER_BUFFERS];
    char path[BK_FILEWRITER_BUFFERS][BK_FILEWRITER_PATH];
    bk_filewriter_entry queue[BK_FILEWRITER_QUEUE];   /* the jobs in the order handed over */
    int head, count;
    int ncall;                           /* calls in the queue */
    long calls, calls_done;              /* calls handed over, calls returned */
    int threaded, stop, ready;         /* ready: mu and cv made */
    int idle;                            /* the thread: 0 working, 1 napping (finds hand-overs itself),
                                          * 2 asleep (a hand-over signals it): filewriter.c nap */
    int waiting;                         /* the caller waits on cv for the thread's progress */
    pthread_t thread;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int failed;                          /* a write failed: */
    int errno_;                          /*   its errno */
    char failed_path[BK_FILEWRITER_PATH];
} bk_filewriter;

int bk_filewriter_open(bk_filewriter *w, size_t cap, int threaded);
int bk_filewriter_start(bk_filewriter *w);
int bk_filewriter_slot(bk_filewriter *w, int wait);
int bk_filewriter_submit_job(bk_filewriter *w, int slot, const char *path, bk_filewriter_make make, const void *job);
long bk_filewriter_call(bk_filewriter *w, bk_filewriter_make fn, const void *arg);
void bk_filewriter_wait(bk_filewriter *w, long ticket);
int bk_filewriter_done(bk_filewriter *w, long ticket);
int bk_filewriter_idle(bk_filewriter *w);
int bk_filewriter_drain(bk_filewriter *w);
void bk_filewriter_close(bk_filewriter *w);

#endif
