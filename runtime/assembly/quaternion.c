/* quaternion.c -- unit-length upkeep of nodal quaternions. */
#include "assembly/quaternion.h"

#include <math.h>
#include <stdlib.h>

int *bk_quat_list(const bk_system *s, int *n)
{
    const bk_model *m = s->m;
    *n = 0;
    char *seen = calloc((size_t)m->ndof, 1);
    int *list = malloc((size_t)(m->ndof / 4 + 1) * sizeof *list);
    if (!seen || !list) {
        free(seen);
        free(list);
        *n = -1;
        return NULL;
    }
    for (int e = 0; e < m->nelem; ++e) {
        const bk_elem *el = &m->elems[e];
        const bk_element *et = m->pairs[el->pair]->element;
        for (int f = 0; f < et->nfield; ++f) {
            if (et->field_role[f] != BK_FIELD_QUATERNION || et->field_dim[f] != 4)
                continue;
            const int *d = el->dofs + et->field_dof[f];
            int ok = !seen[d[0]];
            for (int k = 0; k < 4; ++k)
                ok = ok && s->eq[d[k]] >= 0 && d[k] == d[0] + k;
            seen[d[0]] = 1;
            if (ok)
                list[(*n)++] = d[0];
        }
    }
    free(seen);
    if (*n == 0) {
        free(list);
        return NULL;
    }
    return list;
}

void bk_quat_normalize(const int *list, int n, double *q, double *const *v, int nv)
{
    for (int k = 0; k < n; ++k) {
        double *p = q + list[k];
        double nn = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
        if (!(nn > 0.0) || !isfinite(nn))
            continue;
        for (int i = 0; i < 4; ++i)
            p[i] /= nn;
        for (int j = 0; j < nv; ++j) {
            double *r = v[j] + list[k];
            double c = r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3] * p[3];
            for (int i = 0; i < 4; ++i)
                r[i] -= c * p[i];
        }
    }
}

void bk_quat_normalize_motion(const int *list, int n, double *q, double *qd, double *const *acc, int nacc)
{
    bk_quat_normalize(list, n, q, &qd, 1);
    for (int k = 0; k < n; ++k) {
        const double *p = q + list[k], *v = qd + list[k];
        double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3];
        for (int j = 0; j < nacc; ++j) {
            double *r = acc[j] + list[k];
            double c = r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3] * p[3] + vv;
            for (int i = 0; i < 4; ++i)
                r[i] -= c * p[i];
        }
    }
}
