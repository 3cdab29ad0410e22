/* The parts of the boundary followers (section 2.1 of the paper: *move to goal* until an
 * obstacle is met, then *obstacle avoidance* along its edge until a leaving rule holds): the
 * edge follower, the clearance filter, IBA's side choice, and DistBug's and IBA's leaving rules
 * (sections 2.1.3 and 4.1). DistBug and IBA (boundary_planner.h) and IFGM (ifgm.h) are made
 * of them, of the sight of the goal (sight.h) and of Bug1's round (circuit.h). The
 * reference is ifgm_ref/planners/{boundary,edge_following,distbug,iba}.py; docs/errata.md
 * rows 20, 22, 24-26 and 29-31 give the readings. */
#ifndef IFGM_BOUNDARY_H
#define IFGM_BOUNDARY_H

#include "circuit.h"

/* Behaviours (section 2.1) and the stop reason of a planner that proved the goal
 * unreachable. */
extern const char IFGM_MOVE_TO_GOAL[];        /* "move_to_goal" */
extern const char IFGM_OBSTACLE_AVOIDANCE[];  /* "obstacle_avoidance" */
extern const char IFGM_GOAL_UNREACHABLE[];    /* "goal_unreachable" */

/* The edge follower: *obstacle avoidance*, keeping the nearest remembered point at the
 * stand-off on `side` (edge_following.py). */
typedef struct {
    int following;
    ifgm_follow_side side;
    ifgm_point hit;
} ifgm_follower;

void ifgm_follower_reset(ifgm_follower *f);
/* Start following on `side` at the hit point `here`. */
void ifgm_follower_start(ifgm_follower *f, const ifgm_real here[3], ifgm_follow_side side);
/* The heading that follows the nearest remembered edge; 0 if nothing is remembered. */
int ifgm_follow_heading(const ifgm_follower *f, const ifgm_sight *sight, ifgm_real *heading);

/* Forward speed for a turn of `error` rad still to go: speed * max(0, cos(error)). */
ifgm_real ifgm_turn_speed(ifgm_real error, ifgm_real speed);
/* Turn towards `heading`, slowing with the turn still to go. */
ifgm_command ifgm_steer(ifgm_real heading, const ifgm_sight *sight, const char *behaviour,
                        const char *branch);
/* `command`, or the nearest heading to it, in 15-degree steps up to a right angle either
 * side, that does not bring the robot's disc nearer a remembered point than the corridor
 * margin during this step; if none is free, turn in place (errata row 29). */
ifgm_command ifgm_keep_clear(ifgm_command command, const ifgm_sight *sight);

/* IBA's bidirectional side choice (section 4.1; errata row 26): towards the freer of the
 * side beams of the scan (`ranges`, with its rays' `angle` and `beam`); ties to the goal's
 * side, with the goal dead ahead away from the nearest return. A no-return ray counts as
 * `range_max`. Returns the side the obstacle is then kept on. */
ifgm_follow_side ifgm_freer_side(const ifgm_real *ranges, int n, ifgm_real range_max,
                                 const ifgm_real *angle, const unsigned char *beam,
                                 const ifgm_real pose[3], ifgm_real bearing);

/* DistBug's leaving rule (Kamon and Rivlin; errata row 22) and IBA's (errata rows 24, 31):
 * the best distance to the goal so far, and the least progress that counts. */
typedef struct {
    ifgm_real d_min, step_length;
} ifgm_progress;

/* F: how far the robot can move towards the goal, as the sensor tells (DistBugRule.
 * free_range): 0 with the goal out of view; d when its corridor is free up to the goal and
 * the goal lies within view_range, the farthest the planners remember; otherwise
 * min(free length, view_range) - encounter, at least 0. */
ifgm_real ifgm_free_range(ifgm_sight *sight);
/* d - F <= 0 or d - F <= d_min - Step. */
int ifgm_progress_made(const ifgm_progress *rule, ifgm_sight *sight);
/* IBA's free path, where following it as far as it is seen free brings the robot as near
 * the goal as it has been. */
int ifgm_free_path_leads_on(const ifgm_progress *rule, ifgm_sight *sight);

/* Shared by every planner that remembers: check that the sensor fits the build (its rays,
 * and memory_horizon / dt scans of it), and work out its rays. */
int ifgm_check_capacity(ifgm_rays *rays, const ifgm_episode *episode, const ifgm_body *body);

#endif
