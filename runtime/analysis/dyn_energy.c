/* dyn_energy.c -- the energy balance of a dynamic run (dyn_energy.h). */
#include "analysis/dyn_energy.h"

#include <math.h>
#include <stddef.h>

#include "base/clock.h"

void bk_energy_start(bk_energy *e, double T, double U, double P, double Pd, double floor)
{
    *e = (bk_energy){.T0 = T, .U0 = U, .P = P, .Pd = Pd, .scale = fmax(fabs(T), floor)};
}

void bk_energy_step(bk_energy *e, double t, double h, double T, double U, double P, double Pd)
{
    e->W += 0.5 * h * (e->P + P);
    e->D += 0.5 * h * (e->Pd + Pd);
    e->P = P, e->Pd = Pd;
    e->Dnum = e->W - e->D - (T - e->T0) - (U - e->U0);
    e->scale = fmax(e->scale, fmax(fmax(fabs(T), fabs(T - e->T0)), fmax(fabs(U - e->U0), fabs(e->W))));
    e->Dnum_max = fmax(e->Dnum_max, e->Dnum);
    /* the energy created (the fall below the largest dissipation) as the
     * step check measures it: over the scale at the time */
    const double created = (e->Dnum_max - e->Dnum) / (e->scale > 0.0 ? e->scale : 1.0);
    if (created > e->created)
        e->created = created, e->t_created = t;
}

double bk_energy_trial(const bk_energy *e, double t, double h, double T, double U, double P, double Pd,
                       bk_energy *trial)
{
    *trial = *e;
    bk_energy_step(trial, t, h, T, U, P, Pd);
    return (trial->Dnum_max - trial->Dnum) / (trial->scale > 0.0 ? trial->scale : 1.0);
}

const bk_table_spec bk_energy_csv =
    BK_TABLE("energy.csv", "dynamics",
             "step,time,kinetic,strain,gravity,load_potential,total,constraint_residual,work_loads,"
             "dissipated_damping,dissipated_integrator\n");

void bk_energy_row(const bk_energy *e, bk_output *out, FILE *table, int step, double t, double T, double U,
                   double Vg, double Vf, double cres)
{
    double t0 = bk_clock_s();
    bk_row r;
    bk_output_row(out, &r, table);
    bk_row_int(&r, step);
    const double v[6] = {t, T, U, Vg, Vf, T + U + Vg + Vf};
    for (int i = 0; i < 6; ++i)
        bk_row_num(&r, v[i]);
    bk_row_e(&r, cres, 3);
    bk_row_num(&r, e->W);
    bk_row_num(&r, e->D);
    bk_row_num(&r, e->Dnum);
    bk_output_row_end(out, &r, t0, 1);
}

void bk_energy_summary(const bk_energy *e, char *text, size_t n)
{
    const double sc = e->scale > 0.0 ? e->scale : 1.0;
    snprintf(text, n, "{\"work_loads\": %.17g, \"dissipated_damping\": %.17g, \"dissipated_integrator\": %.17g, "
             "\"drift\": %.17g, \"created_max\": %.17g, \"created_at\": %.17g, \"scale\": %.17g}",
             e->W, e->D, e->Dnum, e->Dnum / sc, e->created, e->t_created, e->scale);
}
