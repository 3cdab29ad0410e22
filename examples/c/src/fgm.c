/* Follow the Gap Method: see fgm.h. Each function names the function of
 * ifgm_ref/planners/fgm.py whose arithmetic it repeats. */
#include "fgm.h"

#include <stddef.h>

#include "equations.h"
#include "tuning.h"

/* Smallest d_min in the final heading, length: a return at range 0 (the robot touches it)
 * weighs the gap by alpha / 1e-6 (fgm.py, D_MIN_FLOOR). */
#define D_MIN_FLOOR ((ifgm_real)1e-6)
/* Added to a return's angular half-width, rad, so that a ray exactly on its border is
 * blocked despite rounding (blocked_rays). */
#define BORDER_SLACK ((ifgm_real)1e-12)
/* Two gaps of as many rays tie when their centres are as far from the goal angle once
 * rounded to 1/FGM_TIE_SCALE rad (choose_max_gap rounds to 9 decimals). A float angle
 * carries some 1e-7 rad of rounding, so the float build rounds to 1e-5 rad. */
#ifdef IFGM_FLOAT
#define FGM_TIE_SCALE ((ifgm_real)1e5)
#else
#define FGM_TIE_SCALE ((ifgm_real)1e9)
#endif

static const char MOVE_TO_GOAL[] = "move_to_goal";
static const char OBSTACLE_AVOIDANCE[] = "obstacle_avoidance";
static const char NO_OBSTACLE[] = "no_obstacle";
static const char MAX_GAP[] = "max_gap";
static const char NO_GAP[] = "no_gap";

int fgm_init(fgm_planner *planner, const ifgm_episode *episode, const ifgm_tuning *tuning)
{
    ifgm_tuning t;
    int status = ifgm_resolve_tuning(&t, episode, tuning); /* FGMParams.for_episode */
    if (status != IFGM_OK)
        return status;
    if (episode->rays > IFGM_MAX_RAYS)
        return IFGM_TOO_MANY_RAYS;
    if (t.alpha == 0 && t.beta == 0)
        return IFGM_BAD_PARAMETER;
    planner->speed = episode->speed;
    planner->alpha = t.alpha;
    planner->beta = t.beta;
    planner->inflation = episode->radius + t.inflation_margin; /* FGMPlanner.inflation */
    if (!isfinite(planner->inflation))
        return IFGM_BAD_PARAMETER;
    return ifgm_governor_reset(&planner->governor, episode);
}

/* Robot-frame angle of ray i (LaserScan.angles). */
static ifgm_real ray_angle(const ifgm_observation *o, int i)
{
    return o->angle_min + o->angle_increment * (ifgm_real)i;
}

/* Range of the return of ray i: -INFINITY (nearer than range_min, REP 117) is read as
 * range_min; +INFINITY and NAN are no return (scan_points). */
static ifgm_real return_range(const ifgm_observation *o, int i)
{
    const ifgm_real r = o->ranges[i];
    return r == -IFGM_INF ? o->range_min : r;
}

static int within(const ifgm_observation *o, int j, ifgm_real angle, ifgm_real reach)
{
    return fabs(ray_angle(o, j) - angle) <= reach;
}

/* blocked_rays: set blocking[j] to the range of the nearest return whose inflated disc
 * covers ray j (+INFINITY if none); return the nearest return's range (d_min), +INFINITY
 * if there is none. The reference tests every return against every ray; this walks away
 * from each return's ray both ways and stops at the first ray out of reach, which finds the
 * same rays: |angle_j - angle_i| never falls as j moves away from i, rounding included. */
static ifgm_real block_rays(fgm_planner *p, const ifgm_observation *o)
{
    ifgm_real *blocking = p->blocking;
    ifgm_real d_min = IFGM_INF;
    for (int j = 0; j < o->n; j++)
        blocking[j] = IFGM_INF;
    for (int i = 0; i < o->n; i++) {
        const ifgm_real d = return_range(o, i);
        if (!isfinite(d))
            continue;
        if (d < d_min)
            d_min = d;
        const ifgm_real ratio = d > 0 ? p->inflation / d : 1; /* inside the disc: pi/2 */
        const ifgm_real reach = asin(ratio < 1 ? ratio : 1) + BORDER_SLACK;
        const ifgm_real angle = ray_angle(o, i);
        for (int j = i; j >= 0 && within(o, j, angle, reach); j--)
            blocking[j] = d < blocking[j] ? d : blocking[j];
        for (int j = i + 1; j < o->n && within(o, j, angle, reach); j++)
            blocking[j] = d < blocking[j] ? d : blocking[j];
    }
    return d_min;
}

/* RayGap.centre of the free rays first..last: FGM's gap centre angle from the border
 * returns (range_max where the gap reaches the edge of the view), or the bisector for a gap
 * wider than pi and where that angle is undefined (fgm.h). */
static ifgm_real gap_centre(const fgm_planner *p, const ifgm_observation *o, int first,
                            int last)
{
    const ifgm_real right = ray_angle(o, first), left = ray_angle(o, last);
    const ifgm_real right_d = first > 0 ? p->blocking[first - 1] : o->range_max;
    const ifgm_real left_d = last < o->n - 1 ? p->blocking[last + 1] : o->range_max;
    ifgm_real centre;
    if (left - right > IFGM_PI || fgm_gap_centre_angle(right_d, -right, left_d, left, &centre))
        centre = (right + left) / 2;
    return centre;
}

/* find_gaps and choose_max_gap: the gaps are the runs of free rays, right to left; the
 * maximum gap has the most rays, then the centre nearest goal_angle (rounded), then is the
 * rightmost. Write its centre and return 1, or return 0 if every ray is blocked. The
 * centre of a gap with fewer rays than the best so far is never needed, nor computed. */
static int max_gap_centre(const fgm_planner *p, const ifgm_observation *o, ifgm_real goal_angle,
                          ifgm_real *centre)
{
    int best_rays = 0;
    ifgm_real best_off = 0;
    int j = 0;
    while (j < o->n) {
        if (p->blocking[j] != IFGM_INF) {
            j++;
            continue;
        }
        const int first = j;
        while (j < o->n && p->blocking[j] == IFGM_INF)
            j++;
        const int rays = j - first;
        if (rays < best_rays)
            continue;
        const ifgm_real c = gap_centre(p, o, first, j - 1);
        const ifgm_real off = round(fabs(ifgm_wrap_angle(c - goal_angle)) * FGM_TIE_SCALE);
        if (rays > best_rays || off < best_off) {
            best_rays = rays;
            best_off = off;
            *centre = c;
        }
    }
    return best_rays > 0;
}

/* edge_following.turn_speed: full speed facing the heading, slowing with the cosine of the
 * turn still to go, turning in place from 90 degrees on. */
static ifgm_real turn_speed(ifgm_real turn, ifgm_real speed)
{
    const ifgm_real c = cos(turn);
    return speed * (c > 0 ? c : 0);
}

/* FGMPlanner.decide and fgm_decide. */
static ifgm_command fgm_decide(fgm_planner *planner, const ifgm_observation *o)
{
    const ifgm_real goal_angle = ifgm_wrap_angle(
        atan2(o->goal[1] - o->pose[1], o->goal[0] - o->pose[0]) - o->pose[2]);
    const ifgm_real d_min = block_rays(planner, o);
    ifgm_command command = {0, 0, OBSTACLE_AVOIDANCE, MAX_GAP, NULL};
    ifgm_real turn = goal_angle; /* the heading in the robot frame */
    ifgm_real centre;
    if (d_min == IFGM_INF) {
        command.behaviour = MOVE_TO_GOAL;
        command.branch = NO_OBSTACLE;
    } else if (!max_gap_centre(planner, o, goal_angle, &centre)) {
        command.branch = NO_GAP;
    } else {
        /* Fails only for a non-finite goal angle (a non-finite pose): turn stays that NAN. */
        eq4_final_heading_fgm(centre, goal_angle, planner->alpha, planner->beta,
                              d_min < D_MIN_FLOOR ? D_MIN_FLOOR : d_min, 0, &turn);
    }
    command.heading = ifgm_wrap_angle(o->pose[2] + turn);
    command.speed = command.branch == NO_GAP ? 0 : turn_speed(turn, planner->speed);
    return command;
}

/* FGMPlanner.step: decide, then stop in time. FGM keeps no ray table: the governor works
 * out the rays' cosines and sines itself, and only for a robot that cannot stop at once. */
ifgm_command fgm_step(fgm_planner *planner, const ifgm_observation *o)
{
    return ifgm_govern(&planner->governor, fgm_decide(planner, o), o, NULL, NULL);
}
