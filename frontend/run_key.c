/* run_key.c -- the run cache's key (see run_key.h): SHA-256 of a tag, the
 * scene's path and bytes, the --set strings, and the fingerprint of the files
 * of gen/ and runtime/ (with their subfolders but __pycache__):
 * "path\0size\0mtime_ns" per file, sorted, joined by newlines.  (The files of
 * out/kernels/ a run is made from are in its entry: run_cached.c.) */
#define _DEFAULT_SOURCE            /* d_type, DT_DIR */
#include "run_key.h"
#include "read_file.h"
#include "sha256.h"

#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct {              /* one file of the fingerprint: "path\0size\0mtime_ns" */
    char *text;
    size_t len;
} item;

typedef struct {
    item *v;
    size_t n, cap;
    size_t cut;               /* strlen(root) + 1: what a path loses to become relative */
    int failed;
} items;

static void add(items *it, const char *path, const struct stat *st)
{
    if (it->n == it->cap) {
        size_t cap = it->cap ? 2 * it->cap : 512;
        item *v = realloc(it->v, cap * sizeof *v);
        if (!v) {
            it->failed = 1;
            return;
        }
        it->v = v;
        it->cap = cap;
    }
    const char *rel = path + it->cut;
    long long ns = bk_stat_ns(st);
    char nums[64];
    int nn = snprintf(nums, sizeof nums, "%lld%c%lld", (long long)st->st_size, '\0', ns);
    size_t lr = strlen(rel), len = lr + 1 + (size_t)nn;
    char *t = malloc(len);
    if (!t) {
        it->failed = 1;
        return;
    }
    memcpy(t, rel, lr);
    t[lr] = '\0';
    memcpy(t + lr + 1, nums, (size_t)nn);
    it->v[it->n].text = t;
    it->v[it->n].len = len;
    it->n++;
}

/* os.scandir's walk of gen/cache.py: a directory entry (not followed when a
 * link) is entered when recursive and not __pycache__; a file (a link is
 * followed) is listed with its stat.  path: the directory's path (for the
 * items), fd: the directory, opened (closed here). */
static void walk(items *it, const char *path, int fd, int recursive)
{
    DIR *d = fdopendir(fd);
    if (!d) {
        close(fd);
        return;
    }
    size_t lp = strlen(path);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        size_t ln = strlen(e->d_name);
        char *sub = malloc(lp + ln + 2);
        if (!sub) {
            it->failed = 1;
            break;
        }
        memcpy(sub, path, lp);
        sub[lp] = '/';
        memcpy(sub + lp + 1, e->d_name, ln + 1);
        struct stat st;
        int isdir = e->d_type == DT_DIR;
        if (e->d_type == DT_UNKNOWN && fstatat(dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0)
            isdir = S_ISDIR(st.st_mode);
        if (isdir) {
            if (recursive && strcmp(e->d_name, "__pycache__")) {
                int sfd = openat(dirfd(d), e->d_name, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
                if (sfd >= 0)
                    walk(it, sub, sfd, 1);
            }
        } else if (fstatat(dirfd(d), e->d_name, &st, 0) == 0 && S_ISREG(st.st_mode)) {
            add(it, sub, &st);
        }
        free(sub);
    }
    closedir(d);
}

/* Python's order of str: code points, which is UTF-8's byte order; a prefix first. */
static int by_text(const void *a, const void *b)
{
    const item *x = a, *y = b;
    size_t n = x->len < y->len ? x->len : y->len;
    int c = memcmp(x->text, y->text, n);
    if (c)
        return c;
    return (x->len > y->len) - (x->len < y->len);
}

static int read_file(const char *path, bk_sha256 *h)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0)
        return -1;
    char buf[65536];
    ssize_t n;
    while ((n = read(fd, buf, sizeof buf)) > 0)
        bk_sha256_update(h, buf, (size_t)n);
    close(fd);
    return n < 0 ? -1 : 0;
}

/* The fingerprint's text for the environment: "PID:" and the items joined by
 * newlines, tabs for their NULs; NULL when a path holds a tab or a newline,
 * when the text is longer than BK_ENV_FINGERPRINT_MAX (an environment string
 * may hold 128 kB: a longer one would make the exec of Python fail; ~15 kB
 * now), or when memory runs out. */
#define BK_ENV_FINGERPRINT_MAX ((size_t)64 << 10)
static char *env_text(const items *it)
{
    size_t len = 32;
    for (size_t i = 0; i < it->n; i++)
        len += it->v[i].len + 1;
    if (len > BK_ENV_FINGERPRINT_MAX)
        return NULL;
    char *t = malloc(len), *w = t;
    if (!t)
        return NULL;
    w += sprintf(w, "%ld:", (long)getpid());
    for (size_t i = 0; i < it->n; i++) {
        if (i)
            *w++ = '\n';
        const char *x = it->v[i].text;
        for (size_t k = 0; k < it->v[i].len; k++) {
            if (x[k] == '\t' || x[k] == '\n') {
                free(t);
                return NULL;
            }
            *w++ = x[k] ? x[k] : '\t';
        }
    }
    *w = '\0';
    return t;
}

int bk_run_key(const char *root, const char *scene, char *const *sets, int nsets, char key[33], char **fp)
{
    if (fp)
        *fp = NULL;
    static const char tag[] = "beamkit-run-cache 2";
    bk_sha256 h;
    bk_sha256_init(&h);
    bk_sha256_update(&h, tag, sizeof tag);              /* (with its NUL) */
    bk_sha256_update(&h, scene, strlen(scene) + 1);
    if (read_file(scene, &h) != 0)
        return -1;
    bk_sha256_update(&h, "", 1);
    for (int i = 0; i < nsets; i++)
        bk_sha256_update(&h, sets[i], strlen(sets[i]) + 1);

    items it = {.cut = strlen(root) + 1};
    static const struct { const char *dir; int recursive; } sources[] = {
        {"gen", 1}, {"runtime", 1}};
    for (size_t s = 0; s < sizeof sources / sizeof *sources; s++) {
        size_t lr = strlen(root), ls = strlen(sources[s].dir);
        char *dir = malloc(lr + ls + 2);
        if (!dir) {
            it.failed = 1;
            break;
        }
        memcpy(dir, root, lr);
        dir[lr] = '/';
        memcpy(dir + lr + 1, sources[s].dir, ls + 1);
        int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (fd >= 0)
            walk(&it, dir, fd, sources[s].recursive);
        free(dir);
    }
    int rc = it.failed ? -1 : 0;
    if (!rc) {
        qsort(it.v, it.n, sizeof *it.v, by_text);
        for (size_t i = 0; i < it.n; i++) {
            if (i)
                bk_sha256_update(&h, "\n", 1);
            bk_sha256_update(&h, it.v[i].text, it.v[i].len);
        }
        char hex[65];
        bk_sha256_hex(&h, hex);
        memcpy(key, hex, 32);
        key[32] = '\0';
        if (fp)
            *fp = env_text(&it);
    }
    for (size_t i = 0; i < it.n; i++)
        free(it.v[i].text);
    free(it.v);
    return rc;
}
