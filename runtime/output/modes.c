/* modes.c -- the modes of a modal or buckling analysis on disk: modes.csv,
 * mode_sensors.csv and one ParaView frame per mode (see output.h
 * bk_output_modes_begin, bk_output_mode). */
#include "output/output.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"

/* DIR/NAME opened with its header and registered (written with fprintf, not
 * queued); NULL with a message in err. */
static FILE *mode_table(bk_output *o, const bk_table_spec *spec, char *err, size_t nerr)
{
    const char *name = spec->name;
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", o->dir, name);
    FILE *fp = fopen(path, "w");
    if (!fp) {
        snprintf(err, nerr, "%s: cannot write: %s", path, strerror(errno));
        return NULL;
    }
    if (bk_tables_add(&o->tables, name, fp, 0) != 0) {
        snprintf(err, nerr, "out of memory for the mode output");
        return NULL;
    }
    fputs(spec->header, fp);
    return fp;
}

/* The names of the values of a mode from the modes table's header
 * "mode,NAMES...,scale_m\n" into o (checked against the sensors table's);
 * 0, or -1 with a message in err. */
static int mode_names(bk_output *o, const bk_table_spec *modes, const bk_table_spec *sensors, char *err,
                      size_t nerr)
{
    const char *h = modes->header, *end = strstr(h, ",scale_m\n");
    int n = 0;
    if (strncmp(h, "mode,", 5) != 0 || !end || end[9] != '\0' || end <= h + 5) {
        snprintf(err, nerr, "%s: header is not \"mode,NAMES,scale_m\"", modes->name);
        return -1;
    }
    for (const char *p = h + 5; p < end; ++n) {
        const char *c = memchr(p, ',', (size_t)(end - p));
        size_t len = (size_t)((c ? c : end) - p);
        if (n == BK_MODE_VALUES || len == 0 || len >= BK_MODE_NAME) {
            snprintf(err, nerr, "%s: expected 1 to %d names of 1 to %d characters", modes->name, BK_MODE_VALUES,
                     BK_MODE_NAME - 1);
            return -1;
        }
        memcpy(o->mode_name[n], p, len);
        o->mode_name[n][len] = '\0';
        o->mode_names[n] = o->mode_name[n];
        p += len + (c != NULL);
    }
    o->mode_nval = n;
    char want[300];
    snprintf(want, sizeof want, "mode,%s,sensor,x,y,z,dx,dy,dz,shape_x,shape_y,shape_z\n", o->mode_name[0]);
    if (strcmp(sensors->header, want) != 0) {
        snprintf(err, nerr, "%s: header is not \"%.*s\"", sensors->name, (int)strlen(want) - 1, want);
        return -1;
    }
    return 0;
}

int bk_output_modes_begin(bk_output *o, const bk_table_spec *modes, const bk_table_spec *sensors, char *err,
                          size_t nerr)
{
    if (mode_names(o, modes, sensors, err, nerr) != 0 || !(o->modes = mode_table(o, modes, err, nerr)) ||
        !(o->mode_sensors = mode_table(o, sensors, err, nerr)))
        return -1;
    o->mode_q = malloc(2 * (size_t)o->m->ndof * sizeof *o->mode_q);
    if (!o->mode_q) {
        snprintf(err, nerr, "out of memory for the mode output");
        return -1;
    }
    return 0;
}

double bk_output_mode(bk_output *o, int mode, const double *vals, const double *q, const double *phi)
{
    double t0 = bk_clock_s();
    const bk_model *m = o->m;
    int n = m->ndof;
    double *qp = o->mode_q, *qm = o->mode_q + n, pmax = 0.0;
    for (int i = 0; i < n; ++i)
        pmax = fmax(pmax, fabs(phi[i]));
    /* a perturbation of 1e-6 of the model length (in the largest DOF) for the
     * central differences of the point positions along the mode */
    double eps = pmax > 0.0 ? 1e-6 * m->length_scale / pmax : 0.0, T = 0.0, R = 0.0;
    for (int i = 0; i < n; ++i) {
        qp[i] = q[i] + eps * phi[i];
        qm[i] = q[i] - eps * phi[i];
    }
    if (eps > 0.0)
        bk_vtk_mode_extent(m, qp, qm, eps, &T, &R);
    double norm = T > 0.0 ? T : 1.0, scale = 0.0;
    if (T > 0.0) {
        scale = BK_MODE_SIZE * m->length_scale;
        if (R / T * scale > BK_MODE_ROTATION)
            scale = BK_MODE_ROTATION * T / R;
    }
    if (eps == 0.0)
        eps = 1.0;                              /* zero vector: qp = qm = q, shape 0 */
    if (o->modes) {
        fprintf(o->modes, "%d", mode);
        for (int k = 0; k < o->mode_nval; ++k)
            fprintf(o->modes, ",%.17g", vals[k]);
        fprintf(o->modes, ",%.9g\n", scale);
        fflush(o->modes);
    }
    if (o->mode_sensors) {
        for (int k = 0; k < m->nsensor; ++k) {
            const bk_sensor *s = &m->sensors[k];
            double x[3], a[3], b[3], sh[3];
            bk_eval_sensor(m, q, s, x, NULL);
            bk_eval_sensor(m, qp, s, a, NULL);
            bk_eval_sensor(m, qm, s, b, NULL);
            for (int i = 0; i < 3; ++i)
                sh[i] = (a[i] - b[i]) / (2.0 * eps * norm);
            fprintf(o->mode_sensors, "%d,%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", mode, vals[0],
                    s->name, x[0] + scale * sh[0], x[1] + scale * sh[1], x[2] + scale * sh[2], scale * sh[0],
                    scale * sh[1], scale * sh[2], sh[0], sh[1], sh[2]);
        }
        fflush(o->mode_sensors);
    }
    bk_vtk_mode(&o->vtk, mode, o->mode_nval, o->mode_names, vals, scale, norm, q, qp, qm, eps);
    o->t_output += bk_clock_s() - t0;
    return scale;
}
