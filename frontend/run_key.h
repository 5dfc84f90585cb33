/* run_key.h -- the key of a run in the run cache (out/cache/run/KEY.run, .dat):
 * the launcher's copy of gen/cache.py key() and fingerprint(), which must give
 * the same 32 hex digits (tests/test_run_cached.py compares them).
 *
 * bk_run_key(root, scene, sets, nsets, key)
 *   root   in   the repository (absolute, as build.sh's ROOT)
 *   scene  in   the scene file's real path
 *   sets   in   the --set strings, in command-line order (nsets of them)
 *   key    out  33 chars: 32 hex digits + NUL
 *   fp     out  (NULL: not wanted) the fingerprint as the Python front end
 *               takes it from the environment (gen/cache.py fingerprint_once):
 *               "PID:" then the text with tabs for its NULs, PID this
 *               process's, malloc'd (the caller frees it); NULL when a path
 *               holds a tab or a newline or the text passes 64 kB
 * Returns 0, or -1 when the scene file cannot be read or memory runs out. */
#ifndef BK_RUN_KEY_H
#define BK_RUN_KEY_H

int bk_run_key(const char *root, const char *scene, char *const *sets, int nsets, char key[33], char **fp);

#endif
