/* The boundary followers: the Bug family's skeleton (section 2.1 of the paper: *move to
 * goal* until an obstacle is met, then *obstacle avoidance* along its edge until a leaving
 * rule holds) with DistBug's and IBA's leaving rules (sections 2.1.3 and 4.1). IFGM
 * (ifgm.h) holds the same parts. The reference is ifgm_ref/planners/{sight,boundary,
 * edge_following,distbug,iba}.py; docs/errata.md rows 20, 22, 24-26, 29-31 give the
 * readings. */
#ifndef IFGM_BOUNDARY_H
#define IFGM_BOUNDARY_H

#include "percepts.h"

/* Behaviours (section 2.1) and the stop reason of a planner that proved the goal
 * unreachable. */
extern const char IFGM_MOVE_TO_GOAL[];        /* "move_to_goal" */
extern const char IFGM_OBSTACLE_AVOIDANCE[];  /* "obstacle_avoidance" */
extern const char IFGM_GOAL_UNREACHABLE[];    /* "goal_unreachable" */

/* Which side of the robot the followed edge is on: +1 left, -1 right (REP-103). */
typedef int ifgm_follow_side;
#define IFGM_FOLLOW_LEFT 1
#define IFGM_FOLLOW_RIGHT (-1)

/* The robot and its episode, fixed at init, with the resolved parameters. */
typedef struct {
    ifgm_point goal;
    ifgm_real radius, speed, fov, range_max, turn_limit, dt;
    ifgm_tuning tuning;
    ifgm_real standoff;   /* radius + standoff_margin: kept from the followed edge */
    ifgm_real half_width; /* radius + corridor_margin: the corridor the robot needs */
    ifgm_real encounter;  /* standoff + hit_margin: an obstacle this near is met */
} ifgm_body;

/* The body of an episode; IFGM_OK or a status (tuning.h). */
int ifgm_body_init(ifgm_body *body, const ifgm_episode *episode, const ifgm_tuning *tuning);

/* One step's sight of the goal: the pose, the remembered points, the goal's bearing and
 * distance, and (worked out at the first question) how far the robot-wide corridor
 * towards the goal is free. */
typedef struct {
    const ifgm_body *body;
    ifgm_real pose[3];
    const ifgm_real *x, *y; /* the remembered points */
    int n;
    ifgm_real bearing, goal_distance;
    ifgm_real free_length; /* NAN until asked */
} ifgm_sight;

void ifgm_sight_init(ifgm_sight *sight, const ifgm_body *body, const ifgm_real pose[3],
                     const ifgm_memory *memory, ifgm_real bearing);
ifgm_real ifgm_goal_free_length(ifgm_sight *sight);
/* An obstacle in the corridor towards the goal nearer than the goal and the encounter
 * distance. */
int ifgm_goal_blocked(ifgm_sight *sight);
/* The goal's bearing lies in the view (at most the paper's 135 degrees), 10 degrees inside
 * its edge (errata row 30). */
int ifgm_goal_in_view(const ifgm_sight *sight);
/* IBA's free path: the goal in view and its corridor clear for view_range or to the goal. */
int ifgm_path_free(ifgm_sight *sight);

/* The edge follower: *obstacle avoidance*, keeping the nearest remembered point at the
 * stand-off on `side` (edge_following.py). */
typedef struct {
    int following;
    ifgm_follow_side side;
    ifgm_point hit, last;
    ifgm_real travelled; /* followed since the hit point */
} ifgm_follower;

void ifgm_follower_reset(ifgm_follower *f, const ifgm_real start[3]);
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
ifgm_command ifgm_guard(ifgm_command command, const ifgm_sight *sight);

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

/* F: how far the robot can move towards the goal, as the sensor tells. */
ifgm_real ifgm_free_range(ifgm_sight *sight);
/* d - F <= 0 or d - F <= d_min - Step. */
int ifgm_progress_made(const ifgm_progress *rule, ifgm_sight *sight);
/* IBA's free path, where following it as far as it is seen free brings the robot as near
 * the goal as it has been. */
int ifgm_free_path_leads_on(const ifgm_progress *rule, ifgm_sight *sight);

/* DistBug and IBA: the skeleton with its rule. */
typedef enum { IFGM_RULE_DISTBUG, IFGM_RULE_IBA } ifgm_rule;

typedef struct {
    ifgm_rule rule;
    ifgm_body body;
    ifgm_progress progress;
    ifgm_follower follower;
    ifgm_rays rays;
    ifgm_scan_points points;
    ifgm_memory memory;
} ifgm_boundary_planner;

typedef ifgm_boundary_planner distbug_planner;
typedef ifgm_boundary_planner iba_planner;

int distbug_init(distbug_planner *p, const ifgm_episode *episode, const ifgm_tuning *tuning);
ifgm_command distbug_step(distbug_planner *p, const ifgm_observation *observation);
int iba_init(iba_planner *p, const ifgm_episode *episode, const ifgm_tuning *tuning);
ifgm_command iba_step(iba_planner *p, const ifgm_observation *observation);

/* Shared by every planner that remembers: check that the sensor fits the build (its rays,
 * and memory_horizon / dt scans of it), and work out its rays. */
int ifgm_check_capacity(ifgm_rays *rays, const ifgm_episode *episode, const ifgm_body *body);

#endif
