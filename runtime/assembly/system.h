/* system.h -- the algebraic system of a model: equation numbering, the sparse
 * pattern of the Newton matrix, and assembly of forces and tangents.
 *
 * Unknowns: the free DOFs (those not held fixed), then one multiplier per
 * linear constraint.  The Newton matrix is
 *     [ K    s G^T ]
 *     [ s G  0     ]
 * with s = cscale, a stiffness-sized factor that keeps the constraint rows on
 * the scale of the stiffness rows.  The pattern and each element's scatter map
 * into it are computed once; assembly does no allocation.  Element kernels
 * run in parallel (OpenMP, when compiled with it), one contiguous part of the
 * elements per thread, each entry summed in element order: results are
 * bit-identical for any thread count.
 */
#ifndef BK_SYSTEM_H
#define BK_SYSTEM_H

#include <stdio.h>

#include "assembly/interaction.h"
#include "model/model.h"

typedef struct bk_system {
    const bk_model *m;
    int nfree, ncon, neq;
    int *eq;                 /* [ndof] equation of each DOF, -1 when fixed     */
    int *Ap, *Ai;            /* CSC pattern, neq columns                      */
    long nnz;
    int *eslot_off;          /* [nelem+1] offsets into eslot                  */
    int *eslot;              /* CSC index of element entry (r, c), -1 if fixed */
    unsigned char *efirst;   /* per eslot entry: the slot's first term in element
                              * order (stored, not added: Ax is not zeroed first) */
    long *zslot, nzslot;     /* slots no element entry writes (zeroed by assembly) */
    int *cslot;              /* per constraint term: CSC index of s G, s G^T  */
    int *cslot_off;          /* [ncon+1]                                      */
    int *diag;               /* [nfree] CSC index of each free DOF's diagonal  */
    int *dinc_ptr, *dinc;    /* the elements at each DOF d, in element order:
                              * dinc[2 i] the element, dinc[2 i + 1] d's place in
                              * it, i in [dinc_ptr[d], dinc_ptr[d + 1]); made with the
                              * pattern, freed once the parts are made */
    /* joints nonlinear in q (model->nlcons): constraint rows nlincon.., one
     * block per joint: its first row jrow[j] (jrow[nnlcon] = ncon) and CSC
     * slots jslot[jslot_off[j]..]: NX x NX of the Hessian term, then nrow x NX
     * of s G and of s G^T (-1 where a coordinate is fixed or constant) */
    int *jrow, *jslot, *jslot_off;
    double cscale;
    int maxdof;              /* largest element DOF count                     */
    double *fe, *Ke;         /* element work buffers (owned)                  */
    /* Evaluation groups: runs of up to BK_LANES consecutive elements of one
     * pair that has lane kernels (one call evaluates the run), or a single
     * element.  They depend on the model only, never on the thread count. */
    int ngroup;
    int *group;              /* [ngroup+1] first element of each group        */
    size_t slot_q, slot_K, slot_tab, slot_mat; /* doubles from one thread's slot of
                              * bq/bf, bK, btab, bmat to the next's (a group's
                              * size, and with threads BK_THREAD_GAP beyond it) */
    double *bq, *bf, *bK;    /* per-thread evaluation buffers (one slot each)  */
    double *btab, *bmat;     /* lane-ordered tables and material parameters   */
    /* Parallel assembly (nthreads > 1 and enough elements): npart contiguous
     * runs of groups of about equal cost, part[npart+1] their first groups,
     * several per thread, each taken by the next free thread.  A thread adds
     * a part's terms directly into the slots of fint and Ax that only that
     * part touches; terms for a slot or
     * DOF that two parts touch go to stage[]: an element with such entries
     * has a map pmap[pel[e]..] (nd*nd slot codes, then nd DOF codes: >= 0
     * target, -1 none, <= -2 stage entry -2-code; pel[e] = -1: use eslot).
     * Shared target i (DOFs first, nshared_dof of them, then slots) sums
     * stage[sh_idx[sh_ptr[i]..sh_ptr[i+1]]] in element order into
     * sh_to[i] after the parallel region.  Parts depend on the thread count;
     * the order of every sum does not. */
    int npart;               /* 1: serial                                       */
    int *part;
    long *pel;
    int *pmap;
    double *stage;
    int nshared, nshared_dof;
    int *sh_ptr, *sh_idx;
    long *sh_to;
    int nthreads;            /* OpenMP threads for element evaluation (1: serial) */
    /* Coupling blocks (bk_system_couple): element pairs a < b whose blocks
     * (rows of a, columns of b and the transpose) the pattern holds besides
     * what elements, constraints and joints couple; sorted, owned.  The
     * pattern grows when they do, and pattern_gen counts its versions: who
     * keeps anything made from the pattern (the Newton solver's matrix and
     * linear-solver plan) makes it anew when pattern_gen changed. */
    int ncouple, capcouple;
    int *couple;             /* [2 ncouple] */
    int pattern_gen;
    bk_interaction *inter;   /* owned: [ninter] the model's interactions (interaction.h) */
    int ninter;
} bk_system;

bk_system *bk_system_create(const bk_model *m, FILE *err);
void bk_system_free(bk_system *s);

/* Internal force over all DOFs into fint[ndof]; when Ax is not NULL also the
 * tangent, written into Ax (nnz values, zeroed here).  Returns 0, or -1 when a
 * kernel produced a non-finite value. */
int bk_assemble_internal(bk_system *s, const double *q, double *fint, double *Ax);

/* Strain energy of the configuration q (J). */
double bk_strain_energy(const bk_system *s, const double *q);

/* Generalized external load of unit load factor into fext[ndof] (zeroed here):
 * point forces and gravity. */
void bk_external_load(const bk_system *s, double *fext);

/* Shape functions N[nshape] of the point force f: at its point (xi, y, z) of
 * the element, or averaged over the rectangular section at xi (f->section). */
void bk_force_shape(const bk_model *m, const bk_force_load *f, double *N);

/* The gravity part alone, into fg[ndof] (zeroed here; zero when gravity has an
 * amplitude: bk_assemble_loads applies it then). */
void bk_gravity_load(const bk_system *s, double *fg);

/* Configuration-dependent loads (moments on sections) at load factor lam:
 * subtracts lam Q(q) from fint[ndof] and, when Ax is not NULL, adds
 * -lam dQ/dq to the tangent. */
void bk_assemble_follower(bk_system *s, const double *q, double lam, double *fint, double *Ax);

/* Constraint part of the Newton system at time t: adds s G^T nu to
 * r[0..nfree), writes s (G q - g) into r[nfree..neq) (r may be NULL), and, when
 * Ax is not NULL, s G and s G^T. */
void bk_assemble_constraints(const bk_system *s, const double *q, const double *nu, double t,
                             double *r, double *Ax);

/* Right-hand side of the constraint rows of the consistent initial
 * accelerations: r[nfree + c] = -s (d^2/dt^2 of row c at fixed q'') given q,
 * qd (linear rows: 2 G' q' + G'' q - g''; joints: q'^T d2 g_c/dq2 q'). */
void bk_constraint_accel_rhs(const bk_system *s, const double *q, const double *qd, double t, double *r);

/* The Jacobian row c of every constraint at (q, t), unscaled, on the free
 * DOFs: calls add(ctx, equation, value) for each term. */
void bk_constraint_jacobian_row(const bk_system *s, const double *q, double t, int c,
                                void (*add)(void *ctx, int eq, double v), void *ctx);

/* Multipliers for a start: adds to nu[ncon] the correction dnu that minimizes
 * |r + s G^T dnu| over the free rows (r: a residual over the equations at q,
 * nu), i.e. the constraint forces that best balance the other forces; a
 * mechanism held only by its loads (a pendulum under gravity) then has the
 * joints' geometric stiffness from the first Newton iteration on.  Returns 0,
 * or -1 (nu unchanged) when the constraints are dependent or memory ran out. */
int bk_constraint_multipliers(bk_system *s, const double *q, double t, const double *r, double *nu);

/* The joints' Hessian term sum_k lam_k d2 g_k/dq2 at q for unscaled
 * multipliers lam[ncon] (the constraint force is G^T lam; the linear rows have
 * none): calls add(ctx, equation i, equation j, value) for each free pair. */
void bk_constraint_hessian(const bk_system *s, const double *q, double t, const double *lam,
                           void (*add)(void *ctx, int i, int j, double v), void *ctx);

/* k-th time derivative (k = 0, 1, 2) at fixed x of one constraint row:
 * d^k/dt^k [G(t) x - g(t)] (the g term only when with_rhs). */
double bk_constraint_row(const bk_lincon *c, const double *x, double t, int k, int with_rhs);

/* Coefficient of term k of a constraint row at time t (the entry of G(t)). */
double bk_constraint_coef(const bk_lincon *c, int k, double t);

/* The parameters prm[BK_JOINT_NPARAM] of joint c at time (or load factor) t:
 * its geometry and the k-th time derivative (k = 0, 1, 2) of its drive's
 * (c, s) (bk_joint.h; zero for a joint that is not driven).  Returns the
 * drive's th(t) (0 when not driven). */
double bk_joint_params(const bk_nlcon *c, double t, int k, double *prm);

/* The number of joints nonlinear in q (constraint rows after the linear
 * ones, with a geometric stiffness from their multipliers). */
int bk_constraints_nonlinear(const bk_system *s);

/* 1 when a linear constraint's coefficients change along the path (a
 * rotating constraint whose angle has a rate or an amplitude): the Newton
 * matrix then changes with the path variable at fixed q. */
int bk_constraints_on_path(const bk_system *s);

/* Largest |G(t) q - g(t)| over the constraint rows. */
double bk_constraint_residual(const bk_system *s, const double *q, double t);

/* Centreline point xi of element e: position and (if d != NULL) the section
 * frame d1, d2, d3 (NaN where the element defines none). */
void bk_eval_point(const bk_model *m, const double *q, int e, double xi, double *pos, double *d);
/* The weights of element e's position shape functions under gravity, N[nshape]
 * (kg): rho times its volume() plus its point masses' m N(xi). */
void bk_element_weight(const bk_model *m, int e, double *N);
/* The position (and frame d[9], may be NULL) of sensor s at q: bk_eval_point
 * of its element and xi, moved by its offset along d1, d2, d3 (a body point). */
void bk_eval_sensor(const bk_model *m, const double *q, const bk_sensor *s, double *pos, double *d);

/* Adds the coupling blocks of n element pairs pairs[2 n] (any order, repeats
 * and a == b allowed) to the pattern.  When that needs entries the pattern
 * lacks, the pattern, its scatter maps and the parallel assembly's parts are
 * made anew (their sizes and slot numbers change) and pattern_gen grows.
 * Returns 1 when the pattern changed, 0 when not, -1 when out of memory (the
 * system is then unusable). */
int bk_system_couple(bk_system *s, int n, const int *pairs);

/* Adds c K to the Newton matrix values Ax on the block of rows of element ea
 * and columns of element eb (K[nd_a x nd_b] row-major; fixed DOFs skipped):
 * entries the pattern lacks are skipped, and their count returned. */
int bk_scatter_coupling(const bk_system *s, int ea, int eb, const double *K, double c, double *Ax);

/* Element e of the model: its descriptor and DOF count. */
static inline const bk_element *bk_elem_type(const bk_model *m, int e)
{
    return m->pairs[m->elems[e].pair]->element;
}

/* Gather: xe[k] = x[dofs[k]] over the element's DOFs (x indexed by DOF). */
static inline void bk_gather(const bk_model *m, int e, const double *x, double *xe)
{
    const int *d = m->elems[e].dofs;
    const int nd = bk_elem_type(m, e)->ndof;
    for (int k = 0; k < nd; ++k)
        xe[k] = x[d[k]];
}

/* Scatter: x[dofs[k]] += c xe[k] over the element's DOFs.  Returns 1 when xe has
 * a non-finite entry, else 0. */
int bk_scatter(const bk_model *m, int e, const double *xe, double c, double *x);

/* Scatter of an element matrix Ke[ndof*ndof] (row-major) into the Newton
 * matrix values Ax: Ax += c Ke on the entries of free rows and columns. */
void bk_scatter_matrix(const bk_system *s, int e, const double *Ke, double c, double *Ax);

/* Element mass Me[ndof*ndof] = rho (m (x) I3) on the position shape functions'
 * DOFs (zero elsewhere), m[nshape*nshape] = bk_element.mass per unit density;
 * work[nshape*nshape] is scratch. */
void bk_element_mass(const bk_model *m, int e, double *work, double *Me);

/* 1 when some field of the element has the role. */
int bk_element_has_role(const bk_element *et, bk_field_role role);

#endif
