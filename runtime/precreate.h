/* precreate.h -- the files of a run created ahead, by a helper thread, while
 * the model is set up and solved.
 *
 * Creating a file on this kind of machine costs 20-25 us (ext4 in a virtual
 * machine: allocating its inode), opening an existing one, writing a small one
 * or renaming one 1-4 us; a static seed run writes nine files and solves in
 * about a millisecond.  So the helper creates:
 *   - the run's result tables under their own names ("named" files, slots
 *     0 .. nnamed-1: the caller says which it wants before the start);
 *   - a few spare files under hidden names (DIR/.bk-spare-NN) that frames,
 *     collections and summary.json are written to and then renamed to their
 *     own names (a reader never sees half a file).
 * The caller never waits for the helper but for a named file it is creating
 * at that moment (a few us): a file it has not reached the caller creates
 * itself, and when no spare is ready it writes its file directly.
 *
 * Sizes and directions:
 *   bk_precreate_init   in: dir (the run's directory, exists), nnamed and
 *                       nspare (slots); 0, or -1 when out of memory.
 *   bk_precreate_want   in: slot k (< nnamed), dir (bk_precreate_init's) and
 *                       the file's name in it (< BK_PRECREATE_NAME bytes):
 *                       file k will be needed (before bk_precreate_start).
 *   bk_precreate_start  starts the helper (if it cannot be made, every file is
 *                       created by the caller when it is needed).
 *   bk_precreate_named  out: a descriptor of named file k, opened for writing
 *                       and emptied (now the caller's), or -1 with errno.
 *   bk_precreate_stream out: a stream on a ready spare (the caller's, to
 *                       fclose; its slot in *slot), or NULL when none is ready
 *                       (also when p is NULL): the caller writes its file
 *                       directly.
 *   bk_precreate_rename in: a spare's slot, whose stream the caller has
 *                       written and closed, and its name (a path); 0, or -1
 *                       with errno (the spare is removed).  A spare whose
 *                       stream could not be written is never renamed:
 *                       bk_precreate_end removes it.
 *   bk_precreate_end    stops the helper, closes and removes the spares not
 *                       named (discard: the named files the caller did not
 *                       take too), frees.
 * The helper's signal mask is the caller's (the solver blocks SIGINT/SIGTERM
 * before: interrupt.h).  A run killed outright may leave spares behind (the
 * next ./build.sh run into the directory clears it). */
#ifndef BK_PRECREATE_H
#define BK_PRECREATE_H

#include <pthread.h>
#include <stdio.h>

#define BK_PRECREATE_NAME 32   /* the longest file name in the directory */

typedef struct bk_precreate {
    int nnamed, nspare, n;   /* slots: named 0 .. nnamed-1, spares nnamed .. n-1 */
    char *path;              /* owned: [n pathlen] */
    size_t dirlen, pathlen;  /* the directory's length; room per path */
    int *state;              /* owned: [n] (precreate.c) */
    int *fd, *err;           /* owned: [n] the helper's result */
    int threaded, ready;     /* ready: mu made */
    pthread_t thread;
    void *stack;             /* owned: the helper's */
    pthread_mutex_t mu;
} bk_precreate;

int bk_precreate_init(bk_precreate *p, const char *dir, int nnamed, int nspare);
void bk_precreate_want(bk_precreate *p, int k, const char *dir, const char *name);
void bk_precreate_start(bk_precreate *p);
int bk_precreate_named(bk_precreate *p, int k);
FILE *bk_precreate_stream(bk_precreate *p, int *slot);
int bk_precreate_rename(bk_precreate *p, int slot, const char *path);
void bk_precreate_end(bk_precreate *p, int discard);

#endif
