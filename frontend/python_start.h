/* python_start.h -- the Python front end started as build.sh's `run` starts it,
 * for a run the launcher cannot take.
 *
 * bk_start_python_front_end(root, argc, argv)
 *   root  in  the repository (absolute)
 *   argv  in  the run's arguments (argc of them, after `run`)
 * When build.sh's Debian packages are known installed -- its stamp
 * out/.deps-installed (written by ensure_deps) exists and is no older than
 * build.sh, whose package list it records -- replaces this process with
 * /usr/bin/python3 -S -X frozen_modules=on -c '<gen.cli run_command>' run ARGS, in
 * root, with build.sh's environment (PYTHONPATH with root first,
 * PYTHONPYCACHEPREFIX=root/out/pycache, no PYTHONDONTWRITEBYTECODE,
 * BK_CALLER_CWD the caller's directory unless given).  Keep this command line
 * in step with build.sh's (tests/test_run_cached.py compares them).  Starting
 * it here saves /bin/sh and /bin/bash: 7 ms of an 80 ms run on a virtual
 * machine.  Returns (nothing changed but maybe the working directory and the
 * environment) when the stamp is missing or stale or Python cannot be
 * started: the caller then goes through build.sh, which does it all again. */
#ifndef BK_PYTHON_START_H
#define BK_PYTHON_START_H

void bk_start_python_front_end(const char *root, int argc, char **argv);

#endif
