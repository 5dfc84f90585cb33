/* interactions.c -- the built-in interaction modules (follower moments, loads:
 * the model's own records), making the model's interactions in the modules'
 * order, and the loops over them (see interaction.h). */
#include "assembly/interaction.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/loads.h"
#include "assembly/system.h"

/* ---- follower moments on sections (constant_loads.c), scaled by p->factor ---- */

static int follower_assemble(void *self, bk_system *s, const double *q, const bk_path *p, double *fint,
                             double *Ax)
{
    (void)self;
    bk_assemble_follower(s, q, p->factor, fint, Ax);
    return 0;
}

static unsigned follower_depends(const void *self, const bk_system *s)
{
    (void)self, (void)s;
    return BK_DEPENDS_FACTOR | BK_DEPENDS_Q;     /* lam Q(q): turn with the section */
}

static const bk_interaction_ops follower_ops = {.name = "moments", .assemble = follower_assemble,
                                                .depends = follower_depends};

static int has_moments(const bk_model *m)
{
    return m->nmoment > 0;
}

static int make_follower(bk_system *s, const bk_model_record *rec, void **self, FILE *err)
{
    (void)s, (void)rec, (void)err;
    *self = NULL;                    /* no data of its own */
    return 0;
}

const bk_interaction_module bk_interaction_moments = {.ops = &follower_ops, .order = 10, .present = has_moments,
                                                      .make = make_follower};

/* ---- loads with amplitudes, follower and distributed loads, tendons (loads.c), at p->x; the forces of
 * every load record along an element (the section forces') ---- */

static int loads_assemble(void *self, bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax)
{
    bk_assemble_loads_in(s, self, q, p->x, fint, Ax);
    return 0;
}

static void loads_free(void *self)
{
    bk_loads_scratch_free(self);
}

/* Amplitudes of x; follower and distributed loads and tendons depend on q (a
 * dead force with an amplitude does not: counted with them, the safe side).
 * Nothing when the model's loads are all dead loads of the load factor (then
 * the interaction adds no force: it is there to answer element_loads). */
static unsigned loads_depends(const void *self, const bk_system *s)
{
    (void)self;
    return bk_loads_present(s->m) ? BK_DEPENDS_X | BK_DEPENDS_Q : 0u;
}

/* Every load record along element e, the dead ones too (bk_element_loads). */
static void loads_on_element(const void *self, const bk_system *s, const double *q, double x, int e, double *Qe)
{
    (void)self;
    bk_element_loads(s, q, x, e, Qe);
}

static void loads_potential(void *self, const bk_system *s, const double *q, double x, double *Vg, double *Vf)
{
    (void)self;
    bk_load_potentials(s, q, x, Vg, Vf);
}

static const bk_interaction_ops loads_ops = {.name = "loads", .assemble = loads_assemble, .free = loads_free,
                                             .depends = loads_depends, .potential = loads_potential,
                                             .element_loads = loads_on_element};

static int make_loads(bk_system *s, const bk_model_record *rec, void **self, FILE *err)
{
    (void)rec;
    *self = bk_loads_scratch_new(s->maxdof);     /* assembly without allocation */
    if (!*self)
        fprintf(err, "error: loads: out of memory\n");
    return *self ? 0 : -1;
}

/* Present with any load record of the model (bk_element_loads_present): it
 * assembles those of bk_assemble_loads (the dead loads of unit factor are the
 * analyses' fext, system.h bk_external_load; the constant moments the
 * "moments" module's) and answers element_loads for all of them. */
const bk_interaction_module bk_interaction_loads = {.ops = &loads_ops, .order = 20,
                                                    .present = bk_element_loads_present, .make = make_loads};

/* Whether the model has the module's interaction, and the record it reads. */
static int module_present(const bk_interaction_module *im, const bk_model *m, const bk_model_record **rec)
{
    *rec = im->record ? bk_model_record_find(m, im->record) : NULL;
    return im->record ? *rec != NULL : im->present(m);
}

int bk_interactions_create(bk_system *s, FILE *err)
{
    const int n = bk_interaction_count;
    s->inter = calloc((size_t)(n > 0 ? n : 1), sizeof *s->inter);
    s->ninter = 0;
    if (!s->inter) {
        fprintf(err, "error: out of memory while building the system of '%s'\n", s->m->name);
        return -1;
    }
    /* the modules in ascending (order, place in the table): a handful, by
     * selection; modules of equal order each come, in the table's order */
    int last = -2147483647 - 1, lastk = -1;
    for (int made = 0; made < n; ++made) {
        const bk_interaction_module *next = NULL;
        int nk = -1;
        for (int k = 0; k < n; ++k) {
            const int o = bk_interaction_table[k]->order;
            if ((o > last || (o == last && k > lastk)) && (!next || o < next->order))
                next = bk_interaction_table[k], nk = k;
        }
        if (!next)
            break;
        last = next->order;
        lastk = nk;
        const bk_model_record *rec;
        if (!module_present(next, s->m, &rec))
            continue;
        void *self = NULL;
        const int r = next->make(s, rec, &self, err);
        s->inter[s->ninter++] = (bk_interaction){next->ops, self};
        if (r != 0)
            return -1;
    }
    for (int i = 0; i < s->m->nrecord; ++i) {          /* a record no module reads: another beamkit's */
        int known = 0;
        for (int k = 0; k < n; ++k)
            known |= bk_interaction_table[k]->record && strcmp(bk_interaction_table[k]->record,
                                                               s->m->records[i].name) == 0;
        if (!known) {
            fprintf(err, "error: %s: no interaction module of this solver reads it (a model file of another "
                    "beamkit version? rerun ./build.sh run)\n", s->m->records[i].where);
            return -1;
        }
    }
    return 0;
}

void bk_interactions_free(bk_system *s)
{
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops->free)
            s->inter[k].ops->free(s->inter[k].self);
    free(s->inter);
    s->inter = NULL;
    s->ninter = 0;
}

int bk_assemble_interactions(bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax)
{
    int bad = 0;
    for (int k = 0; k < s->ninter; ++k)
        bad |= s->inter[k].ops->assemble(s->inter[k].self, s, q, p, fint, Ax) != 0;
    return bad ? -1 : 0;
}

int bk_interactions_prepare(bk_system *s, const double *q)
{
    int bad = 0;
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops->prepare)
            bad |= s->inter[k].ops->prepare(s->inter[k].self, s, q) != 0;
    return bad ? -1 : 0;
}

double bk_interactions_step_limit(const bk_system *s, const double *q, const double *dx)
{
    double a = 1.0;
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops->step_limit) {
            double ak = s->inter[k].ops->step_limit(s->inter[k].self, s, q, dx);
            if (ak < a)
                a = ak;
        }
    return a;
}

void bk_interactions_accept(const bk_system *s, const double *q, const bk_path *p)
{
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops->accept)
            s->inter[k].ops->accept(s->inter[k].self, s, q, p);
}

int bk_interactions_frame(const bk_system *s, const char *dir, int frame, double t, const double *q, FILE *err)
{
    int bad = 0;
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops->frame)
            bad |= s->inter[k].ops->frame(s->inter[k].self, s, dir, frame, t, q, err) != 0;
    return bad ? -1 : 0;
}

int bk_interactions_keep_apart(const bk_system *s)
{
    int any = 0;
    for (int k = 0; k < s->ninter; ++k)
        any |= s->inter[k].ops->keeps_apart;
    return any;
}

int bk_interactions_uncounted_energy(const bk_system *s)
{
    int any = 0;
    for (int k = 0; k < s->ninter; ++k)
        any |= s->inter[k].ops->uncounted_energy;
    return any;
}

int bk_interactions_cut_predictors(const bk_system *s)
{
    int any = 0;
    for (int k = 0; k < s->ninter; ++k)
        any |= s->inter[k].ops->cut_predictors;
    return any;
}

unsigned bk_depends_on_q(const void *self, const bk_system *s)
{
    (void)self, (void)s;
    return BK_DEPENDS_Q;
}

unsigned bk_interaction_depends(const bk_system *s, int k)
{
    const bk_interaction *it = &s->inter[k];
    return it->ops->depends ? it->ops->depends(it->self, s) : BK_DEPENDS_Q | BK_DEPENDS_X;
}

int bk_interactions_load_on_path(const bk_system *s)
{
    int any = 0;
    for (int k = 0; k < s->ninter; ++k)
        any |= (bk_interaction_depends(s, k) & (BK_DEPENDS_FACTOR | BK_DEPENDS_X)) != 0;
    return any;
}

int bk_interactions_tangent_on_path(const bk_system *s)
{
    int any = 0;
    for (int k = 0; k < s->ninter; ++k) {
        const unsigned d = bk_interaction_depends(s, k);
        any |= (d & BK_DEPENDS_Q) && (d & (BK_DEPENDS_FACTOR | BK_DEPENDS_X));
    }
    return any;
}

void bk_interactions_path_rate(bk_system *s, const double *q, double lam, const double *fext, double *rl,
                               double *fol)
{
    const bk_model *m = s->m;
    /* proportional to the factor: the forces at factor 1 are the rate */
    memset(fol, 0, (size_t)m->ndof * sizeof *fol);
    const bk_path one = {.factor = 1.0, .x = lam};
    for (int k = 0; k < s->ninter; ++k)
        if ((bk_interaction_depends(s, k) & (BK_DEPENDS_FACTOR | BK_DEPENDS_X)) == BK_DEPENDS_FACTOR)
            s->inter[k].ops->assemble(s->inter[k].self, s, q, &one, fol, NULL);
    for (int i = 0; i < m->ndof; ++i)
        if (s->eq[i] >= 0)
            rl[s->eq[i]] = fol[i] - fext[i];
    for (int c = 0; c < s->ncon; ++c)
        rl[s->nfree + c] = 0.0;
    /* depending on x: central differences along the path */
    const double d = 1e-6 * fmax(1.0, fabs(lam));
    for (int k = 0; k < s->ninter; ++k) {
        if (!(bk_interaction_depends(s, k) & BK_DEPENDS_X))
            continue;
        for (int sgn = 1; sgn >= -1; sgn -= 2) {
            const bk_path p = {.factor = lam + sgn * d, .x = lam + sgn * d};
            memset(fol, 0, (size_t)m->ndof * sizeof *fol);
            s->inter[k].ops->assemble(s->inter[k].self, s, q, &p, fol, NULL);
            for (int i = 0; i < m->ndof; ++i)
                if (s->eq[i] >= 0)
                    rl[s->eq[i]] += sgn * fol[i] / (2.0 * d);
        }
    }
}

void bk_interactions_potentials(const bk_system *s, const double *q, double x, double *Vg, double *Vf)
{
    for (int k = 0; k < s->ninter; ++k)
        if (s->inter[k].ops->potential)
            s->inter[k].ops->potential(s->inter[k].self, s, q, x, Vg, Vf);
}
