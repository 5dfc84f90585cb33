/* output.c -- sensors.csv, summary.json and the other result tables. */
#include "output.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "clock.h"
#include "csvrow.h"
#include "interrupt.h"
#include "system.h"

static int output_open(bk_output *o, const bk_model *m, const char *dir, FILE *err);

/* Adds the time since t0 to the run's output time (summary.json output_s). */
static void spent(bk_output *o, double t0)
{
    o->t_output += bk_clock_s() - t0;
}

/* The result tables are flushed at most every BK_FLUSH_INTERVAL seconds of wall
 * time while a run goes on (a write per step costs more than the step in small
 * models), and when they are closed: a run killed outright loses at most that
 * much of its tables; an interrupted one (SIGINT/SIGTERM) loses nothing. */
#define BK_FLUSH_INTERVAL 0.5

/* The run's result tables (each NULL when the run has none) and their file
 * names, in one place for the flushes and the closes. */
#define BK_NTABLES 8
static void table_list(bk_output *o, FILE **fp[BK_NTABLES], const char *name[BK_NTABLES])
{
    static const char *const names[BK_NTABLES] = {"sensors.csv", "energy.csv", "newton.csv", "stability.csv",
                                                  "modes.csv", "mode_sensors.csv", "reactions.csv", "sections.csv"};
    FILE **const all[BK_NTABLES] = {&o->sensors, &o->energy, &o->newton, &o->stability,
                                    &o->modes, &o->mode_sensors, &o->forces.reactions, &o->forces.sections};
    for (int k = 0; k < BK_NTABLES; ++k) {
        fp[k] = all[k];
        if (name)
            name[k] = names[k];
    }
}

/* spent, and the tables flushed when due (one reading of the clock for both
 * when they are not); with the rows queued for the writer thread, the thread
 * flushes them after the rows so far. */
static void spent_flush(bk_output *o, double t0)
{
    double now = bk_clock_s();
    if (now - o->t_flush >= BK_FLUSH_INTERVAL) {
        o->t_flush = now;
        if (o->rq.w) {
            bk_rowqueue_submit(&o->rq, 1);
        } else {
            FILE **fp[BK_NTABLES];
            table_list(o, fp, NULL);
            for (int k = 0; k < BK_NTABLES; ++k)
                if (*fp[k])
                    fflush(*fp[k]);
        }
        now = bk_clock_s();
    }
    o->t_output += now - t0;
}

/* Once the frames have a writer thread (vtk.h: a run with enough frames), the
 * tables' rows are formatted there too (csvrow.h bk_rowqueue): from here on
 * the tables are that thread's until bk_output_close_tables. */
static void rows_to_writer(bk_output *o)
{
    if (o->rq.w || !o->vtk.background || !o->vtk.fw.threaded)
        return;
    /* the tables written with bk_row (the mode tables are not) */
    FILE *const list[] = {o->sensors, o->energy, o->newton, o->stability, o->forces.reactions, o->forces.sections};
    if (bk_rowqueue_start(&o->rq, &o->vtk.fw, list, (int)(sizeof list / sizeof *list)) == 0)
        o->forces.rq = &o->rq;
}

int bk_output_open(bk_output *o, const bk_model *m, const char *dir, int progress, FILE *err)
{
    memset(o, 0, sizeof *o);
    o->progress = progress && isatty(2);
    o->t_start = o->t_last = o->t_flush = bk_clock_s();   /* the first flush BK_FLUSH_INTERVAL in */
    int rc = output_open(o, m, dir, err);
    spent(o, o->t_start);
    return rc;
}

static int output_open(bk_output *o, const bk_model *m, const char *dir, FILE *err)
{
    /* the frames a dynamic run writes (known from the start), and the room for
     * them (a static run: its load steps, which the step control may change) */
    const int known = m->analysis == BK_DYNAMIC
                          ? (int)fmin(1e9, m->dyn.t_end / (m->dyn.dt * m->dyn.output_every) /
                                               (m->vtk_every > 0 ? m->vtk_every : 1)) + 1
                          : 0;
    const int frames = known ? known + 3 : m->stat.load_steps * (1 + 2 * m->stat.cycles) + 4;
    if (bk_vtk_open(&o->vtk, m, dir, m->vtk_every, frames, known) != 0) {
        fprintf(err, "error: out of memory for the ParaView frames\n");
        return -1;
    }
    o->m = m;
    snprintf(o->dir, sizeof o->dir, "%s", dir);
    o->sensors = bk_table_open(dir, "sensors.csv", "step,time,sensor,x,y,z,ux,uy,uz,d1x,d1y,d1z,d2x,d2y,d2z,d3x,"
                               "d3y,d3z\n", &o->tbuf[0], err);
    if (!o->sensors)
        return -1;
    o->sensor_p0 = malloc((3 * (size_t)m->nsensor + 1) * sizeof *o->sensor_p0);
    if (!o->sensor_p0) {
        fprintf(err, "error: out of memory\n");
        return -1;
    }
    for (int k = 0; k < m->nsensor; ++k)
        bk_eval_point(m, m->q0, m->sensors[k].elem, m->sensors[k].xi, o->sensor_p0 + 3 * k, NULL);
    if (bk_forces_open(&o->forces, m, dir, err) != 0)
        return -1;
    o->vtk.sec = o->forces.sec;
    o->vtk.sec_step = &o->forces.sec_step;
    o->vtk.ssec = o->forces.ssec;
    o->vtk.maxsample = o->forces.maxsample;
    /* section forces at the steps that get a ParaView frame; without frames at
     * the stride their default would have (gen/scene/options.py: about 100
     * frames in dynamics, every equilibrium in statics) */
    if (m->vtk_every > 0)
        o->sections_every = m->vtk_every;
    else if (m->analysis == BK_DYNAMIC)
        o->sections_every = (int)fmax(1.0, ceil(m->dyn.t_end / (m->dyn.dt * m->dyn.output_every) / 100.0));
    else
        o->sections_every = 1;
    if (m->analysis == BK_DYNAMIC &&
        !(o->energy = bk_table_open(dir, "energy.csv", "step,time,kinetic,strain,gravity,load_potential,total,"
                                    "constraint_residual\n", &o->tbuf[1], err)))
        return -1;
    if (m->analysis == BK_STATIC &&
        !(o->newton = bk_table_open(dir, "newton.csv", "attempt,step,load_factor,iteration,residual,reference,"
                                    "increment,alpha,rcond\n", &o->tbuf[2], err)))
        return -1;
    if (m->analysis == BK_STATIC && m->stat.stability &&
        !(o->stability = bk_table_open(dir, "stability.csv", "step,load_factor,negative_eigenvalues,eig_min,eig_max\n",
                                       &o->tbuf[3], err)))
        return -1;
    return 0;
}

/* Sensor k at q: position, displacement from its reference position (p0 of
 * bk_output_open) and the section vectors. */
static void sensor_state(const bk_output *o, int k, const double *q, double *pos, double *disp, double *grad)
{
    const bk_sensor *s = &o->m->sensors[k];
    bk_eval_point(o->m, q, s->elem, s->xi, pos, grad);
    for (int i = 0; i < 3; ++i)
        disp[i] = pos[i] - o->sensor_p0[3 * k + i];
}

void bk_output_progress(bk_output *o, double frac, int step, double t, int iters, double residual)
{
    if (!o->progress)
        return;
    double now = bk_clock_s();
    if (now - o->t_start < 1.0 || now - o->t_last < 0.25)
        return;
    o->t_last = now;
    double el = now - o->t_start, eta = frac > 1e-9 ? el * (1.0 - frac) / frac : 0.0;
    fprintf(stderr, "\r%s: step %d, %s %.6g, %d Newton it., residual %.2e, %3.0f %%, %.0f s left   ",
            o->m->name, step, o->m->analysis == BK_DYNAMIC ? "t" : "load", t, iters, residual,
            100.0 * frac, eta);
    fflush(stderr);
}

void bk_output_last_frame(bk_output *o, int step, double t, const double *q)
{
    double t0 = bk_clock_s();
    if (o->vtk.every > 0 && (o->vtk.nframe == 0 || o->vtk.frames[o->vtk.nframe - 1] != step))
        bk_vtk_frame(&o->vtk, NULL, -step, t, q);
    rows_to_writer(o);
    spent(o, t0);
}

void bk_output_final(bk_output *o, int step, double t, const double *q)
{
    if (o->m->analysis != BK_MODAL && o->m->analysis != BK_BUCKLING)
        bk_output_last_frame(o, step, t, q);
    double t0 = bk_clock_s();
    bk_vtk_flush(&o->vtk);
    if (bk_vtk_finish(&o->vtk, stderr) != 0)       /* every frame on disk before the summary */
        o->write_failed = 1;
    spent(o, t0);
    if (o->progress && bk_clock_s() - o->t_start >= 1.0)
        fprintf(stderr, "\n");
}

void bk_output_step(bk_output *o, int step, double t, const double *q)
{
    double t0 = bk_clock_s();
    bk_vtk_frame(&o->vtk, NULL, step, t, q);
    rows_to_writer(o);
    if (!o->sensors) {
        spent(o, t0);
        return;
    }
    for (int k = 0; k < o->m->nsensor; ++k) {
        const bk_sensor *s = &o->m->sensors[k];
        double pos[3], disp[3], g[9];
        sensor_state(o, k, q, pos, disp, g);
        /* d1, d2 (section axes), d3 (axis-like); nan where undefined */
        bk_row r;
        bk_row_begin(&r, o->sensors, &o->rq);
        bk_row_int(&r, step);
        bk_row_num(&r, t);
        bk_row_str(&r, s->name);
        for (int i = 0; i < 3; ++i)
            bk_row_num(&r, pos[i]);
        for (int i = 0; i < 3; ++i)
            bk_row_num(&r, disp[i]);
        for (int i = 0; i < 9; ++i)
            bk_row_num(&r, g[i]);
        bk_row_end(&r);
    }
    spent_flush(o, t0);
}

void bk_output_forces(bk_output *o, bk_system *s, int step, double t, const double *q, const double *qd,
                      const double *qdd, const double *nu)
{
    double t0 = bk_clock_s();
    int with_sections = o->forces_calls++ % o->sections_every == 0;
    bk_forces_step(&o->forces, s, step, t, q, qd, qdd, nu, with_sections);
    spent(o, t0);
}

int bk_output_modes_begin(bk_output *o, char *err, size_t nerr)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/modes.csv", o->dir);
    o->modes = fopen(path, "w");
    if (o->modes) {
        fprintf(o->modes, o->m->analysis == BK_BUCKLING ? "mode,load_factor,scale_m\n"
                                                        : "mode,frequency_hz,omega,scale_m\n");
        snprintf(path, sizeof path, "%s/mode_sensors.csv", o->dir);
        o->mode_sensors = fopen(path, "w");
    }
    if (!o->modes || !o->mode_sensors) {
        snprintf(err, nerr, "%s: cannot write: %s", path, strerror(errno));
        return -1;
    }
    fprintf(o->mode_sensors, "mode,%s,sensor,x,y,z,dx,dy,dz,shape_x,shape_y,shape_z\n",
            o->m->analysis == BK_BUCKLING ? "load_factor" : "frequency_hz");
    o->mode_q = malloc(2 * (size_t)o->m->ndof * sizeof *o->mode_q);
    if (!o->mode_q) {
        snprintf(err, nerr, "out of memory for the mode output");
        return -1;
    }
    return 0;
}

double bk_output_mode(bk_output *o, int mode, double f_hz, double omega, const double *q, const double *phi)
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
    if (o->nfreq < (int)(sizeof o->freqs / sizeof *o->freqs))
        o->freqs[o->nfreq++] = f_hz;
    if (o->modes && m->analysis == BK_BUCKLING) {   /* f_hz: the load factor */
        fprintf(o->modes, "%d,%.17g,%.9g\n", mode, f_hz, scale);
        fflush(o->modes);
    } else if (o->modes) {
        fprintf(o->modes, "%d,%.17g,%.17g,%.9g\n", mode, f_hz, omega, scale);
        fflush(o->modes);
    }
    if (o->mode_sensors) {
        for (int k = 0; k < m->nsensor; ++k) {
            const bk_sensor *s = &m->sensors[k];
            double x[3], a[3], b[3], sh[3];
            bk_eval_point(m, q, s->elem, s->xi, x, NULL);
            bk_eval_point(m, qp, s->elem, s->xi, a, NULL);
            bk_eval_point(m, qm, s->elem, s->xi, b, NULL);
            for (int i = 0; i < 3; ++i)
                sh[i] = (a[i] - b[i]) / (2.0 * eps * norm);
            fprintf(o->mode_sensors, "%d,%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", mode, f_hz,
                    s->name, x[0] + scale * sh[0], x[1] + scale * sh[1], x[2] + scale * sh[2], scale * sh[0],
                    scale * sh[1], scale * sh[2], sh[0], sh[1], sh[2]);
        }
        fflush(o->mode_sensors);
    }
    bk_vtk_mode(&o->vtk, mode, f_hz, omega, scale, norm, q, qp, qm, eps);
    spent(o, t0);
    return scale;
}

void bk_output_iteration(bk_output *o, int attempt, int step, double lam, int iter, double residual,
                         double ref, double increment, double alpha, double rcond)
{
    if (!o->newton)
        return;
    double t0 = bk_clock_s();
    bk_row r;                      /* attempt,step,load_factor,iteration,residual,reference,increment,alpha,rcond */
    bk_row_begin(&r, o->newton, &o->rq);
    bk_row_int(&r, attempt);
    bk_row_int(&r, step);
    bk_row_num(&r, lam);
    bk_row_int(&r, iter);
    bk_row_e(&r, residual, 6);
    bk_row_e(&r, ref, 6);
    bk_row_e(&r, increment, 6);
    bk_row_g(&r, alpha, 6);
    bk_row_e(&r, rcond, 3);
    bk_row_end(&r);
    spent(o, t0);
}

void bk_output_stability(bk_output *o, int step, double lam, int negative, double eig_min, double eig_max)
{
    if (!o->stability)
        return;
    double t0 = bk_clock_s();
    bk_row r;                      /* step,load_factor,negative_eigenvalues,eig_min,eig_max */
    bk_row_begin(&r, o->stability, &o->rq);
    bk_row_int(&r, step);
    bk_row_num(&r, lam);
    bk_row_int(&r, negative);
    bk_row_e(&r, eig_min, 9);
    bk_row_e(&r, eig_max, 6);
    bk_row_end(&r);
    spent_flush(o, t0);
}

void bk_output_energy(bk_output *o, int step, double t, double T, double U, double Vg, double Vf,
                      double cres)
{
    if (!o->energy)
        return;
    double t0 = bk_clock_s();
    bk_row r;
    bk_row_begin(&r, o->energy, &o->rq);
    bk_row_int(&r, step);
    const double v[6] = {t, T, U, Vg, Vf, T + U + Vg + Vf};
    for (int i = 0; i < 6; ++i)
        bk_row_num(&r, v[i]);
    bk_row_e(&r, cres, 3);
    bk_row_end(&r);
    spent_flush(o, t0);
}

static void json_string(FILE *fp, const char *s)
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

static void json_num(FILE *fp, double v)
{
    if (isfinite(v))
        fprintf(fp, "%.17g", v);
    else
        fprintf(fp, "null");
}

static void json_vec(FILE *fp, const double *v)
{
    fputc('[', fp);
    for (int i = 0; i < 3; ++i) {
        if (isfinite(v[i]))
            fprintf(fp, "%s%.17g", i ? ", " : "", v[i]);
        else
            fprintf(fp, "%snull", i ? ", " : "");
    }
    fputc(']', fp);
}

int bk_output_summary(const bk_output *o, const bk_run_info *info, const double *q, FILE *err)
{
    char path[1200], tmp[1210];
    snprintf(path, sizeof path, "%s/summary.json", o->dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *fp = fopen(tmp, "w");
    if (!fp) {
        fprintf(err, "error: %s: cannot write: %s\n", tmp, strerror(errno));
        return -1;
    }
    const bk_model *m = o->m;
    fprintf(fp, "{\n  \"scene\": ");
    json_string(fp, m->name);
    static const char *const kind[] = {"static", "dynamic", "modal", "buckling"};
    fprintf(fp, ",\n  \"analysis\": \"%s\",\n", kind[m->analysis]);
    fprintf(fp, "  \"converged\": %s,\n", info->converged ? "true" : "false");
    fprintf(fp, "  \"interrupted\": %s,\n", info->interrupted ? "true" : "false");
    if (info->interrupted)
        fprintf(fp, "  \"signal\": \"%s\",\n", bk_interrupt_name(info->interrupted));
    fprintf(fp, "  \"warnings\": [");
    for (int k = 0; k < info->nwarning; ++k) {
        fprintf(fp, "%s\n    ", k ? "," : "");
        json_string(fp, info->warnings[k]);
    }
    fprintf(fp, "%s],\n", info->nwarning ? "\n  " : "");
    if (info->warnings_dropped)
        fprintf(fp, "  \"warnings_dropped\": %d,\n", info->warnings_dropped);
    fprintf(fp, "  \"wall_s\": %.6f,\n", info->wall_s);
    fprintf(fp, "  \"output_s\": %.6f,\n", info->output_s);
    if (o->m->analysis == BK_STATIC && o->m->stat.stability)
        fprintf(fp, "  \"stability_s\": %.6f,\n", info->stability_s);
    fprintf(fp, "  \"steps\": %d,\n", info->steps);
    fprintf(fp, "  \"newton_iterations\": %d,\n", info->newton_iterations);
    fprintf(fp, "  \"cutbacks\": %d,\n", info->cutbacks);
    fprintf(fp, "  \"factorizations\": %d,\n", info->factorizations);
    fprintf(fp, "  \"symbolic_analyses\": %d,\n", info->analyses);
    fprintf(fp, "  \"%s\": %.17g,\n", m->analysis == BK_DYNAMIC ? "time" : "load_factor", info->load_factor);
    fprintf(fp, "  \"max_constraint_residual\": %.3e,\n", info->max_constraint_residual);
    fprintf(fp, "  \"strain_energy\": %.17g,\n", info->strain_energy);
    fprintf(fp, "  \"dofs\": %d,\n  \"elements\": %d,\n", m->ndof, m->nelem);
    if (m->analysis == BK_MODAL) {
        fprintf(fp, "  \"frequencies_hz\": [");
        for (int k = 0; k < o->nfreq; ++k)
            fprintf(fp, "%s%.17g", k ? ", " : "", o->freqs[k]);
        fprintf(fp, "],\n");
    }
    if (m->analysis == BK_BUCKLING) {     /* positive factors ascending, then negative ones (buckling.c) */
        fprintf(fp, "  \"buckling\": {\"about\": \"%s\", \"load_factors\": [",
                m->modal.about_static ? "preloaded" : "reference");
        for (int k = 0; k < o->nfreq; ++k)
            fprintf(fp, "%s%.17g", k ? ", " : "", o->freqs[k]);
        fprintf(fp, "], \"critical_load_factor\": ");
        json_num(fp, o->nfreq > 0 && o->freqs[0] > 0.0 ? o->freqs[0] : NAN);
        fprintf(fp, "},\n");
    }
    if (info->stability_checked) {
        fprintf(fp, "  \"stability\": {\"negative_eigenvalues\": %d, \"eig_min\": ", info->negative_eigenvalues);
        json_num(fp, info->eig_min);
        fprintf(fp, ", \"eig_max\": ");
        json_num(fp, info->eig_max);
        fprintf(fp, ", \"events\": [");
        for (int k = 0; k < info->nstability; ++k) {
            const bk_stability_event *ev = &info->stability[k];
            fprintf(fp, "%s\n    {\"step\": %d, \"load_factor_before\": %.17g, \"load_factor_after\": %.17g, "
                        "\"negative_before\": %d, \"negative_after\": %d, \"critical_load_factor\": ",
                    k ? "," : "", ev->step, ev->lam_before, ev->lam_after, ev->neg_before, ev->neg_after);
            json_num(fp, ev->lam_critical);
            fprintf(fp, "}");
        }
        fprintf(fp, "%s]},\n", info->nstability ? "\n  " : "");
    }
    if (info->continuation) {
        fprintf(fp, "  \"critical_points\": [");
        for (int k = 0; k < info->ncritical; ++k) {
            const bk_critical_point *c = &info->critical[k];
            fprintf(fp, "%s\n    {\"type\": \"%s\", \"step\": %d, \"load_factor\": ", k ? "," : "",
                    c->limit ? "limit_point" : "bifurcation", c->step);
            json_num(fp, c->lam);
            fprintf(fp, ", \"displacement\": {");
            for (int j = 0; j < c->nsensor; ++j) {
                fprintf(fp, "%s", j ? ", " : "");
                json_string(fp, m->sensors[j].name);
                fprintf(fp, ": ");
                json_vec(fp, c->u[j]);
            }
            fprintf(fp, "}}");
        }
        fprintf(fp, "%s],\n", info->ncritical ? "\n  " : "");
    }
    bk_forces_summary(&o->forces, fp);
    fprintf(fp, "  \"error\": ");
    if (info->message[0])
        json_string(fp, info->message);
    else
        fprintf(fp, "null");
    fprintf(fp, ",\n  \"sensors\": {");
    for (int k = 0; k < m->nsensor; ++k) {
        const bk_sensor *s = &m->sensors[k];
        double pos[3], disp[3], g[9];
        sensor_state(o, k, q, pos, disp, g);
        fprintf(fp, "%s\n    ", k ? "," : "");
        json_string(fp, s->name);
        fprintf(fp, ": {\"position\": ");
        json_vec(fp, pos);
        fprintf(fp, ", \"displacement\": ");
        json_vec(fp, disp);
        fprintf(fp, ", \"d1\": ");
        json_vec(fp, g);
        fprintf(fp, ", \"d2\": ");
        json_vec(fp, g + 3);
        fprintf(fp, ", \"d3\": ");
        json_vec(fp, g + 6);
        fprintf(fp, "}");
    }
    fprintf(fp, "%s}\n}\n", m->nsensor ? "\n  " : "");
    if (fclose(fp) != 0 || rename(tmp, path) != 0) {
        fprintf(err, "error: %s: cannot write: %s\n", path, strerror(errno));
        return -1;
    }
    return 0;
}

void bk_warn(bk_run_info *info, FILE *console, const char *scene, const char *fmt, ...)
{
    char text[BK_WARNING_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    for (int k = 0; k < info->nwarning; ++k)
        if (strcmp(info->warnings[k], text) == 0)
            return;
    if (info->nwarning >= BK_MAX_WARNINGS) {
        info->warnings_dropped++;
        return;
    }
    memcpy(info->warnings[info->nwarning++], text, sizeof text);
    if (console)
        fprintf(console, "warning: %s: %s\n", scene, text);
}

/* Closes *fp (DIR/name); 0, or -1 with the error on err. */
static int close_table(const bk_output *o, FILE **fp, const char *name, FILE *err)
{
    if (!*fp)
        return 0;
    int bad = ferror(*fp) != 0;
    int e = bad ? EIO : 0;
    if (fclose(*fp) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    *fp = NULL;
    if (bad && err)
        fprintf(err, "error: %s/%s: cannot write: %s\n", o->dir, name, strerror(e));
    return bad ? -1 : 0;
}

int bk_output_close_tables(bk_output *o, FILE *err)
{
    bk_rowqueue_stop(&o->rq);            /* the rows the writer thread still has, formatted */
    o->forces.rq = NULL;
    FILE **fp[BK_NTABLES];
    const char *name[BK_NTABLES];
    table_list(o, fp, name);
    int bad = 0;
    for (int k = 0; k < BK_NTABLES; ++k)
        bad |= close_table(o, fp[k], name[k], err);
    return bad ? -1 : 0;
}

void bk_output_close(bk_output *o)
{
    bk_output_close_tables(o, NULL);     /* (before their buffers are freed) */
    free(o->mode_q);
    o->mode_q = NULL;
    free(o->sensor_p0);
    o->sensor_p0 = NULL;
    for (int k = 0; k < 4; ++k) {
        free(o->tbuf[k]);
        o->tbuf[k] = NULL;
    }
    bk_vtk_close(&o->vtk);
    bk_forces_close(&o->forces);
}
