/* vtk_geometry.h -- the drawn beams of the ParaView frames (private to
 * output/): at NX stations along each element a ring of points around its
 * section (vtk_geometry.c), the cells joining them, the element's stress
 * resultants along it, and the view of a mode (vtk.c writes the files). */
#ifndef BK_VTK_GEOMETRY_H
#define BK_VTK_GEOMETRY_H

#include <stddef.h>

#include "model/model.h"

#define NX 4
#define MAX_RING 12              /* points of the largest section ring (bk_vtk_ring_points) */

/* What a .vtu shows.  A step frame (mode == NULL): the points of q and their
 * displacement from the reference.  A mode frame: the base state q displaced by
 * scale * shape, where shape is the linearized motion of each point along the
 * mode vector phi, (x(q + eps phi) - x(q - eps phi)) / (2 eps) / norm (exact for
 * the continuum elements, whose points are linear in q). */
typedef struct mode_view {
    const double *qp, *qm;   /* q + eps phi, q - eps phi */
    double eps, norm, scale;
} mode_view;

int bk_vtk_ring_points(const bk_model *m, int e);
void bk_vtk_stress_value(const bk_model *m, const double *ssec, int maxsample, int e, int a, double xi, double *x);
void bk_vtk_frame_points(const bk_model *m, const double *q, const mode_view *mv, int pass, double *x, int par);
void bk_vtk_frame_cells(const bk_model *m, long *ncell, long *nconn);
/* The strain energy density of every element at q into dens[nelem] (J/m^3; on
 * the threads when par). */
void bk_vtk_energy_density(const bk_model *m, const double *q, double *dens, int par);
size_t bk_vtk_index_size(long npts);
size_t bk_vtk_topology(const bk_model *m, unsigned char *buf);

/* The field data of a mode frame: TIME and MODE (the mode number), the nval
 * values under their names in capitals (caps: their storage), MODE_SCALE;
 * into fname, fval (at most BK_VTK_MODE_FIELDS); returns their count. */
#define BK_VTK_MODE_FIELDS 8
#define BK_VTK_NAME 48
int bk_vtk_mode_fields(int mode, int nval, const char *const *names, const double *vals, double scale,
                       char caps[][BK_VTK_NAME], const char **fname, double *fval);

#endif
