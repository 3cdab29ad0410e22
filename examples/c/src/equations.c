/* Equations (1)-(4) and FGM's gap centre angle: see equations.h. */
#include "equations.h"

ifgm_real ifgm_wrap_angle(ifgm_real x)
{
    /* Python's float modulo: the remainder takes the sign of the divisor (2 pi). */
    const ifgm_real two_pi = 2 * IFGM_PI;
    ifgm_real m = fmod(x + IFGM_PI, two_pi);
    if (m != 0) {
        if (m < 0)
            m += two_pi;
    } else {
        m = 0; /* +0.0, as Python gives */
    }
    return m - IFGM_PI;
}

/* An angle already in [-pi, pi) is kept as it is (no rounding through the modulo). */
static ifgm_real wrap_if_needed(ifgm_real a)
{
    return (-IFGM_PI <= a && a < IFGM_PI) ? a : ifgm_wrap_angle(a);
}

int eq1_gap_midpoint(const ifgm_real p1[2], const ifgm_real p2[2], ifgm_real out[2])
{
    out[0] = (p1[0] + p2[0]) / 2;
    out[1] = (p1[1] + p2[1]) / 2;
    return 0;
}

int eq2_gap_angle_literal(ifgm_real x_g, ifgm_real y_g, ifgm_real *out)
{
    if (x_g == 0)
        return IFGM_EQ_UNDEFINED;
    *out = y_g / x_g;
    return 0;
}

int eq2_gap_angle(ifgm_real x_g, ifgm_real y_g, ifgm_real *out)
{
    if (x_g == 0 && y_g == 0)
        return IFGM_EQ_UNDEFINED;
    *out = atan2(y_g, x_g);
    return 0;
}

int fgm_gap_centre_angle(ifgm_real d1, ifgm_real phi1, ifgm_real d2, ifgm_real phi2,
                         ifgm_real *out)
{
    if (!(isfinite(d1) && d1 > 0) || !(isfinite(d2) && d2 > 0))
        return IFGM_EQ_UNDEFINED;
    ifgm_real width = phi1 + phi2;
    if (!(0 <= width && width <= IFGM_PI))
        return IFGM_EQ_UNDEFINED;
    ifgm_real cos_width = cos(width);
    ifgm_real squared = d1 * d1 + d2 * d2 + 2 * d1 * d2 * cos_width;
    if (squared <= 0)
        return IFGM_EQ_UNDEFINED;
    ifgm_real argument = (d1 + d2 * cos_width) / sqrt(squared);
    if (argument > 1)
        argument = 1;
    if (argument < -1)
        argument = -1;
    *out = acos(argument) - phi1;
    return 0;
}

int eq3_goal_angle_literal(const ifgm_real current[2], const ifgm_real destination[2],
                           ifgm_real *out)
{
    if (destination[0] == current[0])
        return IFGM_EQ_UNDEFINED;
    *out = atan((destination[1] - current[1]) / (destination[0] - current[0]));
    return 0;
}

int eq3_goal_angle(const ifgm_real current[2], const ifgm_real destination[2], ifgm_real *out)
{
    if (destination[0] == current[0] && destination[1] == current[1])
        return IFGM_EQ_UNDEFINED;
    *out = atan2(destination[1] - current[1], destination[0] - current[0]);
    return 0;
}

/* The weights' domain (errata row 9): finite, >= 0, not both 0, divided by a divisor > 0. */
static int weights_ok(ifgm_real gap, ifgm_real goal, ifgm_real divisor)
{
    if (!isfinite(gap) || !isfinite(goal) || !isfinite(divisor))
        return 0;
    return divisor > 0 && gap >= 0 && goal >= 0 && !(gap == 0 && goal == 0);
}

int eq4_final_heading_literal(ifgm_real theta_g, ifgm_real theta_d, ifgm_real w_g,
                              ifgm_real w_d, ifgm_real d_th, ifgm_real *out)
{
    if (!isfinite(theta_g) || !isfinite(theta_d) || !weights_ok(w_g, w_d, d_th))
        return IFGM_EQ_UNDEFINED;
    ifgm_real gap_weight = w_g / d_th;
    *out = (gap_weight * theta_g + w_d * theta_d) / (gap_weight + w_d);
    return 0;
}

/* The weighted mean of two directions, relative to the heading (errata row 6). */
static ifgm_real robot_frame_mean(ifgm_real theta_g, ifgm_real theta_d, ifgm_real gap_weight,
                                  ifgm_real goal_weight, ifgm_real heading)
{
    ifgm_real relative_g = wrap_if_needed(theta_g - heading);
    ifgm_real relative_d = wrap_if_needed(theta_d - heading);
    ifgm_real mean =
        (gap_weight * relative_g + goal_weight * relative_d) / (gap_weight + goal_weight);
    return wrap_if_needed(heading + mean);
}

int eq4_final_heading(ifgm_real theta_g, ifgm_real theta_d, ifgm_real w_g, ifgm_real w_d,
                      ifgm_real d_th, ifgm_real heading, ifgm_real *out)
{
    if (!isfinite(theta_g) || !isfinite(theta_d) || !isfinite(heading) ||
        !weights_ok(w_g, w_d, d_th))
        return IFGM_EQ_UNDEFINED;
    *out = robot_frame_mean(theta_g, theta_d, w_g / d_th, w_d, heading);
    return 0;
}

int eq4_final_heading_fgm(ifgm_real theta_g, ifgm_real theta_d, ifgm_real alpha,
                          ifgm_real beta, ifgm_real d_min, ifgm_real heading, ifgm_real *out)
{
    if (!isfinite(theta_g) || !isfinite(theta_d) || !isfinite(heading) ||
        !weights_ok(alpha, beta, d_min))
        return IFGM_EQ_UNDEFINED;
    *out = robot_frame_mean(theta_g, theta_d, alpha / d_min, beta, heading);
    return 0;
}
