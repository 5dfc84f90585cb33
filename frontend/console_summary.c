/* console_summary.c -- the run's summary on the console (console_summary.h),
 * from summary.json read with json_tree.h. */
#define _POSIX_C_SOURCE 200809L
#include "console_summary.h"
#include "json_tree.h"
#include "read_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A JSON string's characters as text (the escapes the solver writes decoded). */
static void put_string(const bk_jnode *s)
{
    for (size_t i = 0; i < s->len; i++) {
        char c = s->text[i];
        if (c != '\\' || i + 1 >= s->len) {
            putchar(c);
            continue;
        }
        c = s->text[++i];
        switch (c) {
        case 'n': putchar('\n'); break;
        case 't': putchar('\t'); break;
        case 'r': putchar('\r'); break;
        case 'u':
            if (i + 4 < s->len) {
                char hex[5] = {s->text[i + 1], s->text[i + 2], s->text[i + 3], s->text[i + 4], 0};
                putchar((int)strtol(hex, NULL, 16));
                i += 4;
            }
            break;
        default: putchar(c);
        }
    }
}

/* An integer count as Python prints it (the solver writes them as integers). */
static void put_raw(const bk_json *t, int i)
{
    if (i >= 0)
        fwrite(t->node[i].text, 1, t->node[i].len, stdout);
}

static void put_count(const bk_json *t, int i, const char *word)
{
    put_raw(t, i);
    printf(" %s%s", word, bk_json_num(t, i) == 1 ? "" : "s");
}

static int column(char *header, const char *name)
{
    int k = 0;
    for (char *tok = strtok(header, ",\r\n"); tok; tok = strtok(NULL, ",\r\n"), k++)
        if (!strcmp(tok, name))
            return k;
    return -1;
}

/* The frequency table of a modal run (modes.csv), as print_modes() prints it. */
static void print_modes(const char *dir)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/modes.csv", dir);
    size_t len;
    char *text = bk_read_file(path, &len);
    if (!text)
        return;
    char *save = NULL, *line = strtok_r(text, "\n", &save);
    if (line) {
        static const char *names[4] = {"mode", "frequency_hz", "omega", "scale_m"};
        int col[4];
        for (int c = 0; c < 4; c++) {
            char *h = strdup(line);
            col[c] = h ? column(h, names[c]) : -1;
            free(h);
        }
        int first = 1;
        for (char *row = strtok_r(NULL, "\n", &save); row; row = strtok_r(NULL, "\n", &save)) {
            char *cell[64];
            int nc = 0;
            for (char *p = row; nc < 64;) {
                cell[nc++] = p;
                char *comma = strchr(p, ',');
                if (!comma)
                    break;
                *comma = '\0';
                p = comma + 1;
            }
            int ok = 1;
            for (int c = 0; c < 4; c++)
                ok &= col[c] >= 0 && col[c] < nc;
            if (!ok)
                continue;
            if (first) {
                printf("  %4s  %15s  %15s  %15s\n", "mode", "frequency (Hz)", "omega (rad/s)", "shape scale (m)");
                first = 0;
            }
            printf("  %4d  %15.9g  %15.9g  %15.4g\n", atoi(cell[col[0]]), strtod(cell[col[1]], NULL),
                   strtod(cell[col[2]], NULL), strtod(cell[col[3]], NULL));
        }
        snprintf(path, sizeof path, "%s/modes.pvd", dir);
        if (!first && access(path, F_OK) == 0)
            printf("  mode shapes: modes.pvd (mode_NN.vtu, time value = mode number), displaced by the scale above\n"
                   "  (largest translation 10 %% of the model length, section rotation at most 0.5 rad); point data\n"
                   "  mode_shape is the mode normalized to a largest translation of 1\n");
    }
    free(text);
}

static int is_word(const bk_json *t, int i, const char *w)
{
    return i >= 0 && t->node[i].type == BK_JSTR && t->node[i].len == strlen(w) &&
           !memcmp(t->node[i].text, w, t->node[i].len);
}

int bk_print_summary(const char *run_dir, const char *shown)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/summary.json", run_dir);
    size_t len;
    char *text = bk_read_file(path, &len);
    if (!text)
        return -1;
    bk_json t;
    int rc = -1;
    if (bk_json_parse(text, len, &t) != 0 || t.node[0].type != BK_JOBJ)
        goto done;
    static const char *needed[] = {"scene", "analysis", "converged", "steps", "newton_iterations", "dofs",
                                   "elements", "wall_s", "sensors"};
    for (size_t k = 0; k < sizeof needed / sizeof *needed; k++)
        if (bk_json_get(&t, 0, needed[k]) < 0)
            goto done;
    int scene = bk_json_get(&t, 0, "scene"), analysis = bk_json_get(&t, 0, "analysis");
    int sensors = bk_json_get(&t, 0, "sensors");
    if (t.node[scene].type != BK_JSTR || t.node[analysis].type != BK_JSTR || t.node[sensors].type != BK_JOBJ)
        goto done;
    for (int k = t.node[sensors].first; k >= 0; k = t.node[t.node[k].next].next) {
        int v = t.node[k].next, p = bk_json_get(&t, v, "position"), u = bk_json_get(&t, v, "displacement");
        if (p < 0 || u < 0 || t.node[p].type != BK_JARR || t.node[u].type != BK_JARR || t.node[p].count < 3 ||
            t.node[u].count < 3)
            goto done;
    }
    rc = 0;
    printf("scene ");
    put_string(&t.node[scene]);
    printf(" (");
    put_string(&t.node[analysis]);
    printf("): %s; ", bk_json_truthy(&t, bk_json_get(&t, 0, "converged"))     ? "converged"
                      : bk_json_truthy(&t, bk_json_get(&t, 0, "interrupted")) ? "interrupted (results so far kept)"
                                                                             : "NOT converged");
    int freqs = bk_json_get(&t, 0, "frequencies_hz");
    if (is_word(&t, analysis, "modal") && freqs >= 0 && t.node[freqs].type == BK_JARR) {
        int nm = t.node[freqs].count;           /* a modal run has modes, not steps */
        printf("%d mode%s, ", nm, nm == 1 ? "" : "s");
    } else {
        put_count(&t, bk_json_get(&t, 0, "steps"), "step");
        printf(", ");
        put_count(&t, bk_json_get(&t, 0, "newton_iterations"), "Newton iteration");
        printf(", ");
    }
    put_raw(&t, bk_json_get(&t, 0, "dofs"));
    printf(" DOFs, ");
    put_count(&t, bk_json_get(&t, 0, "elements"), "element");
    printf(", wall %.3f s\n", bk_json_num(&t, bk_json_get(&t, 0, "wall_s")));
    for (int k = t.node[sensors].first; k >= 0; k = t.node[t.node[k].next].next) {
        int v = t.node[k].next, p = t.node[bk_json_get(&t, v, "position")].first,
            u = t.node[bk_json_get(&t, v, "displacement")].first;
        printf("  sensor ");
        put_string(&t.node[k]);
        double pv[3], uv[3];
        for (int c = 0; c < 3; c++, p = t.node[p].next, u = t.node[u].next) {
            pv[c] = bk_json_num(&t, p);
            uv[c] = bk_json_num(&t, u);
        }
        printf(": position [%.6e, %.6e, %.6e] m, displacement [%.6e, %.6e, %.6e] m\n", pv[0], pv[1], pv[2],
               uv[0], uv[1], uv[2]);
    }
    if (is_word(&t, analysis, "modal"))
        print_modes(run_dir);
    int buck = bk_json_get(&t, 0, "buckling");
    if (is_word(&t, analysis, "buckling") && bk_json_truthy(&t, buck)) {
        int about = bk_json_get(&t, buck, "about"), lf = bk_json_get(&t, buck, "load_factors");
        printf("  critical load factors (");
        if (about >= 0)
            put_string(&t.node[about]);
        printf(" state): ");
        for (int i = lf >= 0 ? t.node[lf].first : -1, first = 1; i >= 0; i = t.node[i].next, first = 0)
            printf("%s%.9g", first ? "" : ", ", bk_json_num(&t, i));
        printf("; mode shapes: modes.pvd (mode_NN.vtu)\n");
    }
    int warn = bk_json_get(&t, 0, "warnings");
    if (bk_json_truthy(&t, warn)) {
        int n = t.node[warn].count;
        printf("  %d warning%s: the result may be wrong (see above and summary.json)\n", n, n > 1 ? "s" : "");
    }
    printf("  results in %s/\n", shown);
done:
    bk_json_free(&t);
    free(text);
    return rc;
}
