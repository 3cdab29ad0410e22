/* DistBug and IBA: the Bug family's skeleton (BoundaryPlanner of
 * ifgm_ref/planners/boundary.py) with DistBug's or IBA's leaving rule (boundary.h), and
 * Bug1's round of the obstacle after a whole loop without leaving (circuit.h). An obstacle
 * is met where one stands in the corridor towards the goal and it is the nearest ahead
 * (ifgm_meets_obstacle, sight.h), not where the one just left is still the nearest
 * (docs/errata.md row 34). Each step ends in the clearance filter, then the braking governor
 * (governor.h). Each is a struct the caller owns, with an init and a step. */
#ifndef IFGM_BOUNDARY_PLANNER_H
#define IFGM_BOUNDARY_PLANNER_H

#include "boundary.h"
#include "governor.h"

/* The skeleton with its rule: DistBug and IBA differ in nothing else. */
typedef enum { IFGM_RULE_DISTBUG, IFGM_RULE_IBA } ifgm_rule;

typedef struct {
    ifgm_rule rule;
    ifgm_body body;
    ifgm_progress progress;
    ifgm_follower follower;
    ifgm_circuit circuit; /* Bug1's round (errata row 34) */
    ifgm_governor governor; /* the braking governor (governor.h) */
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

#endif
