/* thread_start.h -- a helper thread started on another CPU than its
 * starter's.
 *
 * Left to the scheduler, a new thread began on its starter's CPU in 5 of 6
 * tries on a 2-CPU virtual machine, though the other was idle: it then either
 * ran first, the starter waiting 1.2 ms for the CPU, or waited up to 3.5 ms
 * for the starter's time slice to end.  Started on the other CPU it ran after
 * 0.2-0.4 ms and the starter went on after 0.1-0.2 ms.
 *
 *   bk_thread_start    in: stack (bytes), fn, arg.  Out: *t.  Starts fn(arg)
 *                      on a CPU of the caller's set other than the caller's
 *                      (on any, when the set has one CPU or the CPU is not
 *                      known).  0, or -1 when it cannot be started.
 *   bk_thread_started  called first by such a thread: its CPUs widened to the
 *                      process's set (the main thread's), so that the
 *                      scheduler may move it later. */
#ifndef BK_THREAD_START_H
#define BK_THREAD_START_H

#include <pthread.h>
#include <stddef.h>

int bk_thread_start(pthread_t *t, size_t stack, void *(*fn)(void *), void *arg);
void bk_thread_started(void);

#endif
