/* output.c -- sensors.csv, summary.json and the other result tables. */
#include "output/output.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/clock.h"
#include "base/csvrow.h"
#include "base/json.h"
#include "base/interrupt.h"
#include "assembly/system.h"

static int output_open(bk_output *o, const bk_model *m, const bk_output_plan *plan, const char *dir, FILE *err);

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

/* A table the writer thread holds (not to be flushed here). */
static int queued(void *ctx, FILE *fp)
{
    return bk_rowqueue_owns(ctx, fp);
}

/* spent, and the tables flushed when due (one reading of the clock for both
 * when they are not); with the rows queued for the writer thread, the thread
 * flushes them after the rows so far. */
static void spent_flush(bk_output *o, double t0)
{
    double now = bk_clock_s();
    if (now - o->t_flush >= BK_FLUSH_INTERVAL) {
        o->t_flush = now;
        if (o->rq.w)
            bk_rowqueue_submit(&o->rq, 1);
        bk_tables_flush(&o->tables, queued, &o->rq);
        bk_h5_flush(&o->h5);              /* (a failure is reported by bk_output_close_tables) */
        now = bk_clock_s();
    }
    o->t_output += now - t0;
}

static const bk_table_spec sensors_csv =
    BK_TABLE("sensors.csv", "every run",
             "step,time,sensor,x,y,z,ux,uy,uz,d1x,d1y,d1z,d2x,d2y,d2z,d3x,d3y,d3z\n");

int bk_output_open(bk_output *o, const bk_model *m, const bk_output_plan *plan, const char *dir, int progress,
                   FILE *err)
{
    memset(o, 0, sizeof *o);
    o->progress = !progress ? 0 : isatty(2) ? 1 : 2;
    o->t_start = o->t_last = o->t_flush = bk_clock_s();   /* the first flush BK_FLUSH_INTERVAL in */
    int rc = output_open(o, m, plan, dir, err);
    spent(o, o->t_start);
    return rc;
}

static int output_open(bk_output *o, const bk_model *m, const bk_output_plan *plan, const char *dir, FILE *err)
{
    /* the frames the analysis writes when it knows them from the start, and
     * the room for them (its plan) */
    if (bk_vtk_open(&o->vtk, m, dir, m->output.vtk_every, plan->room, plan->frames) != 0) {
        fprintf(err, "error: out of memory for the ParaView frames\n");
        return -1;
    }
    o->m = m;
    snprintf(o->dir, sizeof o->dir, "%s", dir);
    o->sensors = bk_tables_open(&o->tables, dir, &sensors_csv, 1, err);
    if (!o->sensors)
        return -1;
    o->sensor_p0 = malloc((3 * (size_t)m->nsensor + 1) * sizeof *o->sensor_p0);
    if (!o->sensor_p0) {
        fprintf(err, "error: out of memory\n");
        return -1;
    }
    for (int k = 0; k < m->nsensor; ++k)
        bk_eval_sensor(m, m->q0, &m->sensors[k], o->sensor_p0 + 3 * k, NULL);
    if (bk_forces_open(&o->forces, m, plan->path, dir, &o->tables, err) != 0)
        return -1;
    o->forces.rq = &o->rq;               /* (formatted here until the queue is started) */
    if (m->output.hdf5) {
        /* one writer thread for results.h5, the frames and the tables' rows
         * (the frames' buffers in it when they would have a thread of their own) */
        const int share = o->vtk.every > 0 && o->vtk.frame_bytes <= BK_VTK_BACKGROUND_MAX;
        if (bk_h5_open(&o->h5, m, plan->path == BK_PATH_TIME, plan->states, dir, &o->tables,
                       share ? o->vtk.frame_bytes : 1, err) != 0)
            return -1;
        o->rq.sink = &o->h5.sink;        /* every table's rows mirrored into results.h5 */
        if (share)
            o->vtk.ext = &o->h5.fw;
    }
    o->vtk.forces = &o->forces;
    o->vtk.maxsample = o->forces.maxsample;
    /* section forces at the steps that get a ParaView frame; without frames at
     * the stride their default would have (the analysis' plan: e.g. 50 frames
     * in dynamics, gen/options_schema.py DYNAMIC_FRAMES; every equilibrium in
     * statics) --
     * it was 100 here, so a run without frames computed twice the section
     * forces of one with them (its output took longer) */
    if (m->output.vtk_every > 0)
        o->sections_every = m->output.vtk_every;
    else
        o->sections_every = plan->sections_every > 1 ? plan->sections_every : 1;
    o->plan = *plan;
    o->vtk.end = plan->end;
    o->vtk.modes = plan->modes;
    return 0;
}

/* Sensor k at q: position, displacement from its reference position (p0 of
 * bk_output_open) and the section vectors. */
static void sensor_state(const bk_output *o, int k, const double *q, double *pos, double *disp, double *grad)
{
    const bk_sensor *s = &o->m->sensors[k];
    bk_eval_sensor(o->m, q, s, pos, grad);
    for (int i = 0; i < 3; ++i)
        disp[i] = pos[i] - o->sensor_p0[3 * k + i];
}

void bk_output_progress(bk_output *o, double frac, int step, double t, double dt, int iters, double residual)
{
    if (!o->progress)
        return;
    o->progress_iters += iters;
    double now = bk_clock_s(), every = o->progress == 1 ? BK_PROGRESS_TTY_S : BK_PROGRESS_LOG_S;
    if (now - o->t_start < every || now - o->t_last < every)
        return;
    o->t_last = now;
    o->progress_shown = 1;
    double el = now - o->t_start, eta = frac > 1e-9 ? el * (1.0 - frac) / frac : 0.0;
    fprintf(stderr, "%s%s: %s %.6g (%.0f %%), step %d, %s %.3g, %.0f iterations/s, residual %.1e, %.0f s left%s",
            o->progress == 1 ? "\r" : "", o->m->name, o->plan.path == BK_PATH_TIME ? "t" : "load factor", t,
            100.0 * frac, step, o->plan.path == BK_PATH_TIME ? "dt" : "increment", dt, o->progress_iters / el, residual,
            eta, o->progress == 1 ? "   " : "\n");
    fflush(stderr);
}

void bk_output_last_frame(bk_output *o, int step, double t, const double *q)
{
    double t0 = bk_clock_s();
    if (o->vtk.every > 0 && (o->vtk.nframe == 0 || o->vtk.frames[o->vtk.nframe - 1] != step))
        bk_vtk_frame(&o->vtk, o->sys, -step, t, q);
    bk_output_rows_to_writer(o, t);
    spent(o, t0);
}

void bk_output_final(bk_output *o, int step, double t, const double *q)
{
    if (o->plan.path != BK_PATH_NONE)
        bk_output_last_frame(o, step, t, q);
    double t0 = bk_clock_s();
    bk_vtk_flush(&o->vtk);
    if (bk_vtk_finish(&o->vtk, stderr) != 0)       /* every frame on disk before the summary */
        o->write_failed = 1;
    spent(o, t0);
    if (o->progress == 1 && o->progress_shown)
        fprintf(stderr, "\n");
}

void bk_output_step(bk_output *o, int step, double t, const double *q)
{
    double t0 = bk_clock_s();
    bk_vtk_frame(&o->vtk, o->sys, step, t, q);
    bk_output_rows_to_writer(o, t);
    bk_h5_state(&o->h5, step, t, q);
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
    o->sys = s;
    bk_h5_velocity(&o->h5, step, qd);
    if (o->forces_calls == 0)            /* the interactions' tables, at the first output step */
        for (int k = 0; k < s->ninter; ++k) {
            const bk_interaction *it = &s->inter[k];
            if (it->ops->tables && it->ops->tables(it->self, s, &o->tables, o->dir, stderr) != 0)
                o->write_failed = 1;
        }
    if (o->h5.open && o->h5.fw.threaded)  /* the rows to results.h5's thread from the first step's (sections.csv) */
        bk_output_rows_to_writer(o, t);
    else                                  /* (roll-up: a step's section forces took 40-130 us here) */
        bk_output_rows_due(o, t);
    int with_sections = o->forces_calls++ % o->sections_every == 0;
    bk_forces_step(&o->forces, s, step, t, q, qd, qdd, nu, with_sections);
    for (int k = 0; k < s->ninter; ++k) {
        const bk_interaction *it = &s->inter[k];
        if (it->ops->rows)
            it->ops->rows(it->self, s, step, t, q, &o->rq);
    }
    spent(o, t0);
}

FILE *bk_output_table(bk_output *o, const bk_table_spec *spec, FILE *err)
{
    double t0 = bk_clock_s();
    FILE *fp = bk_tables_open(&o->tables, o->dir, spec, 1, err);
    spent(o, t0);
    return fp;
}

void bk_output_row(bk_output *o, bk_row *r, FILE *table)
{
    bk_row_begin(r, table, &o->rq);
}

void bk_output_row_end(bk_output *o, bk_row *r, double t0, int flush)
{
    bk_row_end(r);
    if (flush)
        spent_flush(o, t0);
    else
        spent(o, t0);
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
    bk_json_string(fp, m->name);
    fprintf(fp, ",\n  \"analysis\": \"%s\",\n", bk_analysis_name(m->analysis));
    fprintf(fp, "  \"converged\": %s,\n", info->converged ? "true" : "false");
    fprintf(fp, "  \"interrupted\": %s,\n", info->interrupted ? "true" : "false");
    if (info->interrupted)
        fprintf(fp, "  \"signal\": \"%s\",\n", bk_interrupt_name(info->interrupted));
    /* the scene reader's warnings first, then the solver's not among them */
    fprintf(fp, "  \"warnings\": [");
    int listed = 0;
    for (int k = 0; k < m->nscene_warning; ++k) {
        fprintf(fp, "%s\n    ", listed++ ? "," : "");
        bk_json_string(fp, m->scene_warnings[k]);
    }
    for (int k = 0; k < info->nwarning; ++k) {
        int seen = 0;
        for (int j = 0; j < m->nscene_warning && !seen; ++j)
            seen = strcmp(m->scene_warnings[j], info->warnings[k]) == 0;
        if (seen)
            continue;
        fprintf(fp, "%s\n    ", listed++ ? "," : "");
        bk_json_string(fp, info->warnings[k]);
    }
    fprintf(fp, "%s],\n", listed ? "\n  " : "");
    if (info->warnings_dropped)
        fprintf(fp, "  \"warnings_dropped\": %d,\n", info->warnings_dropped);
    fprintf(fp, "  \"wall_s\": %.6f,\n", info->wall_s);
    fprintf(fp, "  \"output_s\": %.6f,\n", info->output_s);
    if (o->plan.stability)
        fprintf(fp, "  \"stability_s\": %.6f,\n", info->stability_s);
    fprintf(fp, "  \"steps\": %d,\n", info->steps);
    fprintf(fp, "  \"newton_iterations\": %d,\n", info->newton_iterations);
    fprintf(fp, "  \"cutbacks\": %d,\n", info->cutbacks);
    fprintf(fp, "  \"factorizations\": %d,\n", info->factorizations);
    fprintf(fp, "  \"symbolic_analyses\": %d,\n", info->analyses);
    /* every number through json_num: a non-finite value is null (JSON has no NaN) */
    fprintf(fp, "  \"%s\": ", o->plan.path == BK_PATH_TIME ? "time" : "load_factor");
    bk_json_num(fp, info->load_factor);
    fprintf(fp, ",\n  \"max_constraint_residual\": ");
    bk_json_num(fp, info->max_constraint_residual);
    fprintf(fp, ",\n  \"strain_energy\": ");
    bk_json_num(fp, info->strain_energy);
    fprintf(fp, ",\n");
    fprintf(fp, "  \"dofs\": %d,\n  \"elements\": %d,\n", m->ndof, m->nelem);
    for (int k = 0; k < info->nsummary; ++k) {          /* the analysis's own entries */
        fprintf(fp, "  ");
        bk_json_string(fp, info->summary_key[k]);
        fprintf(fp, ": %s,\n", info->summary_json[k]);
    }
    if (info->stability_checked) {
        fprintf(fp, "  \"stability\": {\"negative_eigenvalues\": %d, \"eig_min\": ", info->negative_eigenvalues);
        bk_json_num(fp, info->eig_min);
        fprintf(fp, ", \"eig_max\": ");
        bk_json_num(fp, info->eig_max);
        fprintf(fp, ", \"events\": [");
        for (int k = 0; k < info->nstability; ++k) {
            const bk_stability_event *ev = &info->stability[k];
            fprintf(fp, "%s\n    {\"step\": %d, \"load_factor_before\": ", k ? "," : "", ev->step);
            bk_json_num(fp, ev->lam_before);
            fprintf(fp, ", \"load_factor_after\": ");
            bk_json_num(fp, ev->lam_after);
            fprintf(fp, ", \"negative_before\": %d, \"negative_after\": %d, \"critical_load_factor\": ",
                    ev->neg_before, ev->neg_after);
            bk_json_num(fp, ev->lam_critical);
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
            bk_json_num(fp, c->lam);
            fprintf(fp, ", \"displacement\": {");
            for (int j = 0; j < c->nsensor; ++j) {
                fprintf(fp, "%s", j ? ", " : "");
                bk_json_string(fp, m->sensors[j].name);
                fprintf(fp, ": ");
                bk_json_vec3(fp, c->u[j]);
            }
            fprintf(fp, "}}");
        }
        fprintf(fp, "%s],\n", info->ncritical ? "\n  " : "");
    }
    bk_forces_summary(&o->forces, fp);
    fprintf(fp, "  \"error\": ");
    if (info->message[0])
        bk_json_string(fp, info->message);
    else
        fprintf(fp, "null");
    fprintf(fp, ",\n  \"sensors\": {");
    for (int k = 0; k < m->nsensor; ++k) {
        const bk_sensor *s = &m->sensors[k];
        double pos[3], disp[3], g[9];
        sensor_state(o, k, q, pos, disp, g);
        fprintf(fp, "%s\n    ", k ? "," : "");
        bk_json_string(fp, s->name);
        fprintf(fp, ": {\"position\": ");
        bk_json_vec3(fp, pos);
        fprintf(fp, ", \"displacement\": ");
        bk_json_vec3(fp, disp);
        fprintf(fp, ", \"d1\": ");
        bk_json_vec3(fp, g);
        fprintf(fp, ", \"d2\": ");
        bk_json_vec3(fp, g + 3);
        fprintf(fp, ", \"d3\": ");
        bk_json_vec3(fp, g + 6);
        fprintf(fp, "}");
    }
    fprintf(fp, "%s}\n}\n", m->nsensor ? "\n  " : "");
    if (fclose(fp) != 0 || rename(tmp, path) != 0) {
        fprintf(err, "error: %s: cannot write: %s\n", path, strerror(errno));
        return -1;
    }
    return 0;
}

int bk_output_close_tables(bk_output *o, FILE *err)
{
    bk_rowqueue_stop(&o->rq);            /* the rows the writer thread still has, formatted */
    if (o->own_fw) {
        bk_filewriter_close(&o->fw);
        o->own_fw = 0;
    }
    int h5 = bk_h5_close(&o->h5, err);   /* (its rows were mirrored as they were given) */
    return bk_tables_close(&o->tables, o->dir, err) != 0 || h5 != 0 ? -1 : 0;
}

void bk_output_close(bk_output *o)
{
    bk_output_close_tables(o, NULL);     /* (before their buffers are freed) */
    bk_rowqueue_free(&o->rq);
    bk_h5_end(&o->h5);                   /* (HDF5, if started, ended meanwhile) */
    free(o->mode_q);
    o->mode_q = NULL;
    free(o->sensor_p0);
    o->sensor_p0 = NULL;
    bk_tables_free(&o->tables);
    o->sensors = o->modes = o->mode_sensors = NULL;
    bk_vtk_close(&o->vtk);
    bk_forces_close(&o->forces);
}
