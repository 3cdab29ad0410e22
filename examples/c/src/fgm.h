/* Follow the Gap Method (FGM): steer through the middle of the widest free gap, towards the goal.
 *
 * V. Sezer and M. Gokasan, "A novel obstacle avoidance algorithm: 'Follow the Gap Method'",
 * Robotics and Autonomous Systems 60(9):1123-1134, 2012, as the IFGM paper (Zohaib et al.,
 * Studies in Informatics and Control 23(1):97-106, 2014) summarises it in section 2.2. The
 * reference is ifgm_ref/planners/fgm.py: this port takes the same decisions by the same
 * arithmetic (the same branch, behaviour, heading and speed), so that the two agree to
 * rounding. FGM is local: it keeps nothing from one scan to the next.
 *
 * At each step every return is an obstacle disc of radius r_inf = radius + inflation_margin;
 * a disc at range d blocks the rays within asin(min(1, r_inf / d)) of its own ray. The runs
 * of free rays are the gaps; the maximum gap is the one with the most rays (ties: the centre
 * nearer the goal, to 1e-9 rad, then the rightmost). Its centre angle (equations.h,
 * fgm_gap_centre_angle; the bisector for a gap wider than pi) and the goal angle are weighed
 * by alpha / d_min and beta (eq4_final_heading_fgm), d_min the nearest return's range.
 *
 *   branch         when                     heading           speed          behaviour
 *   no_obstacle    no return in the scan    the goal          turn_speed     move_to_goal
 *   max_gap        some free ray            the weighed mean  turn_speed     obstacle_avoidance
 *   no_gap         every ray blocked        the goal          0              obstacle_avoidance
 *
 * turn_speed is ifgm_ref.planners.edge_following.turn_speed: speed * max(0, cos(turn)), the
 * turn being the heading relative to the robot's.
 *
 * Parameters (ifgm_tuning; NAN takes the default; docs/parameters.md), each finite and >= 0,
 * alpha and beta not both 0:
 *   alpha             gap weight, a length, default 8 r
 *   beta              goal weight, a number, default 1
 *   inflation_margin  space kept between the robot's disc and a return, default r / 2
 *
 * Where the reference raises (a gap border at range 0, or a gap exactly pi wide with equal
 * border ranges: its centre is undefined), this port steers through the gap's bisector. */
#ifndef IFGM_FGM_H
#define IFGM_FGM_H

#include "governor.h"
#include "types.h"

typedef struct {
    ifgm_real speed;     /* the robot's top speed, length/s */
    ifgm_real alpha;     /* gap weight, length */
    ifgm_real beta;      /* goal weight */
    ifgm_real inflation; /* radius of every inflated return: radius + inflation_margin */
    ifgm_governor governor; /* the braking governor (governor.h) */
    /* Scratch of one step: the range of the nearest return blocking each ray, +INFINITY
     * where the ray is free. Here rather than on the stack, which it would fill. */
    ifgm_real blocking[IFGM_MAX_RAYS];
} fgm_planner;

/* Set up `planner` for an episode: IFGM_OK, or IFGM_BAD_EPISODE, IFGM_BAD_PARAMETER
 * (ifgm_resolve_tuning, tuning.h; alpha and beta both 0) or IFGM_TOO_MANY_RAYS. */
int fgm_init(fgm_planner *planner, const ifgm_episode *episode, const ifgm_tuning *tuning);

/* Decide one step, then stop in time (the braking governor, governor.h). */
ifgm_command fgm_step(fgm_planner *planner, const ifgm_observation *observation);

#endif
