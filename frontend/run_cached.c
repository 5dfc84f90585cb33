/* run_cached.c -- `./build.sh run` without Python when an identical run was
 * made before: the launcher build.sh starts first for `run`.
 *
 * A run is identical when the run cache (out/cache/run/, written by
 * gen/cache.py record()) has an entry for its key -- the scene file's path and
 * bytes, the --set strings and the state of every file of gen/ and runtime/
 * (run_key.h) -- whose solver and kernel files are in the state it records.
 * Then this program does what the Python front end does for such a run
 * (gen/pipeline.py run(reuse=True), gen/cli.py run_and_report): clears the results directory, writes the cached model file
 * into it, runs the solver with SIGINT/SIGTERM passed on, and prints the
 * summary (console_summary.h) -- the same files, output and exit status.  The
 * solver writes the scene's warnings into summary.json itself (they are in the
 * model file), so a --quiet run, which prints nothing after the solve, becomes
 * the solver (exec with SIGINT/SIGTERM blocked: a signal stays pending until
 * the solver polls it) instead of waiting for it.
 *
 * build.sh starts this program when it is newer than build.sh; this program
 * checks that it is newer than its own sources too (stale(); with
 * BK_RUN_CACHED_CHECKED=1 build.sh has just done so) and else goes back to
 * build.sh's `run` with BK_RUN_CACHED_STALE=1, which rebuilds it.
 *
 * Anything else -- a command line of another form, a scene not run before or
 * changed since, a results directory with foreign files, a missing solver --
 * goes to the Python front end unchanged: this program runs
 * `build.sh run ARGS...` with BK_NO_FAST_RUN=1.
 *
 * Usage (from build.sh, in the repository, BK_ROOT = the repository):
 *   run_cached SCENE [--set K=V]... [--out DIR] [--threads N] [--quiet|--verbose]
 *   run_cached --print-key SCENE [--set K=V]...   the run's cache key (tests)
 * With BK_RUN_CACHED_ONLY=1 a run it cannot take exits 3 with the reason on
 * stderr instead of going to Python (tests; "why is my run not fast"). */
#define _DEFAULT_SOURCE
#include "console_summary.h"
#include "python_start.h"
#include "read_file.h"
#include "run_dir.h"
#include "run_key.h"
#include "scene_warnings.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#define REUSED "  model and solver of an identical earlier run (out/cache/run/)"

typedef struct {                /* the common command-line forms (gen/cli.py parse) */
    const char *scene, *out;
    char **sets;
    int nsets, quiet, verbose, threads;
} args;

typedef struct {                /* an entry of the run cache (gen/cache.py write_entry) */
    char scene[PATH_MAX], solver[PATH_MAX], name[256], analysis[64];
    long long size, mtime_ns;
    char **warning;           /* the scene reader's warnings (malloc'd, nwarnings of them) */
    int nwarnings;
    char *kernels;            /* the kernel lines' "NAME SIZE MTIME_NS", one a line (malloc'd) */
    size_t kernels_len;
} entry;

static void free_entry(entry *e)
{
    for (int i = 0; i < e->nwarnings; i++)
        free(e->warning[i]);
    free(e->warning);
    free(e->kernels);
    e->warning = NULL;
    e->kernels = NULL;
    e->nwarnings = 0;
}

/* The one process-wide value: the solver's pid, for the signal handler. */
static volatile sig_atomic_t child_pid;

static void pass_on(int sig)
{
    if (child_pid > 0)
        kill((pid_t)child_pid, sig);
}

static int parse(int argc, char **argv, args *a)
{
    *a = (args){0};
    a->sets = calloc((size_t)argc + 1, sizeof *a->sets);
    if (!a->sets)
        return -1;
    for (int i = 0; i < argc; i++) {
        const char *s = argv[i];
        if ((!strcmp(s, "--set") || !strcmp(s, "--out") || !strcmp(s, "--threads")) && i + 1 < argc) {
            const char *v = argv[++i];
            if (!strcmp(s, "--set")) {
                a->sets[a->nsets++] = (char *)v;
            } else if (!strcmp(s, "--out")) {
                a->out = v;
            } else {
                if (!*v || strspn(v, "0123456789") != strlen(v) || strlen(v) > 5 || atoi(v) < 1 || atoi(v) > 1024)
                    return -1;
                a->threads = atoi(v);
            }
        } else if (!strcmp(s, "--quiet")) {
            a->quiet = 1;
        } else if (!strcmp(s, "--verbose")) {
            a->verbose = 1;
        } else if (s[0] == '-' || a->scene) {
            return -1;
        } else {
            a->scene = s;
        }
    }
    return a->scene && !(a->quiet && a->verbose) ? 0 : -1;
}

/* The scene file of a scene argument (gen/pipeline.py scene_location), real. */
static char *scene_file(const char *root, const char *spec)
{
    size_t n = strlen(spec);
    char *p;
    if ((n >= 5 && !strcmp(spec + n - 5, ".toml")) || strchr(spec, '/')) {
        p = bk_caller_path(spec);
    } else {
        p = malloc(strlen(root) + n + 16);
        if (p)
            sprintf(p, "%s/models/%s.toml", root, spec);
    }
    if (!p)
        return NULL;
    char *real = realpath(p, NULL);
    free(p);
    struct stat st;
    if (real && (stat(real, &st) != 0 || !S_ISREG(st.st_mode))) {
        free(real);
        real = NULL;
    }
    return real;
}

static int field(const char *line, size_t n, const char *name, char *dst, size_t cap)
{
    size_t k = strlen(name);
    if (n <= k || strncmp(line, name, k) || line[k] != ' ' || n - k - 1 >= cap)
        return 0;
    memcpy(dst, line + k + 1, n - k - 1);
    dst[n - k - 1] = '\0';
    return 1;
}

/* gen/cache.py read_entry: one "field value" line each, then "warning ..."
 * and "kernel NAME SIZE MTIME_NS" lines. */
static int read_entry(const char *path, entry *e)
{
    size_t len;
    char *text = bk_read_file(path, &len);
    if (!text)
        return -1;
    *e = (entry){0};
    char version[8] = "", size[32] = "", mtime[32] = "";
    int seen = 0;
    for (char *line = text; *line;) {
        char *nl = strchr(line, '\n');
        size_t n = nl ? (size_t)(nl - line) : strlen(line);
        seen |= field(line, n, "version", version, sizeof version) << 0;
        seen |= field(line, n, "scene", e->scene, sizeof e->scene) << 1;
        seen |= field(line, n, "solver", e->solver, sizeof e->solver) << 2;
        seen |= field(line, n, "solver_size", size, sizeof size) << 3;
        seen |= field(line, n, "solver_mtime_ns", mtime, sizeof mtime) << 4;
        seen |= field(line, n, "name", e->name, sizeof e->name) << 5;
        seen |= field(line, n, "analysis", e->analysis, sizeof e->analysis) << 6;
        if (n >= 7 && !strncmp(line, "warning", 7) && (n == 7 || line[7] == ' ')) {
            char **w = realloc(e->warning, (size_t)(e->nwarnings + 1) * sizeof *w);
            char *v = malloc(n >= 8 ? n - 7 : 1);
            if (!w || !v) {
                free(v);
                if (w)
                    e->warning = w;
                seen = 0;
                break;
            }
            e->warning = w;
            memcpy(v, line + 8 - (n == 7), n >= 8 ? n - 8 : 0);
            v[n >= 8 ? n - 8 : 0] = '\0';
            e->warning[e->nwarnings++] = v;
        }
        if (n > 7 && !strncmp(line, "kernel ", 7)) {
            char *k = realloc(e->kernels, e->kernels_len + n - 7 + 2);
            if (!k) {
                seen = 0;
                break;
            }
            e->kernels = k;
            memcpy(k + e->kernels_len, line + 7, n - 7);
            e->kernels_len += n - 7;
            k[e->kernels_len++] = '\n';
            k[e->kernels_len] = '\0';
        }
        line += n + (nl != NULL);
    }
    free(text);
    if (seen != 0x7f || strcmp(version, "2") || !e->kernels) {
        free_entry(e);
        return -1;
    }
    e->size = atoll(size);
    e->mtime_ns = atoll(mtime);
    return 0;
}

/* gen/cache.py lookup: every kernel file of the entry is in the state it
 * records (size and modification time); 0 when so. */
static int kernels_unchanged(const char *root, const entry *e)
{
    char dir[PATH_MAX];
    snprintf(dir, sizeof dir, "%s/out/kernels", root);
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    int rc = 0;
    for (char *line = e->kernels; rc == 0 && *line;) {
        char *nl = strchr(line, '\n'), name[256];
        long long size, ns;
        struct stat st;
        *nl = '\0';
        if (sscanf(line, "%255s %lld %lld", name, &size, &ns) != 3 || fstatat(fd, name, &st, 0) != 0 ||
            st.st_size != size || bk_stat_ns(&st) != ns)
            rc = -1;
        *nl = '\n';
        line = nl + 1;
    }
    close(fd);
    return rc;
}

static int write_file(const char *path, const char *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    size_t w = fwrite(data, 1, n, f);
    return fclose(f) == 0 && w == n ? 0 : -1;
}

/* gen/pipeline.py write_interrupted_summary: a summary.json for a run stopped
 * by a signal before the solver wrote one; 1 when it wrote one. */
static int interrupted_summary(const char *dir, const entry *e, int rc)
{
    char path[PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/summary.json", dir);
    if (access(path, F_OK) == 0)
        return 0;
    const char *sig = rc == 130 ? "SIGINT" : "SIGTERM";
    FILE *f = fopen(path, "w");
    if (!f)
        return 0;
    fprintf(f, "{\n \"scene\": \"%s\",\n \"analysis\": \"%s\",\n \"converged\": false,\n \"interrupted\": true,\n"
               " \"signal\": \"%s\",\n \"steps\": 0,\n \"newton_iterations\": 0,\n \"cutbacks\": 0,\n"
               " \"wall_s\": 0.0,\n \"sensors\": {},\n \"warnings\": [],\n"
               " \"error\": \"interrupted by %s before the solve started\"\n}\n",
            e->name, e->analysis, sig, sig);
    return fclose(f) == 0;
}

/* The solver on the model file, signals passed on; the exit status as the
 * Python front end reports it. */
static int run_solver(const char *solver, const char *dir, const args *a)
{
    char model[PATH_MAX + 16];
    snprintf(model, sizeof model, "%s/model.dat", dir);
    char *cmd[5] = {(char *)solver, model, (char *)dir, NULL, NULL};
    if (a->verbose)
        cmd[3] = "--verbose";
    else if (a->quiet)
        cmd[3] = "--quiet";
    if (a->quiet) {             /* nothing to do after the solve: become the solver */
        sigset_t stop;
        sigemptyset(&stop);
        sigaddset(&stop, SIGINT);
        sigaddset(&stop, SIGTERM);
        sigprocmask(SIG_BLOCK, &stop, NULL);
        fflush(NULL);
        execv(solver, cmd);
        sigprocmask(SIG_UNBLOCK, &stop, NULL);
        return -1;
    }
    struct sigaction sa = {0}, old_int, old_term;
    sa.sa_handler = pass_on;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        sigaction(SIGINT, &old_int, NULL);
        sigaction(SIGTERM, &old_term, NULL);
        execv(solver, cmd);
        _exit(127);
    }
    if (pid < 0)
        return -1;
    child_pid = pid;
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    child_pid = 0;
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    int sig = WTERMSIG(status);
    return sig == SIGINT ? 130 : sig == SIGTERM ? 143 : (-sig) & 0xff;
}

/* 1 when a file of frontend/ is not older than this program (its build,
 * out/bin/run-cached), or either cannot be read: build.sh's `run` then
 * rebuilds it (its shell test of each file cost 0.4 ms of a 10 ms command). */
static int stale(const char *root)
{
    char path[PATH_MAX];
    const long long mine = bk_mtime_ns(root, "out/bin/run-cached");
    snprintf(path, sizeof path, "%s/frontend", root);
    DIR *d = mine < 0 ? NULL : opendir(path);
    if (!d)
        return 1;
    int old = 1;
    for (struct dirent *de; old && (de = readdir(d)) != NULL;) {
        const char *dot = strrchr(de->d_name, '.');
        if (dot && dot != de->d_name && (strcmp(dot, ".c") == 0 || strcmp(dot, ".h") == 0))
            old = mine > bk_mtime_ns(path, de->d_name);
    }
    closedir(d);
    return !old;
}

/* build.sh's `run` with the same arguments (returns only when it cannot be
 * started: 1). */
static int build_sh_run(const char *root, int argc, char **argv)
{
    char build[PATH_MAX];
    snprintf(build, sizeof build, "%s/build.sh", root ? root : ".");
    char **cmd = calloc((size_t)argc + 3, sizeof *cmd);
    if (!cmd)
        return 1;
    cmd[0] = build;
    cmd[1] = "run";
    for (int i = 0; i < argc; i++)
        cmd[i + 2] = argv[i];
    fflush(NULL);
    execv(build, cmd);
    fprintf(stderr, "error: cannot start %s: %s\n", build, strerror(errno));
    free(cmd);
    return 1;
}

/* Back to build.sh's `run`, which rebuilds this program and starts it again. */
static int rebuild(const char *root, int argc, char **argv)
{
    setenv("BK_RUN_CACHED_STALE", "1", 1);
    return build_sh_run(root, argc, argv);
}

/* The Python front end, with the same arguments: started here as build.sh's
 * `run` starts it when the packages are stamped installed (python_start.h),
 * else through build.sh, which installs them. */
static int fall_back(const char *root, int argc, char **argv)
{
    setenv("BK_NO_FAST_RUN", "1", 1);
    bk_start_python_front_end(root, argc, argv);
    return build_sh_run(root, argc, argv);
}

int main(int argc, char **argv)
{
    const char *root = getenv("BK_ROOT");
    int print_key = argc > 1 && !strcmp(argv[1], "--print-key");
    char **user = argv + 1 + print_key;
    int nuser = argc - 1 - print_key;
    if (!root || *root != '/')
        return print_key ? 1 : fall_back(root, nuser, user);
    const char *checked = getenv("BK_RUN_CACHED_CHECKED");   /* (by build.sh, just now) */
    if (!print_key && !(checked && !strcmp(checked, "1")) && stale(root))
        return rebuild(root, nuser, user);
    unsetenv("BK_RUN_CACHED_CHECKED");
    args a = {0};
    entry e = {0};
    int rc = -1;                         /* the solver's exit status; -1: the run goes to Python */
    const char *why = "not one of the command line's common forms";
    char *scene = NULL, *dest = NULL, *model = NULL, *cache_dir = NULL, *fp = NULL;
    char key[33];
    if (parse(nuser, user, &a) != 0)
        goto done;
    why = "no such scene file";
    if ((scene = scene_file(root, a.scene)) == NULL ||
        bk_run_key(root, scene, a.sets, a.nsets, key, print_key ? NULL : &fp) != 0)
        goto done;
    if (print_key) {
        puts(key);
        return 0;
    }
    cache_dir = malloc(strlen(root) + 64);
    if (!cache_dir)
        goto done;
    sprintf(cache_dir, "%s/out/cache/run/%s.run", root, key);
    struct stat st;
    why = "no identical earlier run (scene, --set values, gen/, runtime/, out/kernels/), or its solver was "
          "rebuilt since";
    if (read_entry(cache_dir, &e) != 0 || stat(e.solver, &st) != 0 || st.st_size != e.size ||
        bk_stat_ns(&st) != e.mtime_ns ||
        kernels_unchanged(root, &e) != 0)
        goto done;
    size_t model_len;
    sprintf(cache_dir, "%s/out/cache/run/%s.dat", root, key);
    if ((model = bk_read_file(cache_dir, &model_len)) == NULL)
        goto done;
    if (a.out) {
        char *p = bk_caller_path(a.out);
        dest = p ? bk_normpath(p) : NULL;
        free(p);
    } else {
        dest = malloc(strlen(root) + strlen(e.name) + 16);
        if (dest)
            sprintf(dest, "%s/out/runs/%s", root, e.name);
    }
    why = "the results directory cannot be used";
    if (!dest || bk_prepare_run_dir(dest) != 0)
        goto done;
    char path[PATH_MAX + 16];
    snprintf(path, sizeof path, "%s/model.dat", dest);
    if (write_file(path, model, model_len) != 0)
        goto done;
    if (!a.quiet) {
        for (int i = 0; i < e.nwarnings; i++)
            fprintf(stderr, "warning: %s: %s\n", e.name, e.warning[i]);
        if (a.verbose)
            fprintf(stderr, "%s\n", REUSED);
    }
    snprintf(path, sizeof path, "%s/out/bin", root);
    bk_link_scene(path, e.name, e.solver);
    if (a.threads) {
        char t[16];
        snprintf(t, sizeof t, "%d", a.threads);
        setenv("OMP_NUM_THREADS", t, 1);
    }
    rc = run_solver(e.solver, dest, &a);
    why = "the solver could not be started";
    if (rc < 0)
        goto done;
    if ((rc == 130 || rc == 143) && interrupted_summary(dest, &e, rc) &&
        bk_add_scene_warnings(dest, e.warning, e.nwarnings) != 0)
        fprintf(stderr, "warning: %s/summary.json: the scene's warnings could not be added to it\n", dest);
    if (!a.quiet) {
        size_t n = strlen(dest);
        while (n > 0 && dest[n - 1] == '/')
            dest[--n] = '\0';
        snprintf(path, sizeof path, "%s/summary.json", dest);
        if (access(path, F_OK) == 0 && bk_print_summary(dest, dest) != 0)
            fprintf(stderr, "warning: %s: not the solver's summary; see the file\n", path);
    }
    fflush(stdout);
done:                                   /* (rc < 0: the run goes to Python) */
    free_entry(&e);
    free(scene);
    free(dest);
    free(model);
    free(cache_dir);
    free(a.sets);
    /* for Python, the fingerprint computed for the key, so that it need not
     * walk gen/ and runtime/ again (1.8 ms); its pid is this one's, which the
     * exec of Python keeps, directly or through build.sh */
    if (rc < 0 && fp)
        setenv("BK_FINGERPRINT", fp, 1);
    free(fp);
    if (rc >= 0)
        return rc;
    if (print_key)
        return 1;
    const char *only = getenv("BK_RUN_CACHED_ONLY");
    if (only && !strcmp(only, "1")) {
        fprintf(stderr, "run-cached: %s\n", why);
        return 3;
    }
    return fall_back(root, nuser, user);
}
