/* python_start.c -- the Python front end started as build.sh does (see
 * python_start.h). */
#define _DEFAULT_SOURCE
#include "python_start.h"
#include "read_file.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PYTHON "/usr/bin/python3"

/* 1 when the package stamp exists and is no older than build.sh. */
static int deps_stamped(const char *root)
{
    const long long stamp = bk_mtime_ns(root, "out/.deps-installed"), build = bk_mtime_ns(root, "build.sh");
    return stamp >= 0 && build >= 0 && stamp >= build;
}

void bk_start_python_front_end(const char *root, int argc, char **argv)
{
    if (!root || *root != '/' || !deps_stamped(root))
        return;
    const char *old = getenv("PYTHONPATH");
    char *pypath = malloc(strlen(root) + (old ? strlen(old) : 0) + 2);
    char *cache = malloc(strlen(root) + sizeof "/out/pycache");
    char **cmd = calloc((size_t)argc + 8, sizeof *cmd);
    if (pypath && cache && cmd) {
        if (old && *old)
            sprintf(pypath, "%s:%s", root, old);
        else
            strcpy(pypath, root);
        sprintf(cache, "%s/out/pycache", root);
        int k = 0;
        cmd[k++] = PYTHON;
        cmd[k++] = "-S";
        cmd[k++] = "-X";
        cmd[k++] = "frozen_modules=on";
        cmd[k++] = "-c";
        cmd[k++] = "import sys; from gen.cli import run_command; run_command(sys.argv[1:])";
        cmd[k++] = "run";
        for (int i = 0; i < argc; i++)
            cmd[k++] = argv[i];
        char here[PATH_MAX];        /* the caller's directory, as build.sh passes it on */
        if (!getenv("BK_CALLER_CWD") && getcwd(here, sizeof here))
            setenv("BK_CALLER_CWD", here, 1);
        if (chdir(root) == 0 && setenv("PYTHONPATH", pypath, 1) == 0 && setenv("PYTHONPYCACHEPREFIX", cache, 1) == 0 &&
            unsetenv("PYTHONDONTWRITEBYTECODE") == 0) {
            fflush(NULL);
            execv(PYTHON, cmd);
        }
    }
    free(pypath);
    free(cache);
    free(cmd);
}
