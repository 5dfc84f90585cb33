/* run_dir.c -- paths and the results directory of a run (run_dir.h). */
#define _XOPEN_SOURCE 700
#include "run_dir.h"

#include <errno.h>
#include <dirent.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MARKER ".beamkit-run"
#define MARKER_TEXT "results of ./build.sh run; cleared on the next run into this directory\n"

static char *join(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    char *s = malloc(la + lb + 2);
    if (!s)
        return NULL;
    memcpy(s, a, la);
    size_t n = la;
    if (la && a[la - 1] != '/')
        s[n++] = '/';
    memcpy(s + n, b, lb + 1);
    return s;
}

char *bk_caller_path(const char *p)
{
    if (p[0] == '~') {
        const char *home = getenv("HOME");
        if ((p[1] != '/' && p[1] != '\0') || !home || !*home)
            return NULL;
        return join(home, p[1] ? p + 2 : "");
    }
    if (p[0] == '/')
        return strdup(p);
    const char *cwd = getenv("BK_CALLER_CWD");
    char here[4096];
    if (!cwd || !*cwd)
        cwd = getcwd(here, sizeof here);
    return cwd ? join(cwd, p) : NULL;
}

char *bk_normpath(const char *p)
{
    size_t n = strlen(p);
    char *out = malloc(n + 2), *work = strdup(p);
    const char **part = malloc((n + 1) * sizeof *part);
    if (!out || !work || !part) {
        free(out);
        free(work);
        free(part);
        return NULL;
    }
    int abs = p[0] == '/', np = 0;
    for (char *tok = strtok(work, "/"); tok; tok = strtok(NULL, "/")) {
        if (!strcmp(tok, "."))
            continue;
        if (!strcmp(tok, "..")) {
            if (np > 0 && strcmp(part[np - 1], ".."))
                np--;
            else if (!abs)
                part[np++] = tok;
            continue;
        }
        part[np++] = tok;
    }
    size_t k = 0;
    if (abs)
        out[k++] = '/';
    if (abs && n >= 2 && p[1] == '/' && p[2] != '/')        /* POSIX keeps a leading "//" */
        out[k++] = '/';
    for (int i = 0; i < np; i++) {
        size_t l = strlen(part[i]);
        if (i)
            out[k++] = '/';
        memcpy(out + k, part[i], l);
        k += l;
    }
    if (k == 0)
        out[k++] = '.';
    out[k] = '\0';
    free(work);
    free(part);
    return out;
}

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    if (ftw->level == 0 || (ftw->level == 1 && !strcmp(path + ftw->base, MARKER)))
        return 0;
    return remove(path) == 0 ? 0 : -1;
}

static int make_dirs(const char *dir)
{
    char *d = strdup(dir);
    if (!d)
        return -1;
    for (char *s = d + 1; *s; s++)
        if (*s == '/') {
            *s = '\0';
            if (mkdir(d, 0777) != 0 && errno != EEXIST) {
                free(d);
                return -1;
            }
            *s = '/';
        }
    int rc = mkdir(d, 0777) == 0 || errno == EEXIST ? 0 : -1;
    free(d);
    return rc;
}

int bk_prepare_run_dir(const char *dir)
{
    struct stat st;
    char *marker = join(dir, MARKER);
    if (!marker)
        return -1;
    int rc = -1;
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode))
            goto done;
        DIR *d = opendir(dir);
        if (!d)
            goto done;
        int entries = 0;
        struct dirent *e;
        while ((e = readdir(d)) != NULL)
            entries += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
        closedir(d);
        if (entries && access(marker, F_OK) != 0)
            goto done;                   /* foreign files: the Python front end says why */
        if (nftw(dir, remove_one, 16, FTW_DEPTH | FTW_PHYS) != 0)   /* all but the marker */
            goto done;
    } else if (make_dirs(dir) != 0) {
        goto done;
    }
    /* (kept when it holds its text: truncating a file costs ext4 ~0.25 ms) */
    char now[sizeof MARKER_TEXT];
    FILE *f = fopen(marker, "rb");
    size_t got = f ? fread(now, 1, sizeof now, f) : 0;
    if (f)
        fclose(f);
    if (got == sizeof MARKER_TEXT - 1 && !memcmp(now, MARKER_TEXT, got)) {
        rc = 0;
        goto done;
    }
    f = fopen(marker, "w");
    if (!f)
        goto done;
    fputs(MARKER_TEXT, f);
    rc = fclose(f) == 0 ? 0 : -1;
done:
    free(marker);
    return rc;
}

void bk_link_scene(const char *bin, const char *name, const char *solver)
{
    const char *base = strrchr(solver, '/');
    base = base ? base + 1 : solver;
    char *link = join(bin, name);
    if (!link)
        return;
    char now[4096];
    ssize_t n = readlink(link, now, sizeof now - 1);
    if (n >= 0) {
        now[n] = '\0';
        if (!strcmp(now, base)) {
            free(link);
            return;
        }
    }
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", link, (long)getpid());
    if (symlink(base, tmp) != 0 || rename(tmp, link) != 0)
        unlink(tmp);
    free(link);
}
