/* actuator_read.c -- the actuator records of the model file (model/actuator.h),
 * written by gen/scene/actuators.py:
 *   actuators N
 *   actuator NAME KIND JOINT EFFORT EAMP KP KD SETPOINT SAMP   (N times; KIND rotation | translation) */
#include <stdlib.h>
#include <string.h>

#include "model/reader.h"

void bk_model_read_actuators(bk_reader *r, bk_model *m)
{
    rd_expect(r, "actuators");
    int n = rd_inum(r, "actuators", 0, MAXN);
    if (r->failed || n == 0)
        return;
    bk_actuator_model *am = rd_xcalloc(r, 1, sizeof *am);
    if (!am)
        return;
    m->actuators = am;
    am->acts = rd_xcalloc(r, (size_t)n, sizeof *am->acts);
    for (int i = 0; i < n && !r->failed; ++i) {
        bk_actuator *a = &am->acts[i];
        rd_expect(r, "actuator");
        rd_copy_token(r, a->name, sizeof a->name, "actuator name");
        const char *t = rd_next(r, "actuator kind");
        a->kind = !t ? 0 : strcmp(t, "rotation") == 0 ? BK_ACT_ROTATION
                  : strcmp(t, "translation") == 0 ? BK_ACT_TRANSLATION : 0;
        if (t && !a->kind)
            rd_fail(r, "actuator %d: unknown kind '%s' (expected rotation or translation)", i, t);
        a->nlcon = rd_inum(r, "actuator joint", 0, m->nnlcon - 1);
        a->effort0 = rd_num(r, "actuator effort");
        a->eamp = rd_inum(r, "actuator effort amplitude", -1, m->namp - 1);
        a->kp = rd_num(r, "actuator kp");
        a->kd = rd_num(r, "actuator kd");
        a->setpoint = rd_num(r, "actuator set-point");
        a->samp = rd_inum(r, "actuator set-point amplitude", -1, m->namp - 1);
        if (!r->failed && !(a->kp >= 0.0 && a->kd >= 0.0))
            rd_fail(r, "actuator %d: gains kp, kd must be >= 0 (%g, %g)", i, a->kp, a->kd);
        am->n = i + 1;
    }
}

void bk_actuator_model_free(bk_actuator_model *am)
{
    if (!am)
        return;
    free(am->acts);
    free(am);
}
