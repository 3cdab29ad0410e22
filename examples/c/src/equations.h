/* Equations (1)-(4) of the paper and FGM's gap centre angle, as printed and as read
 * (docs/errata.md rows 1-10; ifgm_ref/paper/equations.py is the reference). Pure math: nothing
 * here knows a planner.
 *
 * Each function returns 0 and writes its result, or returns IFGM_EQ_UNDEFINED where the
 * reference raises ParameterError (a division by zero, a direction of a zero vector, weights
 * out of their domain), writing nothing. */
#ifndef IFGM_EQUATIONS_H
#define IFGM_EQUATIONS_H

#include "real.h"

#define IFGM_EQ_UNDEFINED (-1)

/* x wrapped into [-pi, pi), as Python's (x + pi) % (2 pi) - pi. */
ifgm_real ifgm_wrap_angle(ifgm_real x);

/* eq. (1), read as the midpoint of the two obstacle points (errata row 1). */
int eq1_gap_midpoint(const ifgm_real p1[2], const ifgm_real p2[2], ifgm_real out[2]);
/* eq. (2) as printed, theta_g = y_g / x_g (a ratio), and as read, atan2 (row 2). */
int eq2_gap_angle_literal(ifgm_real x_g, ifgm_real y_g, ifgm_real *out);
int eq2_gap_angle(ifgm_real x_g, ifgm_real y_g, ifgm_real *out);
/* FGM's gap centre angle by the cosine and Apollonius theorems (row 10). */
int fgm_gap_centre_angle(ifgm_real d1, ifgm_real phi1, ifgm_real d2, ifgm_real phi2,
                         ifgm_real *out);
/* eq. (3) as printed (one-argument arctan) and as read (atan2; row 5). */
int eq3_goal_angle_literal(const ifgm_real current[2], const ifgm_real destination[2],
                           ifgm_real *out);
int eq3_goal_angle(const ifgm_real current[2], const ifgm_real destination[2], ifgm_real *out);
/* eq. (4) as printed (a mean of numbers), and as read: the same weights applied to the
 * angles relative to the heading, wrapped (rows 4, 6-9). */
int eq4_final_heading_literal(ifgm_real theta_g, ifgm_real theta_d, ifgm_real w_g,
                              ifgm_real w_d, ifgm_real d_th, ifgm_real *out);
int eq4_final_heading(ifgm_real theta_g, ifgm_real theta_d, ifgm_real w_g, ifgm_real w_d,
                      ifgm_real d_th, ifgm_real heading, ifgm_real *out);
/* eq. (4) with FGM's weights alpha / d_min and beta (row 8). */
int eq4_final_heading_fgm(ifgm_real theta_g, ifgm_real theta_d, ifgm_real alpha,
                          ifgm_real beta, ifgm_real d_min, ifgm_real heading, ifgm_real *out);

#endif
