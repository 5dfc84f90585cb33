/* thread_start.c -- a helper thread started on another CPU than its
 * starter's (thread_start.h). */
#define _GNU_SOURCE /* cpu_set_t, sched_getcpu, pthread_attr_setaffinity_np */
#include "base/thread_start.h"

#include <sched.h>
#include <unistd.h>

int bk_thread_start(pthread_t *t, size_t stack, void *(*fn)(void *), void *arg)
{
    pthread_attr_t at;
    if (pthread_attr_init(&at) != 0)
        return -1;
    int rc = pthread_attr_setstacksize(&at, stack);
#ifdef __linux__
    cpu_set_t other;
    const int me = sched_getcpu();
    if (rc == 0 && me >= 0 && sched_getaffinity(0, sizeof other, &other) == 0 && CPU_ISSET(me, &other) &&
        CPU_COUNT(&other) > 1) {
        CPU_CLR(me, &other);
        (void)pthread_attr_setaffinity_np(&at, sizeof other, &other);   /* (advice: any CPU without it) */
    }
#endif
    if (rc == 0)
        rc = pthread_create(t, &at, fn, arg);
    pthread_attr_destroy(&at);
    return rc == 0 ? 0 : -1;
}

void bk_thread_started(void)
{
#ifdef __linux__
    cpu_set_t all;
    if (sched_getaffinity(getpid(), sizeof all, &all) == 0)    /* (the main thread's: its id is the pid) */
        (void)sched_setaffinity(0, sizeof all, &all);
#endif
}
