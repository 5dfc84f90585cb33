/* beam_contact_force.c -- the beam contact interaction's forces and Jacobian,
 * step limiter, its rows of contacts.csv, summary.json "contact" and state, and
 * its operations (beam_contact.h; the broad phase and the geometry:
 * beam_contact.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/beam_contact.h"
#include "assembly/beam_contact_impl.h"
#include "assembly/contact_force.h"
#include "base/csvrow.h"
#include "base/tables.h"

/* ---- assemble: per candidate, the two elements' forces and four blocks ----
 * The pairs of segments of a candidate add their gradients and Hessians on
 * the candidate's sample points (gp, Hp: element i's points, then element j's
 * unless j = i); the candidate's end takes them through the points' shape
 * functions to the elements once (a few pairs of segments share each point). */

typedef struct assembly {
    bc_work *w;
    bk_system *s;
    double *fint, *Ax;
    int touched, bad;
} assembly;

/* The number of the candidate's sample points (ns or 2 ns). */
static int local_points(const bc_work *w, const seg_pair *sp)
{
    const int ns = w->bm->sets[sp->c].nsample;
    return sp->i == sp->j ? ns : 2 * ns;
}

/* gp, Hp through the shape functions into fe[side], Kb[2 sP + sQ]. */
static void to_elements(const bc_work *w, const bk_model *m, const seg_pair *sp, int with_K)
{
    const int ns = w->bm->sets[sp->c].nsample, nsides = sp->i == sp->j ? 1 : 2, n3 = 3 * nsides * ns;
    const int el[2] = {sp->ei, sp->ej};
    const bk_element *et[2] = {bk_elem_type(m, sp->ei), bk_elem_type(m, sp->ej)};
    const double *N[2] = {w->N + (size_t)(w->base[sp->c] + sp->i * ns) * w->nsh,
                          w->N + (size_t)(w->base[sp->c] + sp->j * ns) * w->nsh};
    for (int sd = 0; sd < nsides; ++sd) {
        const int nd = bk_elem_type(m, el[sd])->ndof;
        memset(w->fe[sd], 0, (size_t)nd * sizeof *w->fe[sd]);
        for (int k = 0; k < ns; ++k) {
            if (!w->used[sd * ns + k])
                continue;
            const double *Nk = N[sd] + (size_t)k * w->nsh, *gk = w->gp + 3 * (sd * ns + k);
            for (int a = 0; a < et[sd]->nshape; ++a)
                for (int r = 0; r < 3; ++r)
                    w->fe[sd][et[sd]->shape_dof[a] + r] += Nk[a] * gk[r];
        }
    }
    if (!with_K)
        return;
    for (int sQ = 0; sQ < nsides; ++sQ) {
        const int nq = 3 * et[sQ]->nshape;
        /* T[(p, r)][(b, c)] = sum over the points q of side sQ of Hp[(p, r)][(q, c)] N_q[b] */
        const int nsq = et[sQ]->nshape;
        for (int row = 0; row < n3; ++row) {
            if (!w->used[row / 3])
                continue;                        /* (rows and columns of untouched points are zero) */
            double *restrict Trow = w->T + (size_t)row * nq;
            const double *Hrow = w->Hp + (size_t)row * n3 + 3 * sQ * ns;
            for (int m = 0; m < nq; ++m)
                Trow[m] = 0.0;
            for (int k = 0; k < ns; ++k) {       /* (the sum over k in order, as a dot product would) */
                if (!w->used[sQ * ns + k])
                    continue;
                const double *Nk = N[sQ] + (size_t)k * w->nsh, h0 = Hrow[3 * k], h1 = Hrow[3 * k + 1],
                             h2 = Hrow[3 * k + 2];
                for (int b = 0; b < nsq; ++b) {
                    Trow[3 * b] += h0 * Nk[b];
                    Trow[3 * b + 1] += h1 * Nk[b];
                    Trow[3 * b + 2] += h2 * Nk[b];
                }
            }
        }
        for (int sP = 0; sP < nsides; ++sP) {
            const int ndP = et[sP]->ndof, ndQ = et[sQ]->ndof;
            double *K = w->Kb[2 * sP + sQ];
            memset(K, 0, (size_t)ndP * (size_t)ndQ * sizeof *K);
            for (int a = 0; a < et[sP]->nshape; ++a)
                for (int r = 0; r < 3; ++r) {
                    double *Krow = K + (size_t)(et[sP]->shape_dof[a] + r) * (size_t)ndQ;
                    for (int k = 0; k < ns; ++k) {
                        if (!w->used[sP * ns + k])
                            continue;
                        const double na = N[sP][(size_t)k * w->nsh + a];
                        const double *Trow = w->T + (size_t)(3 * (sP * ns + k) + r) * nq;
                        for (int b = 0; b < et[sQ]->nshape; ++b)
                            for (int c = 0; c < 3; ++c)
                                Krow[et[sQ]->shape_dof[b] + c] += na * Trow[3 * b + c];
                    }
                }
        }
    }
}

static void assemble_candidate(void *ctx, seg_pair *sp, int end)
{
    assembly *a = ctx;
    bc_work *w = a->w;
    const bk_model *m = a->s->m;
    if (!end) {
        a->touched = 0;
        return;
    }
    if (!a->touched)
        return;
    to_elements(w, m, sp, a->Ax != NULL);
    const int one = sp->i == sp->j;             /* far segments of one element: its own block */
    a->bad |= bk_scatter(m, sp->ei, w->fe[0], 1.0, a->fint);
    if (!one)
        a->bad |= bk_scatter(m, sp->ej, w->fe[1], 1.0, a->fint);
    if (!a->Ax)
        return;
    const int el[2] = {sp->ei, sp->ej};
    for (int b = 0; b < (one ? 1 : 4); ++b) {
        if (el[b / 2] == el[b % 2])              /* an element's own block: its scatter map, no search */
            bk_scatter_matrix(a->s, el[b / 2], w->Kb[b], 1.0, a->Ax);
        else
            bk_scatter_coupling(a->s, el[b / 2], el[b % 2], w->Kb[b], 1.0, a->Ax);
    }
}

/* The pair's energy gradient g[12] and Hessian H[144] (H may be NULL) in its
 * ends' coordinates: the barrier's, kappa e(x) (bc_pair_energy), within the
 * reach, and the lagged friction's where the pair has a lagged state lg. */
static void pair_terms(const bk_beam_contact_set *set, const seg_pair *sp, const bc_lag *lg, double *g, double *H)
{
    double Hb[144];
    memset(g, 0, 12 * sizeof *g);
    if (H)
        memset(H, 0, 144 * sizeof *H);
    if (sp->dist < set->shat) {
        bc_pair_energy(sp, set->radius[sp->i] + set->radius[sp->j], set->shat, sp->hi, sp->hj, g, H ? Hb : NULL);
        for (int i = 0; i < 12; ++i)
            g[i] *= set->kappa;
        for (int i = 0; H && i < 144; ++i)
            H[i] = set->kappa * Hb[i];
    }
    if (lg)
        bc_friction(set, lg, sp, g, H);
}

/* E = kappa e(x) (bc_pair_energy) and friction on the 12 coordinates of the
 * segments' ends, added on the candidate's sample points. */
static void assemble_pair(void *ctx, seg_pair *sp)
{
    assembly *a = ctx;
    bc_work *w = a->w;
    const bk_beam_contact_set *set = &w->bm->sets[sp->c];
    if (!(sp->dist > 0.0)) {
        a->bad = 1;                          /* through a beam: not an admissible state */
        return;
    }
    const bc_lag *lg = set->mu > 0.0 ? bc_lag_find(w, sp) : NULL;
    if (sp->dist >= set->shat && !lg)
        return;
    const int ns = set->nsample, n3 = 3 * local_points(w, sp);
    if (!a->touched) {
        memset(w->gp, 0, (size_t)n3 * sizeof *w->gp);
        memset(w->used, 0, (size_t)n3 / 3);
        if (a->Ax)
            memset(w->Hp, 0, (size_t)n3 * (size_t)n3 * sizeof *w->Hp);
        a->touched = 1;
    }
    double g[12], H[144];
    pair_terms(set, sp, lg, g, a->Ax ? H : NULL);
    int li[4];                               /* the pair's ends among the candidate's points */
    for (int P = 0; P < 4; ++P)
        li[P] = P < 2 ? sp->pidx[P] - (w->base[sp->c] + sp->i * ns)
                      : sp->pidx[P] - (w->base[sp->c] + sp->j * ns) + (sp->i == sp->j ? 0 : ns);
    for (int P = 0; P < 4; ++P)
        w->used[li[P]] = 1;
    for (int P = 0; P < 4; ++P)
        for (int r = 0; r < 3; ++r) {
            w->gp[3 * li[P] + r] += g[3 * P + r];
            if (!a->Ax)
                continue;
            double *Hrow = w->Hp + (size_t)(3 * li[P] + r) * n3;
            for (int Q = 0; Q < 4; ++Q)
                for (int c = 0; c < 3; ++c)
                    Hrow[3 * li[Q] + c] += H[12 * (3 * P + r) + 3 * Q + c];
        }
}

/* A candidate whose elements' boxes are beyond the barrier's reach (plus the
 * radii) and that has no pair rubbing adds nothing. */
static int far_candidate(void *ctx, const seg_pair *sp, double gap)
{
    const bc_work *w = ((const assembly *)ctx)->w;
    const bk_beam_contact_set *set = &w->bm->sets[sp->c];
    return gap - set->radius[sp->i] - set->radius[sp->j] >= set->shat * (1.0 + 1e-6) &&
           !(set->mu > 0.0 && bc_lag_any(w, sp->c, sp->i, sp->j));
}

static int bc_assemble(void *self, bk_system *s, const double *q, const bk_path *path, double *fint, double *Ax)
{
    (void)path;
    bc_work *w = self;
    bc_points(w, s, q, 0, w->X);
    assembly a = {.w = w, .s = s, .fint = fint, .Ax = Ax};
    bc_each_near_pair(w, s->m, assemble_pair, assemble_candidate, far_candidate, &a);
    return a.bad ? -1 : 0;
}

static double norm3(const double *x)
{
    return sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}

/* ---- the state: forces on the beams, pairs in reach, smallest distance ---- */

typedef struct state {
    const bc_work *w;
    const bk_model *m;
    int c;
    double *F, dmin, normal;
    int nactive;
} state;

/* The contact force (barrier and friction) on the segment pair's first
 * segment (fa; the second gets its opposite) and its magnitude (0: none);
 * when fn, ft are not NULL, the barrier's and the friction's magnitudes. */
double bc_pair_force(const bc_work *w, const bk_model *m, const seg_pair *sp, double *fa, double *fn, double *ft)
{
    (void)m;
    const bk_beam_contact_set *set = &w->bm->sets[sp->c];
    const bc_lag *lg = set->mu > 0.0 ? bc_lag_find(w, sp) : NULL;
    double g[12], f[3] = {0.0, 0.0, 0.0};
    fa[0] = fa[1] = fa[2] = 0.0;
    if (fn)
        *fn = *ft = 0.0;
    if (!(sp->dist > 0.0) || (sp->dist >= set->shat && !lg))
        return 0.0;
    pair_terms(set, sp, NULL, g, NULL);          /* the barrier's */
    for (int r = 0; r < 3; ++r)
        fa[r] = -(g[r] + g[3 + r]);
    if (lg) {                                    /* friction's */
        memset(g, 0, sizeof g);
        bc_friction(set, lg, sp, g, NULL);
        for (int r = 0; r < 3; ++r)
            f[r] = -(g[r] + g[3 + r]);
    }
    if (fn)
        *fn = norm3(fa), *ft = norm3(f);
    for (int r = 0; r < 3; ++r)
        fa[r] += f[r];
    return norm3(fa);
}

static void state_pair(void *ctx, seg_pair *sp)
{
    state *st = ctx;
    if (sp->c != st->c)
        return;
    st->dmin = fmin(st->dmin, sp->dist);
    double fa[3];
    const double fn = bc_pair_force(st->w, st->m, sp, fa, NULL, NULL);
    if (fn <= 0.0)
        return;
    st->nactive++;
    st->normal += fn;
    const int ca = st->w->chain[st->w->ebase[sp->c] + sp->i], cb = st->w->chain[st->w->ebase[sp->c] + sp->j];
    for (int r = 0; r < 3; ++r) {
        st->F[3 * ca + r] += fa[r];
        st->F[3 * cb + r] -= fa[r];
    }
}

static bc_work *work_of(const bk_system *s)
{
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops == &bk_beam_contact_ops)
            return s->inter[k].self;
    return NULL;
}

int bk_beam_contact_state(const bk_system *s, const double *q, int c, double *F, int *nactive, double *normal,
                          double *min_distance)
{
    bc_work *w = work_of(s);
    if (!w || c < 0 || c >= w->bm->nset)
        return -1;
    memset(F, 0, 3 * (size_t)w->bm->sets[c].nchain * sizeof *F);
    bc_points(w, s, q, 0, w->X);
    state st = {.w = w, .m = s->m, .c = c, .F = F, .dmin = INFINITY};
    bc_each_pair(w, s->m, state_pair, NULL, &st);
    if (nactive)
        *nactive = st.nactive;
    if (normal)
        *normal = st.normal;
    *min_distance = st.dmin;
    return 0;
}

/* ---- outputs ---- */

/* The name of the beam element e belongs to (sections.csv's records), or "?". */
static const char *beam_name(const bk_model *m, int e)
{
    for (int k = 0; k < m->nsection; ++k)
        if (m->sections[k].elem == e)
            return m->sections[k].beam;
    return "?";
}

/* summary.json "contact" (merged with rigid contact's entry when both run:
 * min_distance the smaller, max_penetration the larger, run_info.c):
 * min_distance and beam_min_distance the smallest distance between the
 * sections of segments that may touch (null: none near), the largest
 * penetration (0: a state through a beam is refused), the element pairs the
 * pattern couples, and per set (beam_sets) the pairs of segments within the
 * barrier's reach, the sum of their forces' magnitudes and the total contact
 * force on each beam (zero for a beam touching only itself). */
static int bc_summary(void *self, const bk_system *s, const double *q, char *buf, size_t n)
{
    const bc_work *w = self;
    const bk_beam_contact_model *bm = w->bm;
    double dmin = INFINITY, F[3 * 64];
    int len = 0;
    for (int c = 0; c < bm->nset; ++c) {
        double d;
        if (bm->sets[c].nchain > 64 || bk_beam_contact_state(s, q, c, F, NULL, NULL, &d) != 0)
            return -1;
        dmin = fmin(dmin, d);
    }
    if (isfinite(dmin))
        len = snprintf(buf, n, "{\"min_distance\": %.17g, \"max_penetration\": %.17g, \"beam_min_distance\": %.17g, "
                       "\"element_pairs\": %d, \"beam_sets\": [", dmin, dmin < 0.0 ? -dmin : 0.0, dmin, s->ncouple);
    else
        len = snprintf(buf, n, "{\"min_distance\": null, \"max_penetration\": 0, \"beam_min_distance\": null, "
                       "\"element_pairs\": %d, \"beam_sets\": [", s->ncouple);
    for (int c = 0; c < bm->nset && len > 0 && (size_t)len < n; ++c) {
        const bk_beam_contact_set *set = &bm->sets[c];
        int nact;
        double d, fn;
        bk_beam_contact_state(s, q, c, F, &nact, &fn, &d);
        len += snprintf(buf + len, n - (size_t)len, "%s{\"active_pairs\": %d, \"normal_force\": %.17g, \"beams\": {",
                        c ? ", " : "", nact, fn);
        for (int b = 0; b < set->nchain && len > 0 && (size_t)len < n; ++b)
            len += snprintf(buf + len, n - (size_t)len, "%s\"%s\": [%.17g, %.17g, %.17g]", b ? ", " : "",
                            beam_name(s->m, set->elems[set->chain_off[b]]), F[3 * b], F[3 * b + 1], F[3 * b + 2]);
        if (len > 0 && (size_t)len < n)
            len += snprintf(buf + len, n - (size_t)len, "}}");
    }
    if (len > 0 && (size_t)len < n)
        len += snprintf(buf + len, n - (size_t)len, "]}");
    return len > 0 && (size_t)len < n ? 0 : -1;
}

/* contacts.csv (shared with rigid contact, assembly/contact_force.h): per
 * output step every pair of segments within the barrier's reach or rubbing:
 * the set, primitive -1, the first element and its segment, the midpoint of
 * the closest points, the sections' distance, the normal force (the pair's
 * whole force less friction's share, its magnitude), the friction force's
 * magnitude, the friction state (none; stick: slip since the anchor below the
 * tolerance; slip), the force on the first beam (N; the second gets its
 * opposite), and the second beam, its element and segment. */
static int bc_tables(void *self, const bk_system *s, bk_tables *ts, const char *dir, FILE *err)
{
    (void)s;
    bc_work *w = self;
    w->table = bk_tables_find(ts, bk_contacts_csv.name);
    if (!w->table)
        w->table = bk_tables_open(ts, dir, &bk_contacts_csv, 1, err);
    return w->table ? 0 : -1;
}

typedef struct rows {
    const bc_work *w;
    const bk_model *m;
    int step;
    double t;
    bk_rowqueue *rq;
} rows;

static void row_pair(void *ctx, seg_pair *sp)
{
    rows *rw = ctx;
    double fa[3], fn, ft, ut[3];
    const double f = bc_pair_force(rw->w, rw->m, sp, fa, &fn, &ft);
    if (f <= 0.0)
        return;
    const bk_beam_contact_set *set = &rw->w->bm->sets[sp->c];
    const bc_lag *lg = set->mu > 0.0 ? bc_lag_find(rw->w, sp) : NULL;
    bk_row r;
    bk_row_begin(&r, rw->w->table, rw->rq);
    bk_row_int(&r, rw->step);
    bk_row_num(&r, rw->t);
    bk_row_int(&r, sp->c);
    bk_row_int(&r, -1);
    bk_row_int(&r, sp->ei);
    bk_row_int(&r, sp->k);
    for (int d = 0; d < 3; ++d)
        bk_row_num(&r, 0.5 * (sp->pts[0][d] + sp->sg * (sp->pts[1][d] - sp->pts[0][d]) + sp->pts[2][d] +
                              sp->tau * (sp->pts[3][d] - sp->pts[2][d])));
    bk_row_num(&r, sp->dist);
    bk_row_num(&r, fn);
    bk_row_num(&r, ft);
    bk_row_str(&r, !lg ? "none" : bc_slip(lg, sp, ut) < set->slip ? "stick" : "slip");
    for (int d = 0; d < 3; ++d)
        bk_row_num(&r, fa[d]);
    bk_row_str(&r, beam_name(rw->m, sp->ej));
    bk_row_int(&r, sp->ej);
    bk_row_int(&r, sp->l);
    bk_row_end(&r);
}

static void bc_rows(void *self, const bk_system *s, int step, double t, const double *q, bk_rowqueue *rq)
{
    bc_work *w = self;
    if (!w->table)
        return;
    bc_points(w, s, q, 0, w->X);
    rows rw = {.w = w, .m = s->m, .step = step, .t = t, .rq = rq};
    bc_each_pair(w, s->m, row_pair, NULL, &rw);
}

const bk_interaction_ops bk_beam_contact_ops = {.name = "beam_contact", .assemble = bc_assemble,
                                                .prepare = bc_prepare, .step_limit = bc_step_limit, .accept = bc_accept,
                                                .tables = bc_tables, .rows = bc_rows, .frame = bc_frame,
                                                .summary_key = "contact", .uncounted_energy = 1, .cut_predictors = 1,
                                                .keeps_apart = 1,
                                                .summary = bc_summary, .free = bc_free, .depends = bk_depends_on_q};
