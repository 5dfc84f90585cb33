/* extras.c -- the model file's records after the sensors: amplitudes,
 * distributed loads, tendons, reactions and the beams' elements (for
 * sections.csv), checked against the elements and kernels read before; and
 * the scene reader's warnings, the file's last records. */
#include "model/reader.h"

#include <string.h>

/* A follower load turns with the section frame of its element's kernel. */
static void need_section_frame(bk_reader *r, const bk_model *m, const char *what, int i, int e)
{
    const bk_element *et = m->pairs[m->elems[e].pair]->element;
    if (!et->section_frame)
        rd_fail(r, "%s %d: follower load on element %d (%s): expected an element with a section frame", what, i, e,
             et->name);
}

/* Amplitudes, distributed loads, tendons, reactions and the beams' elements
 * (for sections.csv), after the sensors. */
void bk_model_read_extras(bk_reader *r, bk_model *m)
{
    rd_expect(r, "amplitudes");
    m->namp = rd_inum(r, "amplitudes", 0, MAXN);
    m->amps = rd_xcalloc(r, (size_t)m->namp, sizeof *m->amps);
    for (int i = 0; i < m->namp && !r->failed; ++i) {
        bk_amplitude *a = &m->amps[i];
        rd_expect(r, "amplitude");
        const char *t = rd_next(r, "amplitude type");
        if (!t)
            break;
        static const char *names[] = {"ramp", "step", "sine", "table", "cycloidal", "quintic", "spline"};
        for (int k = 0; k < 7; ++k)
            if (strcmp(t, names[k]) == 0)
                a->type = BK_AMP_RAMP + k;
        if (!a->type)
            rd_fail(r, "amplitude %d: unknown type '%s' (expected ramp, step, sine, table, cycloidal, quintic, "
                    "spline)", i, t);
        a->npar = rd_inum(r, "amplitude parameter count", 1, MAXN);
        static const int need[] = {2, 1, 4, 0, 2, 2, 0};
        const int stride = a->type == BK_AMP_TABLE ? 2 : a->type == BK_AMP_SPLINE ? 3 : 0;
        if (!r->failed && a->type && (stride ? a->npar % stride != 0 : a->npar != need[a->type - 1]))
            rd_fail(r, "amplitude %d: %d parameters for type '%s'", i, a->npar, t);
        a->par = rd_xcalloc(r, (size_t)a->npar, sizeof *a->par);
        for (int k = 0; k < a->npar && !r->failed; ++k)
            a->par[k] = rd_num(r, "amplitude parameter");
        for (int k = stride; stride && k < a->npar && !r->failed; k += stride)
            if (!(a->par[k] > a->par[k - stride]))
                rd_fail(r, "amplitude %d: table points out of time order", i);
        if ((a->type == BK_AMP_CYCLOID || a->type == BK_AMP_QUINTIC) && !r->failed && !(a->par[1] > a->par[0]))
            rd_fail(r, "amplitude %d: expected t1 > t0", i);
    }
    for (int i = 0; i < m->nlincon && !r->failed; ++i) {
        int ai = m->lincons[i].ampid;
        if (ai >= m->namp)
            rd_fail(r, "constraint %d: amplitude %d of %d", i, ai, m->namp);
        m->lincons[i].ampl = ai >= 0 && ai < m->namp ? &m->amps[ai] : NULL;
        int ui = m->lincons[i].uampid;
        if (ui >= m->namp)
            rd_fail(r, "constraint %d: motion amplitude %d of %d", i, ui, m->namp);
        m->lincons[i].uampl = ui >= 0 && ui < m->namp ? &m->amps[ui] : NULL;
    }
    for (int i = 0; i < m->nnlcon && !r->failed; ++i) {
        int ai = m->nlcons[i].dampid;
        if (ai >= m->namp)
            rd_fail(r, "joint %d: drive amplitude %d of %d", i, ai, m->namp);
        m->nlcons[i].dampl = ai >= 0 && ai < m->namp ? &m->amps[ai] : NULL;
    }
    if (m->gravity_ampid >= m->namp)
        rd_fail(r, "gravity: amplitude %d of %d", m->gravity_ampid, m->namp);
    m->gravity_amp = m->gravity_ampid >= 0 && m->gravity_ampid < m->namp ? &m->amps[m->gravity_ampid] : NULL;
    for (int i = 0; i < m->nforce && !r->failed; ++i)
        if (m->forces[i].amp >= m->namp)
            rd_fail(r, "force %d: amplitude %d of %d", i, m->forces[i].amp, m->namp);
    for (int i = 0; i < m->nmoment && !r->failed; ++i)
        if (m->moments[i].amp >= m->namp)
            rd_fail(r, "moment %d: amplitude %d of %d", i, m->moments[i].amp, m->namp);
    for (int i = 0; i < m->nforce && !r->failed; ++i)
        if (m->forces[i].follower)
            need_section_frame(r, m, "force", i, m->forces[i].elem);
    for (int i = 0; i < m->nmoment && !r->failed; ++i)
        if (m->moments[i].follower)
            need_section_frame(r, m, "moment", i, m->moments[i].elem);

    rd_expect(r, "dloads");
    m->ndload = rd_inum(r, "dloads", 0, MAXN);
    m->dloads = rd_xcalloc(r, (size_t)m->ndload, sizeof *m->dloads);
    for (int i = 0; i < m->ndload && !r->failed; ++i) {
        bk_dist_load *d = &m->dloads[i];
        rd_expect(r, "dload");
        d->elem = rd_inum(r, "distributed load element", 0, m->nelem - 1);
        d->xi0 = rd_num(r, "distributed load xi0");
        d->xi1 = rd_num(r, "distributed load xi1");
        d->follower = rd_inum(r, "distributed load follower flag", 0, 1);
        d->amp = rd_inum(r, "distributed load amplitude", -1, m->namp - 1);
        for (int k = 0; k < 3; ++k)
            d->value[k] = rd_num(r, "distributed load value");
        if (!r->failed && d->follower)
            need_section_frame(r, m, "distributed load", i, d->elem);
    }

    rd_expect(r, "tendons");
    m->ntendon = rd_inum(r, "tendons", 0, MAXN);
    m->tendons = rd_xcalloc(r, (size_t)m->ntendon, sizeof *m->tendons);
    for (int i = 0; i < m->ntendon && !r->failed; ++i) {
        bk_tendon *t = &m->tendons[i];
        rd_expect(r, "tendon");
        t->amp = rd_inum(r, "tendon amplitude", -1, m->namp - 1);
        t->tension = rd_num(r, "tendon tension");
        t->npiece = rd_inum(r, "tendon pieces", 1, MAXN);
        t->pieces = rd_xcalloc(r, (size_t)t->npiece, sizeof *t->pieces);
        for (int k = 0; k < t->npiece && !r->failed; ++k) {
            bk_tendon_piece *p = &t->pieces[k];
            rd_expect(r, "piece");
            p->elem = rd_inum(r, "tendon element", 0, m->nelem - 1);
            p->xi0 = rd_num(r, "tendon xi0");
            p->xi1 = rd_num(r, "tendon xi1");
            p->dy = rd_num(r, "tendon dy");
            p->dz = rd_num(r, "tendon dz");
            const bk_element *et = r->failed ? NULL : m->pairs[m->elems[p->elem].pair]->element;
            if (et && !(et->caps & BK_CAP_SECTION_FIELD) && !et->section_line)
                rd_fail(r, "tendon %d: element %d (%s) neither interpolates across its section nor has a "
                        "section_line()", i, p->elem, et->name);
        }
    }

    rd_expect(r, "reactions");
    m->nreaction = rd_inum(r, "reactions", 0, MAXN);
    m->reactions = rd_xcalloc(r, (size_t)m->nreaction, sizeof *m->reactions);
    for (int i = 0; i < m->nreaction && !r->failed; ++i) {
        bk_reaction *c = &m->reactions[i];
        rd_expect(r, "reaction");
        c->index = rd_inum(r, "reaction index", 0, MAXN);
        rd_copy_token(r, c->type, sizeof c->type, "reaction type");
        rd_copy_token(r, c->name, sizeof c->name, "reaction name");
        rd_copy_token(r, c->at, sizeof c->at, "reaction point");
        c->elem = rd_inum(r, "reaction element", 0, m->nelem - 1);
        c->xi = rd_num(r, "reaction xi");
        c->nfixed = rd_inum(r, "reaction fixed DOFs", 0, MAXN);
        c->fixed = rd_xcalloc(r, (size_t)c->nfixed, sizeof *c->fixed);
        for (int k = 0; k < c->nfixed && !r->failed; ++k)
            c->fixed[k] = rd_inum(r, "reaction fixed DOF", 0, m->ndof - 1);
        c->nlin = rd_inum(r, "reaction constraints", 0, MAXN);
        c->lin = rd_xcalloc(r, (size_t)c->nlin, sizeof *c->lin);
        for (int k = 0; k < c->nlin && !r->failed; ++k)
            c->lin[k] = rd_inum(r, "reaction constraint", 0, m->nlincon - 1);
        c->nside = rd_inum(r, "reaction side DOFs", 0, MAXN);
        c->side = rd_xcalloc(r, (size_t)c->nside, sizeof *c->side);
        for (int k = 0; k < c->nside && !r->failed; ++k)
            c->side[k] = rd_inum(r, "reaction side DOF", 0, m->ndof - 1);
        c->nlcon = rd_inum(r, "reaction joint", -1, m->nnlcon - 1);
        c->njoint = rd_inum(r, "reaction joints", 0, c->nlcon < 0 ? 0 : m->nnlcon - c->nlcon);
    }

    rd_expect(r, "sections");
    m->nsection = rd_inum(r, "sections", 0, MAXN);
    m->sections = rd_xcalloc(r, (size_t)m->nsection, sizeof *m->sections);
    for (int i = 0; i < m->nsection && !r->failed; ++i) {
        bk_section_rec *c = &m->sections[i];
        rd_expect(r, "section");
        rd_copy_token(r, c->beam, sizeof c->beam, "section beam name");
        c->elem = rd_inum(r, "section element", 0, m->nelem - 1);
        c->s0 = rd_num(r, "section start");
        c->s1 = rd_num(r, "section end");
        c->r = rd_num(r, "section half-height");
        if (!r->failed && !(c->r >= 0.0))
            rd_fail(r, "section %d: negative half-height %g", i, c->r);
        c->group = rd_inum(r, "section group", 0, MAXN);
    }
}

/* The scene reader's warnings (`warnings N`, then N lines `warning TEXT`):
 * summary.json lists them first (output.c), as the front ends did. */
void bk_model_read_scene_warnings(bk_reader *r, bk_model *m)
{
    rd_expect(r, "warnings");
    int n = rd_inum(r, "warnings", 0, MAXN);
    m->scene_warnings = rd_xcalloc(r, (size_t)n, sizeof *m->scene_warnings);
    for (int i = 0; i < n && !r->failed; ++i) {
        rd_expect(r, "warning");
        char *w = rd_line(r);
        if (w)
            m->scene_warnings[m->nscene_warning++] = w;
    }
}
