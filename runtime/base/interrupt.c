/* interrupt.c -- SIGINT / SIGTERM as pending signals polled by the analyses. */
#include "base/interrupt.h"

#include <signal.h>
#include <time.h>

static void stop_set(sigset_t *set)
{
    sigemptyset(set);
    sigaddset(set, SIGINT);
    sigaddset(set, SIGTERM);
}

int bk_interrupt_block(void)
{
    sigset_t set;
    stop_set(&set);
    return sigprocmask(SIG_BLOCK, &set, NULL) == 0 ? 0 : -1;
}

int bk_interrupt_poll(void)
{
    sigset_t pend, set;
    if (sigpending(&pend) != 0)
        return 0;
    if (!sigismember(&pend, SIGINT) && !sigismember(&pend, SIGTERM))
        return 0;
    stop_set(&set);
    struct timespec zero = {0, 0};
    int sig = sigtimedwait(&set, NULL, &zero);
    return sig > 0 ? sig : 0;
}

const char *bk_interrupt_name(int signo)
{
    return signo == SIGINT ? "SIGINT" : signo == SIGTERM ? "SIGTERM" : "signal";
}
