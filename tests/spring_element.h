/* spring_element.h -- hand-written elements behind the same descriptors as the
 * generated kernels (runtime/bk_kernel.h), for C unit tests of the runtime.
 *
 *   spring: 2 nodes x r (6 DOF), an axial spring of stiffness k = mat[0]
 *           between the nodes: U = k/2 (|d| - L0)^2, d = r_1 - r_0, L0 = |d| in
 *           the reference configuration (tab[0]).  Tangent
 *           K_dd = k [n n^T + (1 - L0/|d|)(I - n n^T)], n = d/|d|.
 *           Mass of a bar of section A = geom[BK_GEOM_A], length l.
 *   link:   2 nodes x r + one multiplier lambda (7 DOF): keeps |d| = L0 by an
 *           element-internal Lagrange multiplier, U = c lambda (|d| - L0),
 *           c = mat[0] (the scaling of the multiplier row).
 */
#ifndef SPRING_ELEMENT_H
#define SPRING_ELEMENT_H

#include "bk_kernel.h"

extern const bk_element spring_element, link_element;
extern const bk_pair spring_pair, link_pair;

#endif
