/* step_control_check.c -- drives the dynamic step controller (runtime/solver/step_control.h)
 * through scripted outcomes and prints the step sizes it chooses, one "event h" line each. */
#include <stdio.h>
#include <string.h>

#include "solver/step_control.h"

/* script: a string of outcomes, 'f' a failed step, 's' an accepted one (fast
 * Newton), 'S' an accepted one after a slow Newton (20 iterations); fixed steps. */
int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: step_control_check SCRIPT [ERR_RATIO]\n");
        return 64;
    }
    double ratio = 0.0;
    if (argc > 2 && sscanf(argv[2], "%lf", &ratio) != 1)
        return 64;
    bk_step_ctl c;
    bk_step_ctl_init(&c, 1.0);
    double h = 1.0;
    for (const char *p = argv[1]; *p; ++p) {
        if (*p == 'f')
            h = bk_step_ctl_failed(&c, h);
        else
            h = bk_step_ctl_accepted(&c, h, *p == 'S' ? 20 : 3, ratio);
        printf("%c %.17g\n", *p, h);
    }
    printf("hold %d failures %d\n", c.hold, c.failures);
    return 0;
}
