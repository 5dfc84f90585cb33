/* json.c -- JSON values for summary.json (see json.h). */
#include "base/json.h"

#include <ctype.h>
#include <math.h>
#include <string.h>

void bk_json_string(FILE *fp, const char *s)
{
    fputc('"', fp);
    for (; *s; ++s) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(fp, "\\%c", c);
        else if (c < 0x20)
            fprintf(fp, "\\u%04x", c);
        else
            fputc(c, fp);
    }
    fputc('"', fp);
}

void bk_json_num(FILE *fp, double v)
{
    if (isfinite(v))
        fprintf(fp, "%.17g", v);
    else
        fprintf(fp, "null");
}

void bk_json_vec3(FILE *fp, const double *v)
{
    fputc('[', fp);
    for (int i = 0; i < 3; ++i) {
        fprintf(fp, "%s", i ? ", " : "");
        bk_json_num(fp, v[i]);
    }
    fputc(']', fp);
}

void bk_json_repair(const char *p, char *out)
{
    while (*p) {
        if (*p == '"') {                         /* a string: copied as it is */
            *out++ = *p++;
            while (*p && *p != '"') {
                if (*p == '\\' && p[1])
                    *out++ = *p++;
                *out++ = *p++;
            }
            if (*p)
                *out++ = *p++;
        } else if (isdigit((unsigned char)*p) || *p == '.' ||
                   ((*p == '-' || *p == '+') && (isdigit((unsigned char)p[1]) || p[1] == '.'))) {
            do                                   /* a number, its exponent included */
                *out++ = *p++;
            while (isalnum((unsigned char)*p) || *p == '.' || ((*p == '-' || *p == '+') && (p[-1] == 'e' ||
                                                                                         p[-1] == 'E')));
        } else if (isalpha((unsigned char)*p) || ((*p == '-' || *p == '+') && isalpha((unsigned char)p[1]))) {
            const char *w = p + !isalpha((unsigned char)*p), *e = w;
            while (isalnum((unsigned char)*e))
                ++e;
            size_t n = (size_t)(e - p);
            if ((n == 4 && !strncmp(p, "true", 4)) || (n == 5 && !strncmp(p, "false", 5)) ||
                (n == 4 && !strncmp(p, "null", 4)))
                memcpy(out, p, n), out += n;
            else
                memcpy(out, "null", 4), out += 4;
            p = e;
        } else {
            *out++ = *p++;
        }
    }
    *out = 0;
}
