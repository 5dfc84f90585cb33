/* scene_warnings.h -- the scene reader's warnings of a repeated run put first
 * into summary.json "warnings", beside any others: the launcher's copy of
 * gen/run_summary.py add_scene_warnings() (the same bytes; tests compare),
 * for a summary.json the launcher wrote itself (a run interrupted before the
 * solver started; the solver lists them in its own, from the model file).
 *
 * bk_add_scene_warnings(run_dir, warnings, n)
 *   run_dir   in  the run directory (its summary.json is rewritten)
 *   warnings  in  n strings (UTF-8)
 * Returns 0 (also when there is nothing to do), -1 when summary.json is not
 * in the solver's layout or cannot be rewritten. */
#ifndef BK_SCENE_WARNINGS_H
#define BK_SCENE_WARNINGS_H

int bk_add_scene_warnings(const char *run_dir, char *const *warnings, int n);

#endif
