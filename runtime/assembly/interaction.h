/* interaction.h -- everything that adds to the force residual besides the
 * elements' internal forces, behind one interface: follower moments on
 * sections, loads with amplitudes, follower and distributed loads and tendons
 * (loads.c), contact with rigid primitives, contact between beams.  The
 * system holds the model's interactions in a fixed order, made once by
 * bk_system_create; the analyses reach them only through the loops below.
 *
 * An interaction is a module: a file of assembly/ that defines, at the start
 * of a line,
 *   const bk_interaction_module bk_interaction_NAME = {...};
 * The build finds every such definition and makes the table of them
 * (gen/solver_build.py interaction_table_source), so a new interaction is its
 * module, the scene module that writes its record (gen/scene/, see
 * gen/scene/interactions.py) and its tests: nothing else names it.  A module
 * that reads a record of the model file (model/records.c) is made when the
 * model has that record; make reads it (model/reader.h rd_open_record).
 *
 * An interaction gives:
 *   assemble    (required) its generalized forces at q on the path point p,
 *               subtracted from fint[ndof] (fint holds internal minus
 *               external forces), and, when Ax is not NULL, its Jacobian
 *               d(-Q)/dq added to the Newton matrix values Ax (system.h's
 *               pattern: the element blocks).  0, or -1 on a non-finite value.
 *   prepare     (optional) called by the Newton solver before each iteration
 *               at q: an interaction whose Jacobian couples elements the
 *               pattern may not couple yet (beam-to-beam contact) asks for
 *               their blocks here (system.h bk_system_couple); 0, or -1 when
 *               out of memory.
 *   step_limit  (optional) the largest fraction in (0, 1] of the correction
 *               dx[neq] (on the equations, system.h) that keeps its state
 *               admissible (contact: no gap crosses zero); NULL: 1.
 *   accept      (optional) its per-step state update after an accepted
 *               equilibrium or time step (active sets, friction history).
 *   tables      (optional) registers its result tables in ts (base/tables.h)
 *               in the output directory dir; 0, or -1 with a message on err.
 *   rows        (optional) its rows of an output step (step, t: the time or
 *               the load factor) at q, through the rows' queue rq (csvrow.h).
 *   frame       (optional) its part of ParaView frame number `frame` (time or
 *               load factor t) at q: files of its own in dir next to the
 *               frame's step_NNNNNN.vtu; 0, or -1 with a message on err.
 *   uncounted_energy  1 when it stores energy that the dynamic energy balance
 *               does not count (a contact barrier: a step too long for it
 *               can create energy, which dynamics then warns of).
 *   cut_predictors  1 when an analysis must cut its predicted state (secant,
 *               constant acceleration, arc-length tangent) to the step limit
 *               measured from the last accepted state: a prediction can jump
 *               over what the limit guards (beam-to-beam contact: one beam
 *               predicted beyond another, at a positive distance again).
 *   keeps_apart  1 when it keeps the beams' sections apart (beam-to-beam
 *               contact): the output's check for beams passing through one
 *               another (output/overlap.h) is then off.
 *   depends     (optional) what its forces depend on besides the elements'
 *               state, given its data: bits BK_DEPENDS_* below (the analyses
 *               ask the loops below, never the model's load lists);
 *               NULL: BK_DEPENDS_Q | BK_DEPENDS_X (the safe answer); 0: it
 *               adds no force (the loads of a model whose loads are all dead
 *               loads of the load factor: there to answer element_loads).
 *   potential   (optional) the potential at q and the path variable x of
 *               its forces that have one, relative to the reference state,
 *               added to *Vg (gravity) or *Vf (other forces): the dynamic
 *               energy balance's external potentials.
 *   element_loads  (optional) its forces that act along element e (inside
 *               it, or spread over it: what the element's own section forces
 *               carry besides its nodal forces) at q and the path variable x,
 *               over e's DOFs, added to Qe[ndof of e]: the section forces
 *               (output/sections.c) subtract them from the element's nodal
 *               forces.  Called from several threads at once (for different
 *               elements), and from the output's writer thread while the
 *               solve goes on: it must not write self, nor read what the
 *               other operations write (it answers from the model, q and x).
 *   summary     (optional) its entry of summary.json at the final state q:
 *               the JSON value's text into buf[n]; 0, or -1 for none
 *               (summary_key names the entry).
 *   free        (optional) frees its own data (and completes the files its
 *               frames began: a collection of them).
 * The constraint rows (multipliers) are not interactions: constraints.c. */
#ifndef BK_INTERACTION_H
#define BK_INTERACTION_H

#include <stddef.h>
#include <stdio.h>

struct bk_tables;
struct bk_rowqueue;

struct bk_system;

/* A point of the path: factor scales the loads proportional to the load
 * factor (statics: the load factor; dynamics: 1), x is the variable of the
 * amplitudes (statics: the load factor; dynamics: the time); in dynamics qd
 * the velocities at q (NULL: at rest, statics) and gp the factor of the
 * velocity in the Newton matrix (dq'/dq: gamma' of generalized-alpha, 0 in
 * statics), for forces that depend on velocities (actuators' feedback). */
typedef struct bk_path {
    double factor;
    double x;
    const double *qd;
    double gp;
} bk_path;

/* What an interaction's forces depend on (its depends()):
 *   FACTOR  they are p->factor times those at factor 1, whatever x: work of
 *           external loads scaled by the load factor (a load that
 *           continuation can scale; its rate in the factor is exact);
 *   X       they change with the path variable p->x (amplitudes, prescribed
 *           placements; statics: the load factor, dynamics: the time);
 *   Q       they change with the configuration (follower loads, moments on
 *           sections, contact, springs): its Jacobian is not zero. */
#define BK_DEPENDS_FACTOR 1u
#define BK_DEPENDS_X 2u
#define BK_DEPENDS_Q 4u

typedef struct bk_interaction_ops {
    const char *name;
    int (*assemble)(void *self, struct bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax);
    int (*prepare)(void *self, struct bk_system *s, const double *q);
    double (*step_limit)(void *self, const struct bk_system *s, const double *q, const double *dx);
    void (*accept)(void *self, const struct bk_system *s, const double *q, const bk_path *p);
    int (*tables)(void *self, const struct bk_system *s, struct bk_tables *ts, const char *dir, FILE *err);
    void (*rows)(void *self, const struct bk_system *s, int step, double t, const double *q, struct bk_rowqueue *rq);
    int (*frame)(void *self, const struct bk_system *s, const char *dir, int frame, double t, const double *q,
                 FILE *err);
    const char *summary_key;
    int uncounted_energy;            /* 1: it stores energy the energy balance does not count (a barrier) */
    int cut_predictors;              /* 1: the analyses' predictors are cut to its step limit (a predicted
                                      * state may carry one beam through another, unseen by the limit) */
    int keeps_apart;                 /* 1: it keeps the beams' sections apart (beam-to-beam contact) */
    int (*summary)(void *self, const struct bk_system *s, const double *q, char *buf, size_t n);
    void (*free)(void *self);
    unsigned (*depends)(const void *self, const struct bk_system *s);
    void (*potential)(void *self, const struct bk_system *s, const double *q, double x, double *Vg, double *Vf);
    void (*element_loads)(const void *self, const struct bk_system *s, const double *q, double x, int e,
                          double *Qe);
} bk_interaction_ops;

/* An interaction module: its operations; its place in every sum (ascending
 * order; the built-in ones first); the name of the model record it reads, or
 * NULL for one whose data the model has in its own records (then present
 * says whether the model has any); make builds its data into *self (the
 * record: NULL for a built-in one): 0, or -1 after one line to err (*self is
 * freed through ops->free either way). */
struct bk_model;
struct bk_model_record;
typedef struct bk_interaction_module {
    const bk_interaction_ops *ops;
    int order;
    const char *record;
    int (*present)(const struct bk_model *m);
    int (*make)(struct bk_system *s, const struct bk_model_record *rec, void **self, FILE *err);
} bk_interaction_module;

/* The table of every module of assembly/ (generated at build time). */
extern const bk_interaction_module *const bk_interaction_table[];
extern const int bk_interaction_count;

typedef struct bk_interaction {
    const bk_interaction_ops *ops;
    void *self;                      /* owned through ops->free (may be NULL) */
} bk_interaction;

/* The interactions the model has, in the modules' order, into s->inter
 * (allocated here; s->ninter of them).  0, or -1 after one line to err. */
int bk_interactions_create(struct bk_system *s, FILE *err);
void bk_interactions_free(struct bk_system *s);

/* Every interaction's assemble, in order: subtracts their forces at (q, p)
 * from fint and adds their Jacobians to Ax (when not NULL).  0, or -1 when
 * one gave a non-finite value. */
int bk_assemble_interactions(struct bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax);
/* Every interaction's prepare at q (before a Newton iteration): 0, or -1
 * when out of memory. */
int bk_interactions_prepare(struct bk_system *s, const double *q);
/* The smallest step limit of the interactions for the correction dx (1 when
 * none limits it). */
double bk_interactions_step_limit(const struct bk_system *s, const double *q, const double *dx);
/* Every interaction's frame (see frame above); 0, or -1 when one failed. */
int bk_interactions_frame(const struct bk_system *s, const char *dir, int frame, double t, const double *q, FILE *err);
/* 1 when an interaction of s asks the analyses to cut their predictors. */
int bk_interactions_cut_predictors(const struct bk_system *s);
/* 1 when an interaction of s keeps the beams' sections apart. */
int bk_interactions_keep_apart(const struct bk_system *s);
/* 1 when an interaction of s stores energy the energy balance does not count. */
int bk_interactions_uncounted_energy(const struct bk_system *s);
/* A depends() for the modules whose forces depend on q alone (springs,
 * contact between beams): BK_DEPENDS_Q. */
unsigned bk_depends_on_q(const void *self, const struct bk_system *s);
/* What an interaction depends on (its depends(), or the safe answer). */
unsigned bk_interaction_depends(const struct bk_system *s, int k);
/* 1 when an interaction of s adds forces that change along a path at fixed
 * q (with the load factor or the path variable x): a load to scale. */
int bk_interactions_load_on_path(const struct bk_system *s);
/* 1 when an interaction's Jacobian changes along a path at fixed q (it
 * depends on q and on the factor or x): the Newton matrix at q is then not
 * the same at every load factor. */
int bk_interactions_tangent_on_path(const struct bk_system *s);
/* The rate along the static path (factor = x = lam) of the residual's load
 * terms at q, over the equations: rl[eq[i]] = d/dlam of the interactions'
 * part of fint (exact for those proportional to the factor, by central
 * differences with step 1e-6 max(1, |lam|) for those depending on x) minus
 * fext[i], the dead loads of unit factor; rl's constraint rows are zeroed.
 * fol[ndof] is scratch. */
void bk_interactions_path_rate(struct bk_system *s, const double *q, double lam, const double *fext, double *rl,
                               double *fol);
/* Every interaction's potential at (q, x) added to *Vg and *Vf. */
void bk_interactions_potentials(const struct bk_system *s, const double *q, double x, double *Vg, double *Vf);
/* Every interaction's accept after an accepted state. */
void bk_interactions_accept(const struct bk_system *s, const double *q, const bk_path *p);

#endif
