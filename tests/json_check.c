/* json_check.c -- bk_json_repair and bk_json_num (runtime/base/json.c): each
 * argument repaired, one output line each; then the numbers NaN, -NaN, +inf,
 * -inf, 0.1 through bk_json_num on one line as a JSON array. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/json.h"

int main(int argc, char **argv)
{
    for (int k = 1; k < argc; ++k) {
        char *out = malloc(2 * strlen(argv[k]) + 1);
        if (!out)
            return 1;
        bk_json_repair(argv[k], out);
        printf("%s\n", out);
        free(out);
    }
    const double v[5] = {NAN, -NAN, INFINITY, -INFINITY, 0.1};
    printf("[");
    for (int k = 0; k < 5; ++k) {
        printf("%s", k ? ", " : "");
        bk_json_num(stdout, v[k]);
    }
    printf("]\n");
    return 0;
}
