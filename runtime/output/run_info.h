/* run_info.h -- what a run reports besides its tables: counters, the
 * message of a failure, warnings, and the stability events and critical points
 * of static paths (summary.json).  Warnings, events and critical points are
 * kept in growable storage owned by the bk_run_info (bk_run_info_free). */
#ifndef BK_RUN_INFO_H
#define BK_RUN_INFO_H

#include <stdio.h>

/* A change of the number of negative eigenvalues of the tangent between two
 * consecutive static equilibria: a bifurcation or limit point was passed. */
typedef struct bk_stability_event {
    int step;                /* the first equilibrium with the new count          */
    double lam_before, lam_after;
    int neg_before, neg_after;
    double lam_critical;     /* interpolated critical load factor (NaN: unknown)   */
} bk_stability_event;

/* A critical point of an arc-length path: a limit point (the load factor
 * turns; refined by bisection on the arc length) or a bifurcation (the
 * negative-eigenvalue count changes without a limit point; refined by
 * bisection on the inertia). */
#define BK_CRIT_SENSORS 4
typedef struct bk_critical_point {
    int limit;               /* 1: limit point, 0: bifurcation                    */
    int step;                /* the first equilibrium past it                     */
    double lam;              /* critical load factor                              */
    int nsensor;             /* sensors with a displacement below (the first ones) */
    double u[BK_CRIT_SENSORS][3];   /* their displacements there (m; NaN: unknown) */
} bk_critical_point;

/* Warnings beyond BK_MAX_WARNINGS distinct texts are counted, not kept (a
 * warning that changes at every step of a long run would otherwise fill the
 * summary); each text is cut at BK_WARNING_LEN - 1 characters. */
#define BK_MAX_WARNINGS 1000
#define BK_WARNING_LEN 400

typedef struct bk_run_info {
    int converged;
    double wall_s;           /* model read to results written, less the summary (s) */
    double output_s;         /* of it, writing results: files, frames, the section forces (s) */
    double stability_s;      /* of it, the static stability checks (s) */
    int steps;
    int newton_iterations;
    int cutbacks;
    int factorizations;
    int analyses;
    double load_factor;
    double strain_energy;
    double max_constraint_residual;
    char message[1024];      /* empty when converged */
    int interrupted;         /* the signal (SIGINT, SIGTERM) that stopped the run, or 0 */
    int nwarning;            /* warnings: likely wrong results (also on the console) */
    int warnings_dropped;    /* beyond BK_MAX_WARNINGS */
    char **warnings;         /* owned: [nwarning] texts (room for warning_cap) */
    int warning_cap;
    /* statics with [static] stability */
    int stability_checked;
    int negative_eigenvalues;  /* at the last equilibrium                         */
    double eig_min, eig_max;   /* smallest-magnitude and largest eigenvalue there  */
    int nstability, stability_cap;
    bk_stability_event *stability;   /* owned: [nstability] (bk_run_add_stability) */
    /* statics with static.method = "arc_length" */
    int continuation;
    int ncritical, critical_cap;
    bk_critical_point *critical;     /* owned: [ncritical], in step order (bk_run_insert_critical) */
    /* summary.json entries an analysis adds (bk_run_summary), in order */
    int nsummary, summary_cap;
    char **summary_key, **summary_json;  /* owned: [nsummary] each */
} bk_run_info;


/* Records a warning in info (summary.json "warnings") and prints it as
 * "warning: SCENE: ..." on `console` unless it is NULL.  A warning already
 * recorded with the same text is not repeated. */
void bk_warn(bk_run_info *info, FILE *console, const char *scene, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* A new stability event at the end of info->stability (zeroed), or NULL when
 * out of memory (then none is recorded). */
bk_stability_event *bk_run_add_stability(bk_run_info *info);

/* A new critical point at index at (0 <= at <= ncritical) of info->critical,
 * the later ones moved up; NULL when out of memory. */
bk_critical_point *bk_run_insert_critical(bk_run_info *info, int at);

/* An entry "key": json of summary.json that the analysis adds (json: a JSON
 * value's text, copied), written after the counters in the order added; an
 * object given under a key already added is merged into it (bk_json_merge:
 * rigid and beam contact both report under "contact").  0, or -1 when out of
 * memory or the two are not objects (then none is added). */
int bk_run_summary(bk_run_info *info, const char *key, const char *json);

/* Frees the warnings, events, critical points and summary entries (info may
 * be reused). */
void bk_run_info_free(bk_run_info *info);

#endif
