/* The robot and its sight of the goal: what every boundary follower asks of one step (the
 * reference is ifgm_ref/planners/sight.py; docs/errata.md rows 20, 30 and 34 give the
 * readings). Body holds the robot and its episode, fixed at init; sight, one step's pose,
 * the remembered points and the goal's bearing, each question about them answered once. */
#ifndef IFGM_SIGHT_H
#define IFGM_SIGHT_H

#include "percepts.h"

/* Which side of the robot a followed edge is on: +1 left, -1 right (REP-103;
 * edge_following.FollowSide). */
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
/* The nearest remembered point lies ahead on the way to the goal: on the goal's side of
 * the line through the robot square to the goal's bearing (abeam is not ahead; with
 * nothing remembered, nothing is). */
int ifgm_nearest_ahead(const ifgm_sight *sight);
/* The robot's corridor-wide disc can move one step of travel (speed * dt) straight towards
 * the goal. */
int ifgm_goal_approachable(const ifgm_sight *sight);
/* The robot meets an obstacle here: one blocks the corridor towards the goal, and it is the
 * one the follower would follow (the nearest point lies ahead) or the robot cannot move
 * towards the goal at all. Not while the nearest obstacle is behind or abeam: the one just
 * left, with another in the way (errata row 34). */
int ifgm_meets_obstacle(ifgm_sight *sight);
/* The goal's bearing lies in the view (at most the paper's 135 degrees), 10 degrees inside
 * its edge (errata row 30). */
int ifgm_goal_in_view(const ifgm_sight *sight);
/* IBA's free path: the goal in view and its corridor clear for view_range or to the goal. */
int ifgm_path_free(ifgm_sight *sight);

#endif
