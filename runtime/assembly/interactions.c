/* interactions.c -- the table of interactions and the loops over them (see
 * interaction.h). */
#include "assembly/interaction.h"

#include <stdlib.h>

#include "assembly/actuators.h"
#include "assembly/body_forces.h"
#include "assembly/contact_force.h"
#include "assembly/beam_contact.h"
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

static const bk_interaction_ops follower_ops = {.name = "moments", .assemble = follower_assemble};

static int has_moments(const bk_model *m)
{
    return m->nmoment > 0;
}

static int make_follower(bk_system *s, void **self)
{
    (void)s;
    *self = NULL;                    /* no data of its own */
    return 0;
}

/* ---- loads with amplitudes, follower and distributed loads, tendons (loads.c), at p->x ---- */

static int loads_assemble(void *self, bk_system *s, const double *q, const bk_path *p, double *fint, double *Ax)
{
    bk_assemble_loads_in(s, self, q, p->x, fint, Ax);
    return 0;
}

static void loads_free(void *self)
{
    bk_loads_scratch_free(self);
}

static const bk_interaction_ops loads_ops = {.name = "loads", .assemble = loads_assemble, .free = loads_free};

static int make_loads(bk_system *s, void **self)
{
    *self = bk_loads_scratch_new(s->maxdof);     /* assembly without allocation */
    return *self ? 0 : -1;
}

/* The table: what each interaction is, whether the model has it, and how its
 * data is made (0, or -1 when out of memory).  The order is the order of
 * every sum. */
static const struct {
    const bk_interaction_ops *ops;
    int (*present)(const bk_model *m);
    int (*make)(bk_system *s, void **self);
} table[] = {
    {&follower_ops, has_moments, make_follower},
    {&loads_ops, bk_loads_present, make_loads},
    {&bk_contact_ops, bk_contact_present, bk_contact_make},
    {&bk_beam_contact_ops, bk_beam_contact_present, bk_beam_contact_make},
    {&bk_actuator_ops, bk_actuators_present, bk_actuators_make},
    {&bk_body_force_ops, bk_body_forces_present, bk_body_forces_make},
};

int bk_interactions_create(bk_system *s)
{
    const int n = (int)(sizeof table / sizeof table[0]);
    s->inter = calloc((size_t)n, sizeof *s->inter);
    s->ninter = 0;
    if (!s->inter)
        return -1;
    for (int k = 0; k < n; ++k) {
        if (!table[k].present(s->m))
            continue;
        void *self;
        if (table[k].make(s, &self) != 0)
            return -1;
        s->inter[s->ninter++] = (bk_interaction){table[k].ops, self};
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
