/* IFGM, the Intelligent Follow the Gap Method (section 4 and Figure 3 of the paper), in C99
 * with no heap: the caller owns the planner struct (1.3 MB in the default build, 83 KiB in a
 * float build sized for the paper's sensor, most of it the remembered points and Bug1's
 * trail, circuit.h: keep it in static storage).
 *
 *     static ifgm_planner planner;
 *     if (ifgm_init(&planner, &episode, &tuning) != IFGM_OK) ...   // at every reset
 *     ifgm_command command = ifgm_step(&planner, &observation);    // every dt
 *
 * Written from docs/flowchart.md (the reconstructed Figure 3: percepts, atoms, branches),
 * docs/errata.md (the readings) and docs/parameters.md (the defaults) and, where they were
 * silent, the reference (ifgm_ref/planners/ifgm/planner.py, ifgm_atoms.py): docs/port-guide.md now
 * states every rule a step needs.
 *
 * The paper calls IFGM computationally inexpensive and simpler than FGM (sections 3, 6):
 * benchmarks/bench_c.py measures this port's cost against FGM's (fgm.h), docs/benchmark.md.
 * paper: s3.cheap s6.simpler_than_fgm */
#ifndef IFGM_IFGM_H
#define IFGM_IFGM_H

#include "boundary.h"
#include "governor.h"

/* Deepest Case-3 recursion kept: beyond it the oldest pre-empted obstacle is forgotten. */
#ifndef IFGM_MAX_STACK
#define IFGM_MAX_STACK 32
#endif

/* What IFGM is doing between two steps (Mode). */
typedef enum {
    IFGM_MODE_MOVE_TO_GOAL, /* on the reference path, eq. (3) */
    IFGM_MODE_THROUGH_GAP,  /* Case-1: through the gap, eqs. (1)-(4) */
    IFGM_MODE_FOLLOWING,    /* Case-2, too close, Case-3: IBA follows an edge */
    IFGM_MODE_DEAD_END_TURN, /* turning in place in 45-degree steps */
    IFGM_MODE_ESCAPING       /* driving out of the dead end the way found free */
} ifgm_mode;

/* Figure 3's branches, as they appear in the `branch` of a command (Branch). */
typedef enum {
    IFGM_GOAL_REACHED,
    IFGM_MOVE_TO_GOAL_BRANCH,
    IFGM_CASE1_GAP,
    IFGM_CASE2_NARROW_GAP,
    IFGM_CASE2_ONE_SIDED,
    IFGM_TOO_CLOSE,
    IFGM_CASE3_PREEMPT,
    IFGM_FOLLOW_EDGE,
    IFGM_DEAD_END_TURN,
    IFGM_PATH_REGENERATED,
    IFGM_DEAD_END_ESCAPE,   /* the dead end's later phases: labels of commands, never decided */
    IFGM_DEAD_END_HANDOVER,
    IFGM_BRANCHES
} ifgm_branch;

/* The branch's name ("case1_gap", ...). */
const char *ifgm_branch_name(ifgm_branch branch);

/* Everything IFGM carries from one step to the next besides IBA's follower and rule and
 * Bug1's round (IFGMState). A flag says whether each optional point is set. */
typedef struct {
    ifgm_mode mode;
    int has_turn; /* a dead-end turn: from heading turn_start, turn_steps steps of turn_sign */
    ifgm_real turn_start;
    int turn_sign, turn_steps;
    int has_escape_from; /* where the robot started driving out of the dead end */
    ifgm_point escape_from;
    int walled[2]; /* whether the view's left and right beam have seen a wall (a return within
                      d_look) since the robot started driving out (DeadEndTurn.walled) */
    int has_followed; /* the followed obstacle's point, tracked along its edge */
    ifgm_point followed;
    int stack_n; /* Case-3: the pre-empted obstacles and their sides, last pushed on top */
    ifgm_point stack_point[IFGM_MAX_STACK];
    ifgm_follow_side stack_side[IFGM_MAX_STACK];
    int has_gap_mid; /* the middle of the gap chosen at the last step, if wider than d_th */
    ifgm_point gap_mid;
    int short_look; /* meeting obstacles at IBA's short encounter distance (errata row 24) */
    int escaped;    /* following the wall round from outside after a dead end */
    /* After a round of Bug1's that found no way on (errata row 34): the side the next round
     * follows on, the other one than that round's. */
    int has_turn_other_way;
    ifgm_follow_side turn_other_way;
} ifgm_state;

typedef struct {
    ifgm_body body;
    ifgm_progress iba;
    ifgm_follower follower;
    ifgm_circuit circuit; /* Bug1's round after a whole loop without leaving (errata row 34) */
    ifgm_governor governor; /* the braking governor (governor.h) */
    ifgm_state state;
    ifgm_real goal_tolerance; /* the episode's, plus one step of travel */
    ifgm_branch last_branch;
    /* one step's percepts (scratch, kept here rather than on the stack) */
    ifgm_rays rays;
    ifgm_scan_points points, view_points;
    ifgm_real view_ranges[IFGM_MAX_RAYS]; /* the 135-degree view, view_range deep */
    ifgm_real view_range_max;
    ifgm_cluster clusters[IFGM_MAX_RAYS];
    ifgm_gap gaps[IFGM_MAX_RAYS];
    int n_clusters, n_gaps;
    ifgm_memory memory;
} ifgm_planner;

/* Start an episode: derive and check the parameters (d_th must exceed the robot's
 * diameter, errata row 12), forget everything. IFGM_OK or a status (types.h). */
int ifgm_init(ifgm_planner *planner, const ifgm_episode *episode, const ifgm_tuning *tuning);

/* One decision: perceive, take Figure 3's branch, then never drive into a remembered
 * obstacle (the clearance filter), and stop in time (the braking governor, governor.h). */
ifgm_command ifgm_step(ifgm_planner *planner, const ifgm_observation *observation);

#endif
