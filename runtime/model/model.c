/* model.c -- reading the model file written by gen/scene/model_file.py.
 *
 * The format (version BK_MODEL_VERSION) is a stream of whitespace-separated
 * tokens: a record keyword, then its fields.  Scalar records (scene, static,
 * dynamic, output, modal; the material of a `mat` record) are named fields
 * `key=value` in the order of gen/scene/model_file.py RECORDS, checked here by
 * name; arrays follow their counts.  A model file of another version, or one
 * whose fields do not match, is refused with the record and field named.  The
 * scene has been validated in Python; errors here mean a damaged or mismatched
 * model file and are reported as such.
 */
#include "model/model.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

typedef struct reader {
    char *buf;               /* owned: the whole file, NUL-terminated */
    size_t len, pos;         /* its length; where the next token starts */
    const char *path;
    FILE *err;
    int failed;
    char tok[256];
} reader;

static void fail(reader *r, const char *fmt, ...)
{
    if (r->failed)
        return;
    r->failed = 1;
    va_list ap;
    va_start(ap, fmt);
    fprintf(r->err, "error: %s: ", r->path);
    vfprintf(r->err, fmt, ap);
    fprintf(r->err, "\n");
    va_end(ap);
}

static int is_space(char c)
{
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* The next whitespace-separated token (at most 255 bytes, as "%255s" reads:
 * a longer one goes on in the next token), or NULL at the end.  (A model file
 * has thousands of tokens: reading each with fscanf, and making each one's
 * error-message name whether or not it was needed, were a tenth of a small
 * model's run.) */
static const char *next_tok(reader *r)
{
    if (r->failed)
        return NULL;
    const char *p = r->buf + r->pos, *e = r->buf + r->len;
    while (p < e && is_space(*p))
        ++p;
    if (p == e)
        return NULL;
    size_t n = 0;
    while (p + n < e && n < sizeof r->tok - 1 && !is_space(p[n]))
        ++n;
    memcpy(r->tok, p, n);
    r->tok[n] = '\0';
    r->pos = (size_t)(p + n - r->buf);
    return r->tok;
}

/* next_tok, and an error naming `what` at the end of the file. */
static const char *next(reader *r, const char *what)
{
    const char *t = next_tok(r);
    if (!t && !r->failed)
        fail(r, "model file ends early: expected %s", what);
    return t;
}

static void expect(reader *r, const char *kw)
{
    const char *t = next(r, kw);
    if (t && strcmp(t, kw) != 0)
        fail(r, "expected keyword '%s', found '%s'", kw, t);
}

/* The value of the named field `rec.key` (token "key=value"). */
static const char *field(reader *r, const char *rec, const char *key)
{
    const char *t = next_tok(r);
    if (!t) {
        if (!r->failed)
            fail(r, "model file ends early: expected field %s.%s", rec, key);
        return NULL;
    }
    size_t n = strlen(key);
    if (strncmp(t, key, n) != 0 || t[n] != '=') {
        fail(r, "record '%s': expected field '%s=...', found '%s' (a model file of another beamkit version? "
                "rerun ./build.sh run)", rec, key, t);
        return NULL;
    }
    return t + n + 1;
}

/* The name of a value in an error message: `what`, or "rec.key" of a named
 * field (made only for the message). */
static const char *value_name(char *buf, size_t n, const char *what, const char *rec, const char *key)
{
    if (!rec)
        return what;
    snprintf(buf, n, "%s.%s", rec, key);
    return buf;
}

static double parse_num_of(reader *r, const char *t, const char *what, const char *rec, const char *key)
{
    if (!t)
        return 0.0;
    char *end;
    errno = 0;
    double v = strtod(t, &end);
    if (*end != '\0' || errno == ERANGE || !isfinite(v)) {
        char name[128];
        fail(r, "%s: expected a finite number, found '%s'", value_name(name, sizeof name, what, rec, key), t);
        return 0.0;
    }
    return v;
}

static int parse_int_of(reader *r, const char *t, const char *what, const char *rec, const char *key, int lo, int hi)
{
    if (!t)
        return lo;
    char *end;
    errno = 0;
    long v = strtol(t, &end, 10);
    if (*end != '\0' || errno == ERANGE || v < lo || v > hi) {
        char name[128];
        fail(r, "%s: expected an integer in [%d, %d], found '%s'", value_name(name, sizeof name, what, rec, key),
             lo, hi, t);
        return lo;
    }
    return (int)v;
}

static double parse_num(reader *r, const char *what, const char *t)
{
    return parse_num_of(r, t, what, NULL, NULL);
}

static double fnum(reader *r, const char *rec, const char *key)
{
    return parse_num_of(r, field(r, rec, key), NULL, rec, key);
}

static int fint(reader *r, const char *rec, const char *key, int lo, int hi)
{
    return parse_int_of(r, field(r, rec, key), NULL, rec, key, lo, hi);
}

static double num(reader *r, const char *what)
{
    return parse_num(r, what, next(r, what));
}

static int inum(reader *r, const char *what, int lo, int hi)
{
    return parse_int_of(r, next(r, what), what, NULL, NULL, lo, hi);
}

static void *xcalloc(reader *r, size_t n, size_t size)
{
    if (r->failed)
        return NULL;
    void *p = calloc(n ? n : 1, size);
    if (!p)
        fail(r, "out of memory (%zu x %zu bytes)", n, size);
    return p;
}

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

#define MAXN 100000000

static void copy_token(reader *r, char *dst, size_t n, const char *what)
{
    const char *t = next(r, what);
    if (t && strlen(t) >= n)
        fail(r, "%s longer than %zu characters", what, n - 1);
    else if (t)
        memcpy(dst, t, strlen(t) + 1);
}

/* A follower load turns with the section frame of its element's kernel. */
static void need_section_frame(reader *r, const bk_model *m, const char *what, int i, int e)
{
    const bk_element *et = m->pairs[m->elems[e].pair]->element;
    if (!et->section_frame)
        fail(r, "%s %d: follower load on element %d (%s): expected an element with a section frame", what, i, e,
             et->name);
}

/* Amplitudes, distributed loads, tendons, reactions and the beams' elements
 * (for sections.csv), after the sensors. */
static void read_extras(reader *r, bk_model *m)
{
    expect(r, "amplitudes");
    m->namp = inum(r, "amplitudes", 0, MAXN);
    m->amps = xcalloc(r, (size_t)m->namp, sizeof *m->amps);
    for (int i = 0; i < m->namp && !r->failed; ++i) {
        bk_amplitude *a = &m->amps[i];
        expect(r, "amplitude");
        const char *t = next(r, "amplitude type");
        if (!t)
            break;
        static const char *names[] = {"ramp", "step", "sine", "table"};
        for (int k = 0; k < 4; ++k)
            if (strcmp(t, names[k]) == 0)
                a->type = BK_AMP_RAMP + k;
        if (!a->type)
            fail(r, "amplitude %d: unknown type '%s' (expected ramp, step, sine, table)", i, t);
        a->npar = inum(r, "amplitude parameter count", 1, MAXN);
        static const int need[] = {2, 1, 4, 0};
        if (!r->failed && a->type && (a->type == BK_AMP_TABLE ? a->npar % 2 != 0 : a->npar != need[a->type - 1]))
            fail(r, "amplitude %d: %d parameters for type '%s'", i, a->npar, t);
        a->par = xcalloc(r, (size_t)a->npar, sizeof *a->par);
        for (int k = 0; k < a->npar && !r->failed; ++k)
            a->par[k] = num(r, "amplitude parameter");
        for (int k = 2; a->type == BK_AMP_TABLE && k < a->npar && !r->failed; k += 2)
            if (!(a->par[k] > a->par[k - 2]))
                fail(r, "amplitude %d: table points out of time order", i);
    }
    for (int i = 0; i < m->nlincon && !r->failed; ++i) {
        int ai = m->lincons[i].ampid;
        if (ai >= m->namp)
            fail(r, "constraint %d: amplitude %d of %d", i, ai, m->namp);
        m->lincons[i].ampl = ai >= 0 && ai < m->namp ? &m->amps[ai] : NULL;
    }
    if (m->gravity_ampid >= m->namp)
        fail(r, "gravity: amplitude %d of %d", m->gravity_ampid, m->namp);
    m->gravity_amp = m->gravity_ampid >= 0 && m->gravity_ampid < m->namp ? &m->amps[m->gravity_ampid] : NULL;
    for (int i = 0; i < m->nforce && !r->failed; ++i)
        if (m->forces[i].amp >= m->namp)
            fail(r, "force %d: amplitude %d of %d", i, m->forces[i].amp, m->namp);
    for (int i = 0; i < m->nmoment && !r->failed; ++i)
        if (m->moments[i].amp >= m->namp)
            fail(r, "moment %d: amplitude %d of %d", i, m->moments[i].amp, m->namp);
    for (int i = 0; i < m->nforce && !r->failed; ++i)
        if (m->forces[i].follower)
            need_section_frame(r, m, "force", i, m->forces[i].elem);
    for (int i = 0; i < m->nmoment && !r->failed; ++i)
        if (m->moments[i].follower)
            need_section_frame(r, m, "moment", i, m->moments[i].elem);

    expect(r, "dloads");
    m->ndload = inum(r, "dloads", 0, MAXN);
    m->dloads = xcalloc(r, (size_t)m->ndload, sizeof *m->dloads);
    for (int i = 0; i < m->ndload && !r->failed; ++i) {
        bk_dist_load *d = &m->dloads[i];
        expect(r, "dload");
        d->elem = inum(r, "distributed load element", 0, m->nelem - 1);
        d->xi0 = num(r, "distributed load xi0");
        d->xi1 = num(r, "distributed load xi1");
        d->follower = inum(r, "distributed load follower flag", 0, 1);
        d->amp = inum(r, "distributed load amplitude", -1, m->namp - 1);
        for (int k = 0; k < 3; ++k)
            d->value[k] = num(r, "distributed load value");
        if (!r->failed && d->follower)
            need_section_frame(r, m, "distributed load", i, d->elem);
    }

    expect(r, "tendons");
    m->ntendon = inum(r, "tendons", 0, MAXN);
    m->tendons = xcalloc(r, (size_t)m->ntendon, sizeof *m->tendons);
    for (int i = 0; i < m->ntendon && !r->failed; ++i) {
        bk_tendon *t = &m->tendons[i];
        expect(r, "tendon");
        t->amp = inum(r, "tendon amplitude", -1, m->namp - 1);
        t->tension = num(r, "tendon tension");
        t->npiece = inum(r, "tendon pieces", 1, MAXN);
        t->pieces = xcalloc(r, (size_t)t->npiece, sizeof *t->pieces);
        for (int k = 0; k < t->npiece && !r->failed; ++k) {
            bk_tendon_piece *p = &t->pieces[k];
            expect(r, "piece");
            p->elem = inum(r, "tendon element", 0, m->nelem - 1);
            p->xi0 = num(r, "tendon xi0");
            p->xi1 = num(r, "tendon xi1");
            p->dy = num(r, "tendon dy");
            p->dz = num(r, "tendon dz");
            if (!r->failed && !(m->pairs[m->elems[p->elem].pair]->element->caps & BK_CAP_SECTION_FIELD))
                fail(r, "tendon %d: element %d does not interpolate across its section", i, p->elem);
        }
    }

    expect(r, "reactions");
    m->nreaction = inum(r, "reactions", 0, MAXN);
    m->reactions = xcalloc(r, (size_t)m->nreaction, sizeof *m->reactions);
    for (int i = 0; i < m->nreaction && !r->failed; ++i) {
        bk_reaction *c = &m->reactions[i];
        expect(r, "reaction");
        c->index = inum(r, "reaction index", 0, MAXN);
        copy_token(r, c->type, sizeof c->type, "reaction type");
        copy_token(r, c->at, sizeof c->at, "reaction point");
        c->elem = inum(r, "reaction element", 0, m->nelem - 1);
        c->xi = num(r, "reaction xi");
        c->nfixed = inum(r, "reaction fixed DOFs", 0, MAXN);
        c->fixed = xcalloc(r, (size_t)c->nfixed, sizeof *c->fixed);
        for (int k = 0; k < c->nfixed && !r->failed; ++k)
            c->fixed[k] = inum(r, "reaction fixed DOF", 0, m->ndof - 1);
        c->nlin = inum(r, "reaction constraints", 0, MAXN);
        c->lin = xcalloc(r, (size_t)c->nlin, sizeof *c->lin);
        for (int k = 0; k < c->nlin && !r->failed; ++k)
            c->lin[k] = inum(r, "reaction constraint", 0, m->nlincon - 1);
        c->nside = inum(r, "reaction side DOFs", 0, MAXN);
        c->side = xcalloc(r, (size_t)c->nside, sizeof *c->side);
        for (int k = 0; k < c->nside && !r->failed; ++k)
            c->side[k] = inum(r, "reaction side DOF", 0, m->ndof - 1);
        c->nlcon = inum(r, "reaction joint", -1, m->nnlcon - 1);
    }

    expect(r, "sections");
    m->nsection = inum(r, "sections", 0, MAXN);
    m->sections = xcalloc(r, (size_t)m->nsection, sizeof *m->sections);
    for (int i = 0; i < m->nsection && !r->failed; ++i) {
        bk_section_rec *c = &m->sections[i];
        expect(r, "section");
        copy_token(r, c->beam, sizeof c->beam, "section beam name");
        c->elem = inum(r, "section element", 0, m->nelem - 1);
        c->s0 = num(r, "section start");
        c->s1 = num(r, "section end");
    }
}

bk_model *bk_model_read(const char *path, const bk_pair *const *avail, int navail, FILE *err)
{
    reader R = {0}, *r = &R;
    r->path = path;
    r->err = err;
    FILE *fp = fopen(path, "r");
    if (!fp) {
        fprintf(err, "error: %s: cannot open model file: %s\n", path, strerror(errno));
        return NULL;
    }
    /* the whole file in memory (read in pieces: its size need not be known) */
    size_t cap = 1 << 16;
    r->buf = malloc(cap);
    while (r->buf) {
        r->len += fread(r->buf + r->len, 1, cap - r->len - 1, fp);
        if (r->len < cap - 1)
            break;
        char *nb = realloc(r->buf, cap *= 2);
        if (!nb)
            free(r->buf);
        r->buf = nb;
    }
    int bad = !r->buf || ferror(fp);
    fclose(fp);
    if (bad) {
        fprintf(err, "error: %s: %s\n", path, r->buf ? "cannot read model file" : "out of memory");
        free(r->buf);
        return NULL;
    }
    r->buf[r->len] = '\0';
    bk_model *m = calloc(1, sizeof *m);
    if (!m) {
        free(r->buf);
        fprintf(err, "error: out of memory\n");
        return NULL;
    }
    expect(r, "beamkit-model");
    {
        const char *v = next(r, "format version");
        int ver = v ? atoi(v) : -1;
        if (v && ver != BK_MODEL_VERSION)
            fail(r, "model file format version %s, this solver reads version %d: the file was written by "
                    "another version of beamkit (rerun ./build.sh run to rewrite it)", v, BK_MODEL_VERSION);
    }
    expect(r, "scene");
    const char *t = field(r, "scene", "name");
    if (t && strlen(t) >= sizeof m->name)
        fail(r, "scene name longer than %zu characters", sizeof m->name - 1);
    else if (t)
        memcpy(m->name, t, strlen(t) + 1);
    t = field(r, "scene", "analysis");
    if (t && strcmp(t, "static") == 0)
        m->analysis = BK_STATIC;
    else if (t && strcmp(t, "dynamic") == 0)
        m->analysis = BK_DYNAMIC;
    else if (t && strcmp(t, "modal") == 0)
        m->analysis = BK_MODAL;
    else if (t && strcmp(t, "buckling") == 0)
        m->analysis = BK_BUCKLING;
    else if (t)
        fail(r, "analysis '%s' is not supported by this solver (expected static, dynamic, modal, buckling)", t);
    m->length_scale = fnum(r, "scene", "length_scale");
    expect(r, "static");
    m->stat.load_steps = fint(r, "static", "load_steps", 1, MAXN);
    m->stat.max_iter = fint(r, "static", "max_iterations", 1, 10000);
    m->stat.max_cutbacks = fint(r, "static", "max_cutbacks", 0, 60);
    m->stat.cycles = fint(r, "static", "cycles", 0, 1000);
    m->stat.rtol = fnum(r, "static", "rtol");
    m->stat.utol = fnum(r, "static", "utol");
    m->stat.predictor = fint(r, "static", "predictor", 0, 1);
    m->stat.stability = fint(r, "static", "stability", 0, 1);
    m->stat.eigenvalues = fint(r, "static", "eigenvalues", 0, 1);
    m->stat.stable_path = fint(r, "static", "stable_path", 0, 1);
    m->stat.adaptive = fint(r, "static", "step_control", 0, 1);
    expect(r, "continuation");
    m->stat.arc_length = fint(r, "continuation", "method", 0, 1);
    m->stat.arc_spherical = fint(r, "continuation", "arc_constraint", 0, 1);
    m->stat.target = fnum(r, "continuation", "target_load_factor");
    m->stat.max_steps = fint(r, "continuation", "max_steps", 1, MAXN);
    m->stat.max_displacement = fnum(r, "continuation", "max_displacement");
    m->stat.arc_iters = fint(r, "continuation", "arc_iterations", 1, 10000);
    m->stat.branch_switch = fint(r, "continuation", "branch_switch", 0, 1);
    expect(r, "dynamic");
    m->dyn.t_end = fnum(r, "dynamic", "t_end");
    m->dyn.dt = fnum(r, "dynamic", "dt");
    m->dyn.dt_min = fnum(r, "dynamic", "dt_min");
    m->dyn.rho_inf = fnum(r, "dynamic", "rho_inf");
    m->dyn.tol = fnum(r, "dynamic", "tol");
    m->dyn.max_iter = fint(r, "dynamic", "max_iterations", 1, 10000);
    m->dyn.max_cutbacks = fint(r, "dynamic", "max_cutbacks", 0, 60);
    m->dyn.output_every = fint(r, "dynamic", "output_every", 1, MAXN);
    m->dyn.rayleigh_alpha = fnum(r, "dynamic", "rayleigh_alpha");
    m->dyn.rayleigh_beta = fnum(r, "dynamic", "rayleigh_beta");
    m->dyn.rtol = fnum(r, "dynamic", "rtol");
    m->dyn.utol = fnum(r, "dynamic", "utol");
    m->dyn.reuse_jacobian = fint(r, "dynamic", "jacobian", 0, 1);
    expect(r, "output");
    m->vtk_every = fint(r, "output", "vtk_every", 0, MAXN);
    expect(r, "modal");
    m->modal.nmodes = fint(r, "modal", "modes", 1, 100000);
    m->modal.about_static = fint(r, "modal", "about", 0, 1);

    expect(r, "ndof");
    m->ndof = inum(r, "ndof", 1, MAXN);
    expect(r, "q0");
    m->q0 = xcalloc(r, (size_t)m->ndof, sizeof *m->q0);
    for (int i = 0; i < m->ndof && !r->failed; ++i)
        m->q0[i] = num(r, "q0 entry");
    expect(r, "qd0");
    m->qd0 = xcalloc(r, (size_t)m->ndof, sizeof *m->qd0);
    for (int i = 0; i < m->ndof && !r->failed; ++i)
        m->qd0[i] = num(r, "qd0 entry");

    expect(r, "pairs");
    m->npair = inum(r, "pairs", 1, 1000);
    m->pairs = xcalloc(r, (size_t)m->npair, sizeof *m->pairs);
    for (int i = 0; i < m->npair && !r->failed; ++i) {
        expect(r, "pair");
        t = next(r, "kernel name");
        if (!t)
            break;
        m->pairs[i] = find_pair(t, avail, navail);
        if (!m->pairs[i])
            fail(r, "kernel '%s' is not linked into this solver (rebuild with ./build.sh run)", t);
        else if (m->pairs[i]->element->nshape > BK_MAX_SHAPE || m->pairs[i]->element->ndof > BK_MAX_ELEMENT_DOF)
            fail(r, "kernel '%s' is larger than this runtime supports", t);
    }

    expect(r, "mats");
    m->nmat = inum(r, "mats", 1, MAXN);
    m->mats = xcalloc(r, (size_t)m->nmat, sizeof *m->mats);
    for (int i = 0; i < m->nmat && !r->failed; ++i) {
        bk_mat *mt = &m->mats[i];
        expect(r, "mat");
        mt->rho = fnum(r, "mat", "rho");
        mt->nparam = fint(r, "mat", "params", 0, BK_MAT_MAXPARAM);
        for (int k = 0; k < mt->nparam && !r->failed; ++k) {
            /* name=value: the name is checked against the kernel's param_names below */
            const char *tk = next(r, "material parameter");
            const char *eq = tk ? strchr(tk, '=') : NULL;
            if (!eq || eq == tk || (size_t)(eq - tk) >= sizeof mt->param_names[k]) {
                fail(r, "material %d: expected a parameter 'name=value', found '%s'", i, tk ? tk : "");
                break;
            }
            memcpy(mt->param_names[k], tk, (size_t)(eq - tk));
            mt->param_names[k][eq - tk] = '\0';
            mt->params[k] = parse_num(r, "material parameter", eq + 1);
        }
        mt->nvisc = fint(r, "mat", "visc", 0, BK_MAT_MAXPARAM);
        for (int k = 0; k < mt->nvisc; ++k)
            mt->visc[k] = num(r, "viscous parameter");
    }

    expect(r, "geoms");
    m->ngeom = inum(r, "geoms", 1, MAXN);
    m->geoms = xcalloc(r, (size_t)m->ngeom, sizeof *m->geoms);
    m->geom_pair = xcalloc(r, (size_t)m->ngeom, sizeof *m->geom_pair);
    m->geom_elem = xcalloc(r, (size_t)m->ngeom, sizeof *m->geom_elem);
    m->tabs = xcalloc(r, (size_t)m->ngeom, sizeof *m->tabs);
    for (int i = 0; i < m->ngeom && !r->failed; ++i) {
        expect(r, "geom");
        m->geom_pair[i] = inum(r, "geometry kernel", 0, m->npair - 1);
        m->geom_elem[i] = inum(r, "geometry element", 0, MAXN);
        for (int k = 0; k < BK_NGEOM; ++k)
            m->geoms[i][k] = num(r, "geometry");
    }

    expect(r, "elements");
    m->nelem = inum(r, "elements", 1, MAXN);
    m->elems = xcalloc(r, (size_t)m->nelem, sizeof *m->elems);
    for (int i = 0; i < m->nelem && !r->failed; ++i) {
        bk_elem *e = &m->elems[i];
        expect(r, "element");
        e->pair = inum(r, "element kernel", 0, m->npair - 1);
        e->geom = inum(r, "element geometry", 0, m->ngeom - 1);
        e->mat = inum(r, "element material", 0, m->nmat - 1);
        int nd = inum(r, "element DOF count", 1, 10000);
        if (r->failed)
            break;
        const bk_pair *p = m->pairs[e->pair];
        if (nd != p->element->ndof)
            fail(r, "element %d: %d DOFs given, kernel %s has %d", i, nd, p->element->name, p->element->ndof);
        if (m->mats[e->mat].nparam != p->nparam)
            fail(r, "element %d: material has %d parameters, kernel %s_%s expects %d", i,
                 m->mats[e->mat].nparam, p->element->name, p->material, p->nparam);
        for (int k = 0; k < p->nparam && !r->failed && k < m->mats[e->mat].nparam; ++k)
            if (strcmp(m->mats[e->mat].param_names[k], p->param_names[k]) != 0)
                fail(r, "element %d: material parameter %d is '%s', kernel %s_%s expects '%s'", i, k + 1,
                     m->mats[e->mat].param_names[k], p->element->name, p->material, p->param_names[k]);
        if (m->mats[e->mat].nvisc > 0 && p->viscous && m->mats[e->mat].nvisc != p->nvisc)
            fail(r, "element %d: %d viscous parameters given, kernel %s_%s expects %d", i,
                 m->mats[e->mat].nvisc, p->element->name, p->material, p->nvisc);
        e->dofs = xcalloc(r, (size_t)nd, sizeof *e->dofs);
        for (int k = 0; k < nd && !r->failed; ++k)
            e->dofs[k] = inum(r, "element DOF", 0, m->ndof - 1);
    }

    /* Tables: each from the reference coordinates of one of its elements. */
    for (int i = 0; i < m->ngeom && !r->failed; ++i) {
        int e = m->geom_elem[i];
        if (e >= m->nelem || m->elems[e].pair != m->geom_pair[i]) {
            fail(r, "geometry %d: element %d does not use its kernel", i, e);
            break;
        }
        const bk_pair *p = m->pairs[m->geom_pair[i]];
        double *q0e = xcalloc(r, (size_t)p->element->ndof, sizeof *q0e);
        m->tabs[i] = xcalloc(r, (size_t)(p->ntab ? p->ntab : 1), sizeof(double));
        if (q0e && m->tabs[i]) {
            for (int k = 0; k < p->element->ndof; ++k)
                q0e[k] = m->q0[m->elems[e].dofs[k]];
            p->tabulate(m->geoms[i], q0e, m->tabs[i]);
        }
        free(q0e);
    }

    expect(r, "fixed");
    m->nfixed = inum(r, "fixed", 0, MAXN);
    m->fixed = xcalloc(r, (size_t)m->nfixed, sizeof *m->fixed);
    for (int i = 0; i < m->nfixed && !r->failed; ++i)
        m->fixed[i] = inum(r, "fixed DOF", 0, m->ndof - 1);

    expect(r, "lincons");
    m->nlincon = inum(r, "lincons", 0, MAXN);
    m->lincons = xcalloc(r, (size_t)m->nlincon, sizeof *m->lincons);
    for (int i = 0; i < m->nlincon && !r->failed; ++i) {
        bk_lincon *c = &m->lincons[i];
        expect(r, "lincon");
        c->nterm = inum(r, "constraint terms", 1, 10000);
        c->dof = xcalloc(r, (size_t)c->nterm, sizeof *c->dof);
        c->c0 = xcalloc(r, (size_t)c->nterm, sizeof *c->c0);
        c->cc = xcalloc(r, (size_t)c->nterm, sizeof *c->cc);
        c->cs = xcalloc(r, (size_t)c->nterm, sizeof *c->cs);
        for (int k = 0; k < c->nterm && !r->failed; ++k) {
            c->dof[k] = inum(r, "constraint DOF", 0, m->ndof - 1);
            c->c0[k] = num(r, "constraint coefficient");
            c->cc[k] = num(r, "constraint coefficient");
            c->cs[k] = num(r, "constraint coefficient");
        }
        c->r0 = num(r, "constraint right-hand side");
        c->rc = num(r, "constraint right-hand side");
        c->rs = num(r, "constraint right-hand side");
        c->kappa = num(r, "constraint angle factor");
        c->rate = num(r, "constraint angle rate");
        c->amp = num(r, "constraint angle amplitude");
        c->freq = num(r, "constraint angle frequency");
        c->angle = num(r, "constraint angle");
        c->ampl = NULL;                       /* resolved with the amplitudes */
        c->ampid = (int)num(r, "constraint angle amplitude index");
    }

    expect(r, "nlcons");
    m->nnlcon = inum(r, "nlcons", 0, MAXN);
    m->nlcons = xcalloc(r, (size_t)m->nnlcon, sizeof *m->nlcons);
    for (int i = 0; i < m->nnlcon && !r->failed; ++i) {
        bk_nlcon *c = &m->nlcons[i];
        expect(r, "nlcon");
        t = next(r, "joint type");
        if (t && strlen(t) >= sizeof c->type)
            fail(r, "joint type '%s' too long", t);
        else if (t)
            memcpy(c->type, t, strlen(t) + 1);
        for (int k = 0; k < BK_JOINT_NX; ++k)
            c->dof[k] = inum(r, "joint DOF", -1, m->ndof - 1);
        for (int k = 0; k < BK_JOINT_NX; ++k)
            c->x0[k] = num(r, "joint coordinate");
        for (int k = 0; k < BK_JOINT_NPARAM; ++k)
            c->prm[k] = num(r, "joint parameter");
    }

    expect(r, "forces");
    m->nforce = inum(r, "forces", 0, MAXN);
    m->forces = xcalloc(r, (size_t)m->nforce, sizeof *m->forces);
    for (int i = 0; i < m->nforce && !r->failed; ++i) {
        bk_force_load *f = &m->forces[i];
        expect(r, "force");
        f->elem = inum(r, "force element", 0, m->nelem - 1);
        f->xi = num(r, "force xi");
        f->y = num(r, "force y");
        f->z = num(r, "force z");
        f->section = inum(r, "force distribution", 0, 1);
        for (int k = 0; k < 3; ++k)
            f->value[k] = num(r, "force value");
        f->amp = inum(r, "force amplitude", -1, MAXN);
        f->follower = inum(r, "force follower flag", 0, 1);
    }

    expect(r, "moments");
    m->nmoment = inum(r, "moments", 0, MAXN);
    m->moments = xcalloc(r, (size_t)m->nmoment, sizeof *m->moments);
    for (int i = 0; i < m->nmoment && !r->failed; ++i) {
        bk_moment_load *mo = &m->moments[i];
        expect(r, "moment");
        mo->elem = inum(r, "moment element", 0, m->nelem - 1);
        mo->xi = num(r, "moment xi");
        for (int k = 0; k < 3; ++k)
            mo->value[k] = num(r, "moment value");
        mo->amp = inum(r, "moment amplitude", -1, MAXN);
        mo->follower = inum(r, "moment follower flag", 0, 1);
    }

    expect(r, "gravity");
    m->has_gravity = inum(r, "gravity flag", 0, 1);
    m->gravity_ampid = -1;
    if (m->has_gravity) {
        for (int k = 0; k < 3; ++k)
            m->gravity[k] = num(r, "gravity");
        m->gravity_ampid = inum(r, "gravity amplitude", -1, MAXN);
    }

    expect(r, "sensors");
    m->nsensor = inum(r, "sensors", 0, MAXN);
    m->sensors = xcalloc(r, (size_t)m->nsensor, sizeof *m->sensors);
    for (int i = 0; i < m->nsensor && !r->failed; ++i) {
        bk_sensor *s = &m->sensors[i];
        expect(r, "sensor");
        t = next(r, "sensor name");
        if (t && strlen(t) >= sizeof s->name)
            fail(r, "sensor name longer than %zu characters", sizeof s->name - 1);
        else if (t)
            memcpy(s->name, t, strlen(t) + 1);
        s->elem = inum(r, "sensor element", 0, m->nelem - 1);
        s->xi = num(r, "sensor xi");
    }
    read_extras(r, m);
    expect(r, "end");
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
