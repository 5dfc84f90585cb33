/* output.h -- result files of a run: sensors.csv (one row per output step and
 * sensor, flushed as it is written so an interrupted run keeps its results),
 * results.h5 (h5.h: every output step's q, and every table's rows),
 * summary.json (written at the end, also when the solve failed) and, for modal
 * analyses, modes.csv, mode_sensors.csv and the mode files of vtk.h. */
#ifndef BK_OUTPUT_H
#define BK_OUTPUT_H

#include <stdio.h>

#include "output/forces.h"
#include "output/h5.h"
#include "output/run_info.h"
#include "base/tables.h"
#include "model/model.h"
#include "output/vtk.h"

/* What the running analysis tells the output of the states it will write
 * (its module's plan, analysis/analysis.h), so that no output code tests the
 * kind of analysis or reads its options. */
typedef struct bk_output_plan {
    int path;                /* the kind of its states' path (bk_options.h enum bk_path_kind): BK_PATH_NONE
                              * (modal, buckling: no path, no sections.csv, joints.csv or last frame),
                              * BK_PATH_LOAD (the load factor), BK_PATH_TIME (time: velocities, inertia) */
    double end;              /* the path variable at the run's end: a frame's progress is t / end (0: unknown,
                              * e.g. continuation, load cycles) */
    int frames;              /* ParaView frames of states it writes, when known from the start (else 0) */
    int states;              /* output states it gives, when known from the start (else 0) */
    int room;                /* frames to make room for at the start (more are made room for as they come) */
    int sections_every;      /* output states between two of sections.csv when output.vtk_every does not set
                              * it (0: every state) */
    int modes;               /* mode frames it writes (progress: mode / modes; 0: none) */
    int stability;           /* 1: it checks the stability of its states (summary.json: stability_s) */
} bk_output_plan;

#define BK_MODE_VALUES 4
#define BK_MODE_NAME 32

typedef struct bk_output {
    const bk_model *m;
    char dir[1024];
    bk_tables tables;        /* every result table of the run (tables.h): owned */
    FILE *sensors;           /* sensors.csv (registered in tables) */
    FILE *modes;             /* modal analyses only (registered in tables) */
    FILE *mode_sensors;      /* modal analyses only (registered in tables) */
    double *mode_q;          /* owned; modal: [2 ndof] q + eps phi, q - eps phi */
    int mode_nval;           /* values per mode and their names (bk_output_modes_begin: from modes.csv's header) */
    char mode_name[BK_MODE_VALUES][BK_MODE_NAME];
    const char *mode_names[BK_MODE_VALUES];
    double *sensor_p0;       /* owned: [3 nsensor] the sensors' reference positions */
    bk_vtk vtk;              /* ParaView frames */
    int progress;            /* 1: an updating progress line on stderr (a terminal), 2: a line
                              * every BK_PROGRESS_LOG_S (a log), 0: none */
    long progress_iters;     /* Newton iterations reported to bk_output_progress */
    int progress_shown;      /* a progress line was written */
    FILE *console;           /* warnings are printed here (NULL: --quiet) */
    double t_start, t_last;  /* wall clock of the start and of the last progress line */
    double t_flush;          /* wall clock of the last flush of the result tables */
    double t_output;         /* wall time spent in the bk_output_* calls so far (s) */
    bk_forces forces;        /* reactions.csv, sections.csv (forces.h) */
    bk_output_plan plan;     /* the analysis' (bk_output_open) */
    int sections_every, forces_calls;   /* sections.csv every n-th output step (with the frames) */
    int write_failed;        /* a ParaView frame could not be written (reported by bk_output_final) */
    const bk_system *sys;    /* the system of the last bk_output_forces: its interactions add to the frames */
    bk_rowqueue rq;          /* the tables' rows, formatted by the frames' writer thread once it runs (csvrow.h) */
    bk_h5 h5;                /* results.h5 (h5.h; output.hdf5): the states and a mirror of the tables */
    bk_filewriter fw;        /* the rows' writer thread when neither the frames' nor results.h5's runs */
    int own_fw, own_tried;   /*   1: fw is open; its opening was tried */
    int row_steps;           /*   output steps before it */
} bk_output;


/* progress: report long runs on stderr: on a terminal one updating line at
 * most every BK_PROGRESS_TTY_S, else (a log) one line every BK_PROGRESS_LOG_S;
 * nothing before the first interval has passed. */
#define BK_PROGRESS_TTY_S 2.0
#define BK_PROGRESS_LOG_S 10.0
int bk_output_open(bk_output *o, const bk_model *m, const bk_output_plan *plan, const char *dir, int progress,
                   FILE *err);
/* Progress at fraction frac (0..1) of the run; prints at most 4 times a second,
 * only after the first second, only on a terminal. */
/* After an accepted step: the fraction done, the step, the time or load
 * factor t, the step's length dt, its Newton iterations and residual. */
void bk_output_progress(bk_output *o, double frac, int step, double t, double dt, int iters, double residual);
/* Writes the ParaView frame of the last state if the stride skipped it (not
 * for modal analyses: bk_solve_modal writes the frames of the state the modes
 * are about itself, with bk_output_last_frame), waits until every frame is on
 * disk (they are written by a background thread, vtk.h), and ends the
 * progress line. */
void bk_output_final(bk_output *o, int step, double t, const double *q);
void bk_output_last_frame(bk_output *o, int step, double t, const double *q);
/* One row per sensor for the configuration q at output step `step`, time t. */
void bk_output_step(bk_output *o, int step, double t, const double *q);
/* Reactions and section forces of the output step (forces.h bk_forces_step). */
void bk_output_forces(bk_output *o, bk_system *s, int step, double t, const double *q, const double *qd,
                      const double *qdd, const double *nu);
/* A result table of an analysis or an interaction: DIR/NAME opened with its
 * header line and registered (tables.h: closed with the others, its rows
 * queued to the writer thread once it runs).  The stream, or NULL with a
 * message on err. */
FILE *bk_output_table(bk_output *o, const bk_table_spec *spec, FILE *err);
/* A row of such a table (csvrow.h: then bk_row_num, ...), and its end: the
 * row written (or queued), the tables flushed when due (flush), the time
 * since t0 (bk_clock_s) counted as output time. */
void bk_output_row(bk_output *o, bk_row *r, FILE *table);
void bk_output_row_end(bk_output *o, bk_row *r, double t0, int flush);
/* Opens modes.csv and mode_sensors.csv with the analysis' specs of them (its
 * registrations, base/tables.h) and allocates the mode buffers; -1 on failure
 * (a message in err).  The values each mode carries are named by the modes
 * table's header "mode,NAMES...,scale_m" (1 to BK_MODE_VALUES names of fewer
 * than BK_MODE_NAME characters; a modal analysis "frequency_hz,omega"); the
 * sensors table's header must be "mode,NAMES[0],sensor,x,y,z,dx,dy,dz,
 * shape_x,shape_y,shape_z". */
int bk_output_modes_begin(bk_output *o, const bk_table_spec *modes, const bk_table_spec *sensors, char *err,
                          size_t nerr);
/* Mode `mode` (1, 2, ...) with its values vals[nval] and vector phi[ndof]
 * (any scale) about the state q: normalizes it to a largest point translation
 * of 1 (mode_shape), scales it for display to a largest translation of
 * BK_MODE_SIZE times the model length, or less if the sections would turn by
 * more than BK_MODE_ROTATION rad, and writes the row of modes.csv (mode, the
 * values, that scale in m), the rows of mode_sensors.csv and mode_NN.vtu (its
 * field data: MODE, the values under their names in capitals, MODE_SCALE).
 * Returns the scale (m). */
double bk_output_mode(bk_output *o, int mode, const double *vals, const double *q, const double *phi);
#define BK_MODE_SIZE 0.1
#define BK_MODE_ROTATION 0.5
int bk_output_summary(const bk_output *o, const bk_run_info *info, const double *q, FILE *err);
/* Writes out and closes the result tables (their last rows are still in
 * their buffers: a short run writes them only now), before summary.json;
 * 0, or -1 with "error: PATH: cannot write: REASON" on err for each table
 * that could not be written. */
int bk_output_close_tables(bk_output *o, FILE *err);
/* (output.c's, in rows_writer.c) The tables' rows to a writer thread once one
 * runs, called at every output step (t: its time or load factor). */
void bk_output_rows_to_writer(bk_output *o, double t);
/* (rows_writer.c) The same decision at an output step's section forces, before
 * they are computed, as bk_output_rows_to_writer will count the step (not
 * counted here): when the step makes the run due a thread, it starts now and
 * makes the step's section forces too (a small model's, forces.h). */
void bk_output_rows_due(bk_output *o, double t);
/* Closes what is still open (the tables too, unreported), waits for results.h5's
 * thread to end and frees. */
void bk_output_close(bk_output *o);

#endif
