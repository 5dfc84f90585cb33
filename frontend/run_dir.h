/* run_dir.h -- the paths and the results directory of a run, as the Python
 * front end makes them (gen/pipeline.py caller_path, prepare_run_dir,
 * gen/cache.py link_scene; posixpath.normpath).  Strings returned are
 * malloc'd: the caller frees them.
 *
 * bk_caller_path(p)       p as the user meant it: absolute, or relative to
 *                         $BK_CALLER_CWD (else the working directory); NULL
 *                         for a "~user" path (left to the Python front end)
 * bk_normpath(p)          p with "//", "." and ".." resolved lexically
 * bk_prepare_run_dir(d)   create d, or clear it if it holds only a run's
 *                         files (its .beamkit-run marker); 0, or -1 when it
 *                         cannot be used (nothing is removed then)
 * bk_link_scene(bin, name, solver)
 *                         bin/NAME -> basename(solver), replaced atomically
 *                         unless it points there already */
#ifndef BK_RUN_DIR_H
#define BK_RUN_DIR_H

char *bk_caller_path(const char *p);
char *bk_normpath(const char *p);
int bk_prepare_run_dir(const char *dir);
void bk_link_scene(const char *bin, const char *name, const char *solver);

#endif
