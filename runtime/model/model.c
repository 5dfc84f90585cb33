/* model.c -- reading the model file written by gen/scene/model_file.py.
 *
 * The format (version BK_MODEL_VERSION, out/kernels/bk_options.h) is a stream
 * of whitespace-separated tokens: a record keyword, then its fields.  Scalar
 * records (the option records, read in options.c; the material of a `mat`
 * record) are named fields `key=value`, checked by name; arrays follow their
 * counts.  A model file of another version, or one whose fields do not match,
 * is refused with the record and field named.  The scene has been validated in
 * Python; errors here mean a damaged or mismatched model file and are reported
 * as such.  The tokens: reader.c; the records after the sensors: extras.c.
 */
#include "model/model.h"

#include <stdlib.h>
#include <string.h>

#include "model/reader.h"

static const bk_pair *find_pair(const char *sym, const bk_pair *const *avail, int navail)
{
    for (int i = 0; i < navail; ++i) {
        char buf[256];
        snprintf(buf, sizeof buf, "%s_%s_%s", avail[i]->element->name, avail[i]->material,
                 avail[i]->integration);
        if (strcmp(buf, sym) == 0)
            return avail[i];
    }
    return NULL;
}

bk_model *bk_model_read(const char *path, const bk_pair *const *avail, int navail, FILE *err)
{
    bk_reader R = {0}, *r = &R;
    r->path = path;
    r->err = err;
    if (rd_load(r) != 0)
        return NULL;
    bk_model *m = calloc(1, sizeof *m);
    if (!m) {
        free(r->buf);
        fprintf(err, "error: out of memory\n");
        return NULL;
    }
    rd_expect(r, "beamkit-model");
    {
        const char *v = rd_next(r, "format version");
        int ver = v ? atoi(v) : -1;
        if (v && ver != BK_MODEL_VERSION)
            rd_fail(r, "model file format version %s, this solver reads version %d: the file was written by "
                    "another version of beamkit (rerun ./build.sh run to rewrite it)", v, BK_MODEL_VERSION);
    }
    bk_model_read_options(r, m);
    const char *t;

    rd_expect(r, "ndof");
    m->ndof = rd_inum(r, "ndof", 1, MAXN);
    rd_expect(r, "q0");
    m->q0 = rd_xcalloc(r, (size_t)m->ndof, sizeof *m->q0);
    for (int i = 0; i < m->ndof && !r->failed; ++i)
        m->q0[i] = rd_num(r, "q0 entry");
    rd_expect(r, "qd0");
    m->qd0 = rd_xcalloc(r, (size_t)m->ndof, sizeof *m->qd0);
    for (int i = 0; i < m->ndof && !r->failed; ++i)
        m->qd0[i] = rd_num(r, "qd0 entry");

    rd_expect(r, "pairs");
    m->npair = rd_inum(r, "pairs", 1, 1000);
    m->pairs = rd_xcalloc(r, (size_t)m->npair, sizeof *m->pairs);
    for (int i = 0; i < m->npair && !r->failed; ++i) {
        rd_expect(r, "pair");
        t = rd_next(r, "kernel name");
        if (!t)
            break;
        m->pairs[i] = find_pair(t, avail, navail);
        if (!m->pairs[i])
            rd_fail(r, "kernel '%s' is not linked into this solver (rebuild with ./build.sh run)", t);
        else if (m->pairs[i]->element->nshape > BK_MAX_SHAPE || m->pairs[i]->element->ndof > BK_MAX_ELEMENT_DOF)
            rd_fail(r, "kernel '%s' is larger than this runtime supports", t);
    }

    rd_expect(r, "mats");
    m->nmat = rd_inum(r, "mats", 1, MAXN);
    m->mats = rd_xcalloc(r, (size_t)m->nmat, sizeof *m->mats);
    for (int i = 0; i < m->nmat && !r->failed; ++i) {
        bk_mat *mt = &m->mats[i];
        rd_expect(r, "mat");
        mt->rho = rd_fnum(r, "mat", "rho");
        mt->nparam = rd_fint(r, "mat", "params", 0, BK_MAT_MAXPARAM);
        for (int k = 0; k < mt->nparam && !r->failed; ++k) {
            /* name=value: the name is checked against the kernel's param_names below */
            const char *tk = rd_next(r, "material parameter");
            const char *eq = tk ? strchr(tk, '=') : NULL;
            if (!eq || eq == tk || (size_t)(eq - tk) >= sizeof mt->param_names[k]) {
                rd_fail(r, "material %d: expected a parameter 'name=value', found '%s'", i, tk ? tk : "");
                break;
            }
            memcpy(mt->param_names[k], tk, (size_t)(eq - tk));
            mt->param_names[k][eq - tk] = '\0';
            mt->params[k] = rd_parse_num(r, "material parameter", eq + 1);
        }
        mt->nvisc = rd_fint(r, "mat", "visc", 0, BK_MAT_MAXPARAM);
        for (int k = 0; k < mt->nvisc; ++k)
            mt->visc[k] = rd_num(r, "viscous parameter");
    }

    rd_expect(r, "geoms");
    m->ngeom = rd_inum(r, "geoms", 1, MAXN);
    m->geoms = rd_xcalloc(r, (size_t)m->ngeom, sizeof *m->geoms);
    m->geom_pair = rd_xcalloc(r, (size_t)m->ngeom, sizeof *m->geom_pair);
    m->geom_elem = rd_xcalloc(r, (size_t)m->ngeom, sizeof *m->geom_elem);
    m->tabs = rd_xcalloc(r, (size_t)m->ngeom, sizeof *m->tabs);
    for (int i = 0; i < m->ngeom && !r->failed; ++i) {
        rd_expect(r, "geom");
        m->geom_pair[i] = rd_inum(r, "geometry kernel", 0, m->npair - 1);
        m->geom_elem[i] = rd_inum(r, "geometry element", 0, MAXN);
        for (int k = 0; k < BK_NGEOM; ++k)
            m->geoms[i][k] = rd_num(r, "geometry");
    }

    rd_expect(r, "elements");
    m->nelem = rd_inum(r, "elements", 1, MAXN);
    m->elems = rd_xcalloc(r, (size_t)m->nelem, sizeof *m->elems);
    for (int i = 0; i < m->nelem && !r->failed; ++i) {
        bk_elem *e = &m->elems[i];
        rd_expect(r, "element");
        e->pair = rd_inum(r, "element kernel", 0, m->npair - 1);
        e->geom = rd_inum(r, "element geometry", 0, m->ngeom - 1);
        e->mat = rd_inum(r, "element material", 0, m->nmat - 1);
        int nd = rd_inum(r, "element DOF count", 1, 10000);
        if (r->failed)
            break;
        const bk_pair *p = m->pairs[e->pair];
        if (nd != p->element->ndof)
            rd_fail(r, "element %d: %d DOFs given, kernel %s has %d", i, nd, p->element->name, p->element->ndof);
        if (m->mats[e->mat].nparam != p->nparam)
            rd_fail(r, "element %d: material has %d parameters, kernel %s_%s expects %d", i,
                 m->mats[e->mat].nparam, p->element->name, p->material, p->nparam);
        for (int k = 0; k < p->nparam && !r->failed && k < m->mats[e->mat].nparam; ++k)
            if (strcmp(m->mats[e->mat].param_names[k], p->param_names[k]) != 0)
                rd_fail(r, "element %d: material parameter %d is '%s', kernel %s_%s expects '%s'", i, k + 1,
                     m->mats[e->mat].param_names[k], p->element->name, p->material, p->param_names[k]);
        if (m->mats[e->mat].nvisc > 0 && p->viscous && m->mats[e->mat].nvisc != p->nvisc)
            rd_fail(r, "element %d: %d viscous parameters given, kernel %s_%s expects %d", i,
                 m->mats[e->mat].nvisc, p->element->name, p->material, p->nvisc);
        e->dofs = rd_xcalloc(r, (size_t)nd, sizeof *e->dofs);
        for (int k = 0; k < nd && !r->failed; ++k)
            e->dofs[k] = rd_inum(r, "element DOF", 0, m->ndof - 1);
    }

    /* Tables: each from the reference coordinates of one of its elements. */
    for (int i = 0; i < m->ngeom && !r->failed; ++i) {
        int e = m->geom_elem[i];
        if (e >= m->nelem || m->elems[e].pair != m->geom_pair[i]) {
            rd_fail(r, "geometry %d: element %d does not use its kernel", i, e);
            break;
        }
        const bk_pair *p = m->pairs[m->geom_pair[i]];
        double *q0e = rd_xcalloc(r, (size_t)p->element->ndof, sizeof *q0e);
        m->tabs[i] = rd_xcalloc(r, (size_t)(p->ntab ? p->ntab : 1), sizeof(double));
        if (q0e && m->tabs[i]) {
            for (int k = 0; k < p->element->ndof; ++k)
                q0e[k] = m->q0[m->elems[e].dofs[k]];
            p->tabulate(m->geoms[i], q0e, m->tabs[i]);
        }
        free(q0e);
    }

    rd_expect(r, "fixed");
    m->nfixed = rd_inum(r, "fixed", 0, MAXN);
    m->fixed = rd_xcalloc(r, (size_t)m->nfixed, sizeof *m->fixed);
    for (int i = 0; i < m->nfixed && !r->failed; ++i)
        m->fixed[i] = rd_inum(r, "fixed DOF", 0, m->ndof - 1);

    rd_expect(r, "lincons");
    m->nlincon = rd_inum(r, "lincons", 0, MAXN);
    m->lincons = rd_xcalloc(r, (size_t)m->nlincon, sizeof *m->lincons);
    for (int i = 0; i < m->nlincon && !r->failed; ++i) {
        bk_lincon *c = &m->lincons[i];
        rd_expect(r, "lincon");
        c->nterm = rd_inum(r, "constraint terms", 1, 10000);
        c->dof = rd_xcalloc(r, (size_t)c->nterm, sizeof *c->dof);
        c->c0 = rd_xcalloc(r, (size_t)c->nterm, sizeof *c->c0);
        c->cc = rd_xcalloc(r, (size_t)c->nterm, sizeof *c->cc);
        c->cs = rd_xcalloc(r, (size_t)c->nterm, sizeof *c->cs);
        for (int k = 0; k < c->nterm && !r->failed; ++k) {
            c->dof[k] = rd_inum(r, "constraint DOF", 0, m->ndof - 1);
            c->c0[k] = rd_num(r, "constraint coefficient");
            c->cc[k] = rd_num(r, "constraint coefficient");
            c->cs[k] = rd_num(r, "constraint coefficient");
        }
        c->r0 = rd_num(r, "constraint right-hand side");
        c->rc = rd_num(r, "constraint right-hand side");
        c->rs = rd_num(r, "constraint right-hand side");
        c->kappa = rd_num(r, "constraint angle factor");
        c->rate = rd_num(r, "constraint angle rate");
        c->amp = rd_num(r, "constraint angle amplitude");
        c->freq = rd_num(r, "constraint angle frequency");
        c->angle = rd_num(r, "constraint angle");
        c->ampl = NULL;                       /* resolved with the amplitudes */
        c->ampid = (int)rd_num(r, "constraint angle amplitude index");
        c->ru = rd_num(r, "constraint motion");
        c->uampid = (int)rd_num(r, "constraint motion amplitude index");
        c->uampl = NULL;
    }

    rd_expect(r, "nlcons");
    m->nnlcon = rd_inum(r, "nlcons", 0, MAXN);
    m->nlcons = rd_xcalloc(r, (size_t)m->nnlcon, sizeof *m->nlcons);
    for (int i = 0; i < m->nnlcon && !r->failed; ++i) {
        bk_nlcon *c = &m->nlcons[i];
        rd_expect(r, "nlcon");
        t = rd_next(r, "joint type");
        if (t && strlen(t) >= sizeof c->type)
            rd_fail(r, "joint type '%s' too long", t);
        else if (t)
            memcpy(c->type, t, strlen(t) + 1);
        for (int k = 0; k < BK_JOINT_NX; ++k)
            c->dof[k] = rd_inum(r, "joint DOF", -1, m->ndof - 1);
        for (int k = 0; k < BK_JOINT_NX; ++k)
            c->x0[k] = rd_num(r, "joint coordinate");
        for (int k = 0; k < BK_JOINT_NGEOM; ++k)
            c->prm[k] = rd_num(r, "joint parameter");
        c->rate = rd_num(r, "joint drive rate");
        c->amp = rd_num(r, "joint drive amplitude");
        c->freq = rd_num(r, "joint drive frequency");
        c->scale = rd_num(r, "joint drive scale");
        c->dampid = rd_inum(r, "joint drive amplitude index", -1, MAXN);
        c->dampl = NULL;                      /* resolved with the amplitudes */
    }

    rd_expect(r, "forces");
    m->nforce = rd_inum(r, "forces", 0, MAXN);
    m->forces = rd_xcalloc(r, (size_t)m->nforce, sizeof *m->forces);
    for (int i = 0; i < m->nforce && !r->failed; ++i) {
        bk_force_load *f = &m->forces[i];
        rd_expect(r, "force");
        f->elem = rd_inum(r, "force element", 0, m->nelem - 1);
        f->xi = rd_num(r, "force xi");
        f->y = rd_num(r, "force y");
        f->z = rd_num(r, "force z");
        f->section = rd_inum(r, "force distribution", 0, 1);
        for (int k = 0; k < 3; ++k)
            f->value[k] = rd_num(r, "force value");
        f->amp = rd_inum(r, "force amplitude", -1, MAXN);
        f->follower = rd_inum(r, "force follower flag", 0, 1);
    }

    rd_expect(r, "moments");
    m->nmoment = rd_inum(r, "moments", 0, MAXN);
    m->moments = rd_xcalloc(r, (size_t)m->nmoment, sizeof *m->moments);
    for (int i = 0; i < m->nmoment && !r->failed; ++i) {
        bk_moment_load *mo = &m->moments[i];
        rd_expect(r, "moment");
        mo->elem = rd_inum(r, "moment element", 0, m->nelem - 1);
        mo->xi = rd_num(r, "moment xi");
        for (int k = 0; k < 3; ++k)
            mo->value[k] = rd_num(r, "moment value");
        mo->amp = rd_inum(r, "moment amplitude", -1, MAXN);
        mo->follower = rd_inum(r, "moment follower flag", 0, 1);
    }

    rd_expect(r, "gravity");
    m->has_gravity = rd_inum(r, "gravity flag", 0, 1);
    m->gravity_ampid = -1;
    if (m->has_gravity) {
        for (int k = 0; k < 3; ++k)
            m->gravity[k] = rd_num(r, "gravity");
        m->gravity_ampid = rd_inum(r, "gravity amplitude", -1, MAXN);
    }

    rd_expect(r, "sensors");
    m->nsensor = rd_inum(r, "sensors", 0, MAXN);
    m->sensors = rd_xcalloc(r, (size_t)m->nsensor, sizeof *m->sensors);
    for (int i = 0; i < m->nsensor && !r->failed; ++i) {
        bk_sensor *s = &m->sensors[i];
        rd_expect(r, "sensor");
        t = rd_next(r, "sensor name");
        if (t && strlen(t) >= sizeof s->name)
            rd_fail(r, "sensor name longer than %zu characters", sizeof s->name - 1);
        else if (t)
            memcpy(s->name, t, strlen(t) + 1);
        s->elem = rd_inum(r, "sensor element", 0, m->nelem - 1);
        s->xi = rd_num(r, "sensor xi");
        for (int k = 0; k < 3; ++k)
            s->off[k] = rd_num(r, "sensor offset");
    }
    bk_model_read_extras(r, m);
    bk_model_read_point_masses(r, m);
    bk_model_read_records(r, m);
    bk_model_read_scene_warnings(r, m);
    rd_expect(r, "end");
    free(r->buf);
    if (r->failed) {
        bk_model_free(m);
        return NULL;
    }
    return m;
}

void bk_model_free(bk_model *m)
{
    if (!m)
        return;
    bk_model_records_free(m);
    for (int i = 0; i < m->nscene_warning; ++i)
        free(m->scene_warnings[i]);
    free(m->scene_warnings);
    free(m->pmass);
    free(m->q0);
    free(m->qd0);
    free(m->pairs);
    free(m->geoms);
    free(m->geom_pair);
    free(m->geom_elem);
    if (m->tabs)
        for (int i = 0; i < m->ngeom; ++i)
            free(m->tabs[i]);
    free(m->tabs);
    free(m->mats);
    if (m->elems)
        for (int i = 0; i < m->nelem; ++i)
            free(m->elems[i].dofs);
    free(m->elems);
    free(m->fixed);
    if (m->lincons)
        for (int i = 0; i < m->nlincon; ++i) {
            free(m->lincons[i].dof);
            free(m->lincons[i].c0);
            free(m->lincons[i].cc);
            free(m->lincons[i].cs);
        }
    free(m->lincons);
    free(m->nlcons);
    free(m->forces);
    free(m->moments);
    free(m->sensors);
    if (m->amps)
        for (int i = 0; i < m->namp; ++i)
            free(m->amps[i].par);
    free(m->amps);
    free(m->dloads);
    if (m->tendons)
        for (int i = 0; i < m->ntendon; ++i)
            free(m->tendons[i].pieces);
    free(m->tendons);
    if (m->reactions)
        for (int i = 0; i < m->nreaction; ++i) {
            free(m->reactions[i].fixed);
            free(m->reactions[i].lin);
            free(m->reactions[i].side);
        }
    free(m->reactions);
    free(m->sections);
    free(m);
}

int bk_model_bind_joints(bk_model *m, const bk_joint_kind *const *kinds, int nkinds, FILE *err)
{
    for (int i = 0; i < m->nnlcon; ++i) {
        bk_nlcon *c = &m->nlcons[i];
        c->kind = NULL;
        for (int k = 0; k < nkinds && !c->kind; ++k)
            if (strcmp(kinds[k]->name, c->type) == 0)
                c->kind = kinds[k];
        if (!c->kind) {
            fprintf(err, "error: %s: joint type '%s' has no kernel linked into this solver\n", m->name, c->type);
            return -1;
        }
    }
    return 0;
}
