/* overlap.c -- parts of beams passing through one another with no beam
 * contact modelled (see overlap.h). */
#include "output/overlap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assembly/interaction.h"
#include "assembly/system.h"

#define NS (BK_OVERLAP_SEG + 1)

/* The least distance between the segments a0-a1 and b0-b1 (closest points by
 * the clamped parameters of the two lines; degenerate segments as points). */
static double seg_dist(const double *a0, const double *a1, const double *b0, const double *b1)
{
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; ++k)
        d1[k] = a1[k] - a0[k], d2[k] = b1[k] - b0[k], r[k] = a0[k] - b0[k];
    const double a = d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2];
    const double e = d2[0] * d2[0] + d2[1] * d2[1] + d2[2] * d2[2];
    const double f = d2[0] * r[0] + d2[1] * r[1] + d2[2] * r[2];
    const double tiny = 1e-300;
    double s = 0.0, t = 0.0;
    if (a <= tiny && e <= tiny) {
        s = t = 0.0;
    } else if (a <= tiny) {
        t = fmin(fmax(f / e, 0.0), 1.0);
    } else {
        const double c = d1[0] * r[0] + d1[1] * r[1] + d1[2] * r[2];
        if (e <= tiny) {
            s = fmin(fmax(-c / a, 0.0), 1.0);
        } else {
            const double b = d1[0] * d2[0] + d1[1] * d2[1] + d1[2] * d2[2], den = a * e - b * b;
            s = den > 1e-14 * a * e ? fmin(fmax((b * f - c * e) / den, 0.0), 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0)
                t = 0.0, s = fmin(fmax(-c / a, 0.0), 1.0);
            else if (t > 1.0)
                t = 1.0, s = fmin(fmax((b - c) / a, 0.0), 1.0);
        }
    }
    double d2s = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double x = r[k] + s * d1[k] - t * d2[k];
        d2s += x * x;
    }
    return sqrt(d2s);
}

/* The least distance between elements ia and ib in the reference configuration. */
static double ref_dist(const bk_overlap *o, int ia, int ib)
{
    double d = INFINITY;
    for (int ja = 0; ja < BK_OVERLAP_SEG; ++ja)
        for (int jb = 0; jb < BK_OVERLAP_SEG; ++jb) {
            const double *a = o->ref + 3 * (NS * ia + ja), *b = o->ref + 3 * (NS * ib + jb);
            d = fmin(d, seg_dist(a, a + 3, b, b + 3));
        }
    return d;
}

/* (on the threads from BK_OVERLAP_PAR elements: a 10,000-element check took
 * 15 ms on one) */
#define BK_OVERLAP_PAR 2048
static void sample_one(const bk_model *m, const double *q, int i, double *out)
{
    for (int j = 0; j < NS; ++j)
        bk_eval_point(m, q, m->sections[i].elem, (double)j / BK_OVERLAP_SEG, out + 3 * (NS * i + j), NULL);
}

static void sample(const bk_model *m, const double *q, double *out)
{
    if (m->nsection >= BK_OVERLAP_PAR) {      /* (no team for small models: libgomp makes one even if(0)) */
#pragma omp parallel for schedule(static)
        for (int i = 0; i < m->nsection; ++i)
            sample_one(m, q, i, out);
    } else {
        for (int i = 0; i < m->nsection; ++i)
            sample_one(m, q, i, out);
    }
}

/* Chunks: runs of consecutive elements of one beam no longer than the least
 * section in them (their element pairs are neighbours by arc length, below),
 * so that a fine mesh gives the broad phase boxes about as long as wide. */
static int make_chunks(bk_overlap *o, const bk_model *m)
{
    o->nchunk = 0;
    double cs0 = 0.0, rmin = 0.0;
    for (int i = 0; i < m->nsection; ++i) {
        const bk_section_rec *c = &m->sections[i];
        const int join = i > 0 && o->beam[i] == o->beam[i - 1] && c->s0 >= cs0 &&
                         c->s0 <= m->sections[i - 1].s1 + 1e-12 * (1.0 + fabs(c->s0)) &&
                         c->s1 - cs0 <= 2.0 * fmin(rmin, c->r);
        if (join) {
            rmin = fmin(rmin, c->r);
            o->crmin[o->nchunk - 1] = rmin;
            o->cord[o->nchunk - 1] &= c->s0 >= m->sections[i - 1].s0 && c->s1 >= m->sections[i - 1].s1;
            continue;
        }
        o->crmin[o->nchunk] = c->r;
        o->cord[o->nchunk] = 1;
        o->chunk[o->nchunk++] = i;
        cs0 = c->s0, rmin = c->r;
    }
    o->chunk[o->nchunk] = m->nsection;
    return o->nchunk;
}

/* o->beam: the sections' beam names as numbers, so that a check compares
 * numbers, not names (a 10,000-element beam's check compared names some
 * 100,000 times).  A beam's sections are mostly consecutive: a name is
 * looked up among the beams so far (first: a section of each) only where it
 * changes.  0, or -1 when out of memory. */
static int number_beams(bk_overlap *o, const bk_model *m)
{
    int nb = 0, *first = malloc((size_t)m->nsection * sizeof *first);
    if (!first)
        return -1;
    for (int i = 0; i < m->nsection; ++i) {
        const char *b = m->sections[i].beam;
        if (i > 0 && strcmp(b, m->sections[i - 1].beam) == 0) {
            o->beam[i] = o->beam[i - 1];
            continue;
        }
        int id = 0;
        while (id < nb && strcmp(b, m->sections[first[id]].beam) != 0)
            ++id;
        if (id == nb)
            first[nb++] = i;
        o->beam[i] = id;
    }
    free(first);
    return 0;
}

int bk_overlap_init(bk_overlap *o, const bk_system *s)
{
    const bk_model *m = s->m;
    memset(o, 0, sizeof *o);
    if (m->nsection < 2 || bk_interactions_keep_apart(s))
        return 0;
    const size_t n = (size_t)m->nsection;
    o->ref = malloc(n * NS * 3 * sizeof *o->ref);
    o->cur = malloc(n * NS * 3 * sizeof *o->cur);
    o->box = malloc(n * sizeof *o->box);
    o->cbox = malloc(n * sizeof *o->cbox);
    o->chunk = malloc((n + 1) * sizeof *o->chunk);
    o->beam = malloc(n * sizeof *o->beam);
    o->crmin = malloc(n * sizeof *o->crmin);
    o->cord = malloc(n);
    if (!o->ref || !o->cur || !o->box || !o->cbox || !o->chunk || !o->beam || !o->crmin || !o->cord) {
        bk_overlap_free(o);
        return -1;
    }
    if (number_beams(o, m) != 0) {
        bk_overlap_free(o);
        return -1;
    }
    sample(m, m->q0, o->ref);
    make_chunks(o, m);
    o->n = m->nsection;
    return 0;
}

void bk_overlap_free(bk_overlap *o)
{
    free(o->ref);
    free(o->cur);
    free(o->box);
    free(o->cbox);
    free(o->chunk);
    free(o->pairs);
    free(o->beam);
    free(o->crmin);
    free(o->cord);
    memset(o, 0, sizeof *o);
}

static int boxes_meet(const bk_box *a, const bk_box *b)
{
    for (int k = 0; k < 3; ++k)
        if (a->hi[k] < b->lo[k] || b->hi[k] < a->lo[k])
            return 0;
    return 1;
}

/* Elements ia, ib: a pair to compare (not neighbours), then their first two
 * segments closer than their half-heights (1, with the warning), else 0. */
static int compare(bk_overlap *o, const bk_model *m, int ia, int ib, const char *what, double t,
                   bk_run_info *info, FILE *console)
{
    const bk_section_rec *A = &m->sections[ia], *B = &m->sections[ib];
    const double rr = A->r + B->r;
    const int self = o->beam[ia] == o->beam[ib];
    if (self && fmax(A->s0, B->s0) - fmin(A->s1, B->s1) <= 2.0 * rr)
        return 0;                           /* neighbours along the beam (so also in the reference) */
    if (!self && A->group == B->group)
        return 0;                           /* links of one mechanism */
    if (!boxes_meet(&o->box[ia], &o->box[ib]) || ref_dist(o, ia, ib) <= 2.0 * rr)
        return 0;                           /* apart, or neighbours from the start */
    for (int ja = 0; ja < BK_OVERLAP_SEG; ++ja)
        for (int jb = 0; jb < BK_OVERLAP_SEG; ++jb) {
            const double *a = o->cur + 3 * (NS * ia + ja), *b = o->cur + 3 * (NS * ib + jb);
            const double d = seg_dist(a, a + 3, b, b + 3);
            if (!(d < rr))
                continue;
            const double sa = A->s0 + (ja + 0.5) / BK_OVERLAP_SEG * (A->s1 - A->s0);
            const double sb = B->s0 + (jb + 0.5) / BK_OVERLAP_SEG * (B->s1 - B->s0);
            o->reported = 1;
            bk_warn(info, console, m->name,
                    "beam '%s' at s = %.4g m (element %d) and beam '%s' at s = %.4g m (element %d) are %.3g m "
                    "apart at %s %.6g, less than their sections' half-heights (%.3g + %.3g m): %s, and "
                    "nothing keeps them apart (no beam contact is modelled: add [[beam_contact]] with "
                    "self = true and the beams)", A->beam, sa, A->elem + 1, B->beam, sb, B->elem + 1, d, what, t,
                    A->r, B->r, self ? "the beam passes through itself" : "the beams pass through each other");
            return 1;
        }
    return 0;
}

void bk_overlap_check(bk_overlap *o, const bk_model *m, const double *q, const char *what, double t,
                      bk_run_info *info, FILE *console)
{
    if (o->n == 0 || o->reported)
        return;
    sample(m, q, o->cur);
    for (int c = 0; c < o->nchunk; ++c) {
        bk_box *cb = &o->cbox[c];
        for (int k = 0; k < 3; ++k)
            cb->lo[k] = INFINITY, cb->hi[k] = -INFINITY;
        for (int i = o->chunk[c]; i < o->chunk[c + 1]; ++i) {
            const double r = m->sections[i].r;
            bk_box *b = &o->box[i];
            for (int k = 0; k < 3; ++k)
                b->lo[k] = INFINITY, b->hi[k] = -INFINITY;
            for (int j = 0; j < NS; ++j)
                for (int k = 0; k < 3; ++k) {
                    const double x = o->cur[3 * (NS * i + j) + k];
                    if (!isfinite(x))
                        return;             /* the admissibility checks name a non-finite state */
                    /* (comparisons, not fmin/fmax: finite here, and a call each otherwise) */
                    b->lo[k] = x - r < b->lo[k] ? x - r : b->lo[k];
                    b->hi[k] = x + r > b->hi[k] ? x + r : b->hi[k];
                }
            for (int k = 0; k < 3; ++k) {
                cb->lo[k] = b->lo[k] < cb->lo[k] ? b->lo[k] : cb->lo[k];
                cb->hi[k] = b->hi[k] > cb->hi[k] ? b->hi[k] : cb->hi[k];
            }
        }
    }
    const int np = bk_broad_pairs(o->cbox, o->nchunk, &o->pairs, &o->cap);
    for (int p = 0; p < np; ++p) {
        const int ca = o->pairs[2 * p], cb = o->pairs[2 * p + 1];
        const int a0 = o->chunk[ca], a1 = o->chunk[ca + 1], b0 = o->chunk[cb], b1 = o->chunk[cb + 1];
        /* Two ordered chunks of one beam, one after the other along it: the
         * pairs whose gap in arc length is within twice the chunks' least
         * half-heights are neighbours (compare would pass them at once); for
         * each ia they are a run at the end of cb's elements next to ca's,
         * and that run only grows with ia (a 10,000-element beam's check
         * went through ~3 million of them).  The others in the same order. */
        const int along = o->beam[a0] == o->beam[b0] && o->cord[ca] && o->cord[cb];
        const double near = 2.0 * (o->crmin[ca] + o->crmin[cb]);
        const bk_section_rec *S = m->sections;
        const int after = along && S[a1 - 1].s1 <= S[b0].s0, before = along && !after && S[b1 - 1].s1 <= S[a0].s0;
        int lo = b0, hi = before ? b0 : b1;      /* cb's elements compared with ia: lo .. hi - 1 */
        for (int ia = a0; ia < a1; ++ia) {
            if (after)                           /* cb after ca: its first ones are neighbours */
                while (lo < b1 && S[lo].s0 - S[ia].s1 <= near)
                    ++lo;
            else if (before)                     /* cb before ca: its last ones */
                while (hi < b1 && S[ia].s0 - S[hi].s1 > near)
                    ++hi;
            for (int ib = lo; ib < hi; ++ib)
                if (compare(o, m, ia, ib, what, t, info, console))
                    return;
        }
    }
}
