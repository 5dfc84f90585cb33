/* interrupt.h -- stopping a run cleanly on SIGINT (Ctrl-C) and SIGTERM.
 *
 * The signals are blocked for the whole process at start-up (threads started
 * later, OpenMP's among them, inherit the mask), so they stay pending instead
 * of killing the solver; the analyses poll for them between Newton iterations
 * (at most every BK_INTERRUPT_POLL_S of wall time, nonlinear.h) and steps, stop, keep every converged step and write summary.json with
 * "interrupted": true.  No handler and no global state: the pending set is the
 * kernel's.  Exit status 128 + signal (130 SIGINT, 143 SIGTERM).
 */
#ifndef BK_INTERRUPT_H
#define BK_INTERRUPT_H

/* Blocks SIGINT and SIGTERM.  Returns 0, or -1 if the mask cannot be set. */
int bk_interrupt_block(void);

/* The pending SIGINT or SIGTERM, consumed, or 0 when there is none. */
int bk_interrupt_poll(void);

/* "SIGINT", "SIGTERM" or "signal". */
const char *bk_interrupt_name(int signo);

#endif
