/* console_summary.h -- what `./build.sh run` prints after a solve: the
 * launcher's copy of gen/run_summary.py print_summary() (and print_modes()),
 * which must print the same bytes (tests/test_run_cached.py compares them).
 *
 * bk_print_summary(run_dir, shown)
 *   run_dir in  the run directory (summary.json, modes.csv, modes.pvd in it)
 *   shown   in  the directory as the "results in" line names it
 * Returns 0, or -1 when summary.json is missing or not the solver's (nothing
 * printed: the caller lets the Python front end print it). */
#ifndef BK_CONSOLE_SUMMARY_H
#define BK_CONSOLE_SUMMARY_H

int bk_print_summary(const char *run_dir, const char *shown);

#endif
