/* model.h -- the discretized scene the solver works on.
 *
 * A model is read from the model file that gen/scene/model_file.py writes (the scene's
 * TOML, validated and meshed).  The runtime never sees TOML.  All arrays are
 * owned by the model and released by bk_model_free().
 */
#ifndef BK_MODEL_H
#define BK_MODEL_H

#include <stdio.h>

#include "bk_joint.h"
#include "bk_kernel.h"
#include "bk_options.h"        /* generated (out/kernels/): the option structs and enums */

/* An interaction module's record (model/records.c): its name, and its text,
 * which the model keeps unread; the module reads it (model/reader.h
 * rd_open_record) when the system makes the interaction. */
typedef struct bk_model_record {
    char name[32];
    char *text;                /* owned: the tokens between "record NAME" and "end_record" */
    char *where;               /* owned: "MODEL FILE, record NAME", for messages */
} bk_model_record;

typedef struct bk_elem {
    int pair;          /* index into model->pairs                          */
    int geom;          /* index into model->geoms (and model->tabs)        */
    int mat;           /* index into model->mats                           */
    int *dofs;         /* [ndof of the element] global DOF of each local DOF */
} bk_elem;

#define BK_MAT_MAXPARAM 8

typedef struct bk_mat {
    int nparam;
    double params[BK_MAT_MAXPARAM];
    char param_names[BK_MAT_MAXPARAM][24];  /* as the model file names them; checked against the kernel */
    double rho;        /* kg/m^3 */
    int nvisc;         /* Kelvin-Voigt parameters (0: no material damping) */
    double visc[BK_MAT_MAXPARAM];
} bk_mat;

/* Amplitude: the history a load or a prescribed angle is multiplied by, as a
 * function of the time (dynamics) or the load factor (statics); see
 * runtime/model/amplitude.h.  par: ramp t0, t1; step t0; sine amplitude, frequency,
 * phase, offset; table x0, a0, x1, a1, ...; cycloidal and quintic (rest to rest
 * from 0 to 1) t0, t1; spline x0, a0, m0, x1, a1, m1, ... (m: the second
 * derivatives of the cubic spline at its knots) */
enum bk_amplitude_type { BK_AMP_RAMP = 1, BK_AMP_STEP, BK_AMP_SINE, BK_AMP_TABLE, BK_AMP_CYCLOID, BK_AMP_QUINTIC,
                         BK_AMP_SPLINE };
typedef struct bk_amplitude {
    int type;
    int npar;
    double *par;
} bk_amplitude;

typedef struct bk_force_load {   /* force at a material point of an element */
    int elem;
    double xi, y, z;   /* element coordinates of the point */
    int section;       /* 1: spread uniformly over the cross-section at xi */
    double value[3];   /* N (follower: components along the section frame e1, e2, e3) */
    int amp;           /* amplitude index, -1: the default (load factor in statics, 1 in dynamics) */
    int follower;      /* 1: turns with the section frame at the point */
} bk_force_load;

typedef struct bk_point_mass {  /* a mass without rotary inertia at a material point of an element */
    int elem;
    double xi;         /* on the centreline */
    double mass;       /* kg */
} bk_point_mass;

typedef struct bk_moment_load {  /* moment on the cross-section at xi */
    int elem;
    double xi;
    double value[3];   /* N m (follower: along e1, e2, e3 of the section) */
    int amp, follower; /* as for forces; not follower: fixed in space */
} bk_moment_load;

typedef struct bk_dist_load {    /* force per unit reference length on xi0..xi1 of an element */
    int elem;
    double xi0, xi1;
    int follower, amp;
    double value[3];   /* N/m (follower: along e1, e2, e3 of the section) */
} bk_dist_load;

typedef struct bk_tendon_piece {
    int elem;
    double xi0, xi1;   /* part of the element the tendon runs through */
    double dy, dz;     /* offset from the centreline along the section axes (m) */
} bk_tendon_piece;

typedef struct bk_tendon {       /* a tendon pulled with tension amp(x) T: potential T l(q) */
    int amp;
    double tension;
    int npiece;
    bk_tendon_piece *pieces;
} bk_tendon;

/* The rows one [[constraint]] added (fixed DOFs and linear constraints): its
 * reaction is reported as one force and moment (about the point `elem`, `xi`). */
typedef struct bk_reaction {
    int index;         /* of the [[constraint]] table */
    char type[32], name[64], at[64];   /* name: constraint.name (default constraintN) */
    int elem;
    double xi;
    int nfixed, nlin, nside;
    int *fixed, *lin;
    int *side;         /* DOFs of body a when the joint is between bodies (nside 0: all; of a
                        * joint nonlinear in q: its x[0 .. 6]) */
    int nlcon;         /* its first joint nonlinear in q (model->nlcons), -1: none */
    int njoint;        /* its joints nonlinear in q, nlcons[nlcon .. nlcon + njoint - 1] (a weld
                        * of an ANCF node is several: gen/scene/weld.py) */
} bk_reaction;

typedef struct bk_section_rec {  /* an element of a beam, for sections.csv */
    char beam[64];
    int elem;
    double s0, s1;     /* arc length of its start and end (m) */
    double r;          /* its section's half-height (m; a circle's radius): output/overlap.c */
    int group;         /* the same for beams joined by constraints (a mechanism's links) */
} bk_section_rec;

typedef struct bk_sensor {
    char name[64];
    int elem;
    double xi;         /* along the element axis, on the centreline */
    double off[3];     /* a point of a body: its place along the body axes d1, d2, d3 (else 0) */
} bk_sensor;

/* A constraint linear in q, possibly rheonomic:
 *   sum_k (c0[k] + cc[k] cos phi(t) + cs[k] sin phi(t)) q[dof[k]]
 *       = r0 + rc cos phi(t) + rs sin phi(t),
 *   phi(t) = kappa (rate t + amp sin(2 pi freq t) + angle a(t)).
 * Clamps, spherical joints, revolute joints and prescribed rotations of ANCF
 * slopes and of quaternions are all of this form. */
typedef struct bk_lincon {
    int nterm;
    int *dof;
    double *c0, *cc, *cs;
    double r0, rc, rs;
    double kappa, rate, amp, freq;
    double angle;                 /* phi += kappa angle a(t) with a = *ampl (NULL: none) */
    int ampid;                    /* index of *ampl in the model's amplitudes, -1: none */
    const bk_amplitude *ampl;
    double ru;                    /* a prescribed motion: the right-hand side gains ru u(t), u = *uampl, */
    int uampid;                   /*   or the path parameter itself when uampid = -1 (statics: the load factor) */
    const bk_amplitude *uampl;
} bk_lincon;

/* A joint between two frames (beam nodes with a rotation, rigid bodies, the
 * ground), nonlinear in q: g(x) = 0 with x = (r_a, p_a, r_b, p_b) gathered
 * from q (dof >= 0) or constant (dof = -1: the ground, x0), the generated
 * kernel `kind` (runtime/bk_joint.h) bound by bk_model_bind_joints. */
typedef struct bk_nlcon {
    char type[24];
    const bk_joint_kind *kind;
    int dof[BK_JOINT_NX];
    double x0[BK_JOINT_NX];
    double prm[BK_JOINT_NPARAM];  /* the geometry prm[0 .. BK_JOINT_NGEOM - 1]; the drive's at a time: bk_joint_params */
    /* a driven joint (kind->driven): th(t) = rate t + amp sin(2 pi freq t) + scale a(t), a = *dampl (NULL: none) */
    double rate, amp, freq, scale;
    int dampid;                   /* index of *dampl in the model's amplitudes, -1: none */
    const bk_amplitude *dampl;
} bk_nlcon;

typedef struct bk_model {
    char name[128];
    int analysis;                /* enum bk_analysis (scene.analysis) */
    double length_scale;         /* m, for increment tolerances (scene record) */
    int ndof;
    double *q0;                  /* [ndof] reference configuration       */
    int npair;
    const bk_pair **pairs;       /* resolved kernel descriptors          */
    int ngeom;                   /* distinct (kernel, congruent element) tables */
    double (*geoms)[BK_NGEOM];   /* geometry of each table (bk_kernel.h)  */
    int *geom_pair;              /* kernel whose tabulate() builds it     */
    int *geom_elem;              /* element whose reference coordinates it uses */
    double **tabs;               /* [ngeom] tabulated constants            */
    int nmat;
    bk_mat *mats;
    int nelem;
    bk_elem *elems;
    int nfixed;
    int *fixed;                  /* DOFs held at their reference value   */
    int nlincon;
    bk_lincon *lincons;
    int nnlcon;
    bk_nlcon *nlcons;            /* joints nonlinear in q (rows after the linear ones) */
    int nforce;
    bk_force_load *forces;
    int nmoment;
    bk_moment_load *moments;
    int has_gravity;
    double gravity[3];
    int gravity_ampid;           /* amplitude index of gravity in the model file, -1: none */
    const bk_amplitude *gravity_amp;   /* its amplitude, NULL: the default (bk_external_load) */
    int npmass;
    bk_point_mass *pmass;        /* point masses (bk_element_mass, bk_element_weight) */
    int nsensor;
    bk_sensor *sensors;
    int namp;
    bk_amplitude *amps;
    int ndload;
    bk_dist_load *dloads;
    int ntendon;
    bk_tendon *tendons;
    int nreaction;
    bk_reaction *reactions;
    int nsection;
    bk_section_rec *sections;
    bk_static_opts stat;
    bk_dynamic_opts dyn;
    bk_modal_opts modal;         /* (and of the buckling analysis: buckling.c) */
    double *qd0;                 /* [ndof] initial velocities (dynamic) */
    bk_output_opts output;
    int nrecord;
    bk_model_record *records;    /* the interaction modules' records, in the file's order */
    int nscene_warning;
    char **scene_warnings;       /* the scene reader's warnings (owned), first in summary.json */
} bk_model;

/* The record named `name`, or NULL when the model has none. */
const bk_model_record *bk_model_record_find(const bk_model *m, const char *name);

/* Reads a model file.  `avail` lists the kernel descriptors linked into this
 * solver.  On error returns NULL and writes one line to `err` naming the file
 * and what was expected. */
bk_model *bk_model_read(const char *path, const bk_pair *const *avail, int navail, FILE *err);
void bk_model_free(bk_model *m);

/* Binds every joint of the model to its generated kernel in kinds[nkinds] by
 * type name.  Returns 0, or -1 after one line to err. */
int bk_model_bind_joints(bk_model *m, const bk_joint_kind *const *kinds, int nkinds, FILE *err);

/* What the layers below the analyses may know of the analysis: whether its
 * states form a path (load steps or time steps: sensors, sections and frames
 * per state) and whether the path's parameter is time (dynamics) or the load
 * factor: the kind of path the options schema gives each analysis
 * (bk_options.h bk_analysis_path).  The analyses themselves are chosen by
 * their modules (analysis/analysis.h).  The output does not ask these: the
 * analysis tells it the kind in its plan (output/output.h, tests/test_layout.py). */
static inline int bk_model_on_path(const bk_model *m)
{
    return bk_analysis_path(m->analysis) != BK_PATH_NONE;
}

static inline int bk_model_in_time(const bk_model *m)
{
    return bk_analysis_path(m->analysis) == BK_PATH_TIME;
}

/* A path in the load factor (statics: load control or continuation). */
static inline int bk_model_in_load(const bk_model *m)
{
    return bk_analysis_path(m->analysis) == BK_PATH_LOAD;
}

#endif
