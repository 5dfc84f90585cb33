/* dyn_energy.h -- the energy balance of a dynamic run (energy.csv, summary.json
 * "energy"), private to analysis/.
 *
 * Over every accepted step the powers at the converged state (dynamics.c's
 * residual records them) are integrated by the trapezoidal rule:
 *   W  the work of everything acting on the model from outside: constant loads
 *      and gravity (f_ext q'), the interactions (loads with amplitudes,
 *      tendons, chambers, contact: -f q') and the constraints (-s G^T nu q':
 *      the work of prescribed motions; ~0 for fixed joints),
 *   D  the energy dissipated by damping (Rayleigh alpha q'Mq' + beta q'K_t q',
 *      viscous laws f_v q').
 * The integrator's dissipation is what closes the balance,
 *   D_num = W - D - (T - T0) - (U - U0),
 * T the kinetic (with rotary) and U the strain energy: positive when the
 * scheme removes energy (rho_inf < 1), negative when it creates it.  Its
 * drift is reported relative to the largest energy seen (`scale`). */
#ifndef BK_DYN_ENERGY_H
#define BK_DYN_ENERGY_H

#include <stdio.h>

#include "output/output.h"

typedef struct bk_energy {
    double T0, U0;        /* at t = 0 (U is reported relative to U0)            */
    double P, Pd;         /* applied and damping power at the last state        */
    double W, D, Dnum;    /* work of loads, damping dissipation, integrator's   */
    double Dnum_max;      /* its largest value so far                           */
    double created;       /* the largest (Dnum_max - D_num) / scale so far      */
    double t_created;     /* when (the energy created, as the step check sees)  */
    double scale;         /* the largest |T - T0|, |U - U0|, |W|, T seen        */
} bk_energy;

/* At t = 0: T, U and the powers of the initial state; floor, the least energy
 * scale (the energies of a run that has barely started are round-off and the
 * start of its transients: dynamics.c takes the kinetic energy of the model's
 * mass moving its length over the run). */
void bk_energy_start(bk_energy *e, double T, double U, double P, double Pd, double floor);
/* After an accepted step of length h ending at t in a state with T, U, P, Pd. */
void bk_energy_step(bk_energy *e, double t, double h, double T, double U, double P, double Pd);
/* Energy created: an accepted step may not bring the integrator's dissipation
 * more than BK_ENERGY_CREATED times the energy scale below its largest value
 * (the scheme gives energy back only by round-off and the small swings of
 * its high modes); above BK_ENERGY_CREATED_WARN the run is warned. */
#define BK_ENERGY_CREATED 5e-2
#define BK_ENERGY_CREATED_WARN 1e-2
/* The balance e would have after a step (h, T, U, P, Pd) into *trial; returns
 * the energy created so far (the fall of D_num below its largest value) over
 * the energy scale. */
double bk_energy_trial(const bk_energy *e, double t, double h, double T, double U, double P, double Pd,
                       bk_energy *trial);
/* energy.csv (its registration, base/tables.h) and one of its rows (T, U
 * relative to U0, the gravity and load potentials, their total, the balance,
 * the constraint residual). */
extern const bk_table_spec bk_energy_csv;
void bk_energy_row(const bk_energy *e, bk_output *out, FILE *table, int step, double t, double T, double U,
                   double Vg, double Vf, double cres);
/* summary.json "energy": {"work_loads", "dissipated_damping", "dissipated_integrator",
 * "drift", "created_max", "created_at", "scale"}: drift = D_num / scale at the end,
 * created_max = the largest energy created (D_num's fall below its largest value
 * before, over the scale then: what the step check and its warning measure) and
 * created_at its time, written into text (size n). */
void bk_energy_summary(const bk_energy *e, char *text, size_t n);

#endif
