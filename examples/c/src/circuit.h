/* Bug1's round of one obstacle: what every boundary follower falls back on after a lap
 * (section 2.1.1 of the paper: "the robot moves around the obstacle completely in order to
 * find the point (leaving point) having minimum distance to destination"; Lumelsky and
 * Stepanov, Algorithmica 2 (1987) 403-430). The reference is ifgm_ref/planners/circuit.py;
 * docs/errata.md row 34 gives the reading. DistBug, IBA and IFGM (boundary_planner.h, ifgm.h)
 * run it beside their own leaving rules:
 *
 * 1. first pass: from the hit point H, lay a trail of the way driven, a point every
 *    return_radius / 2 of travel (the circuit counts the way itself, from the first pose
 *    noted after H), each marked whether it was laid while following an edge; the loop is
 *    closed where the robot, following, passes a point of its trail laid while following
 *    again, within return_radius, heading the same way (within 45 degrees), at least
 *    min_loop further on (of several such points, the earliest). IFGM lays the trail in
 *    every mode: its round spans the edges it leaves by IBA's rules (ifgm.h);
 * 2. on to Q: retrace the trail, the same way round, to the loop's point Q nearest the goal;
 * 3. at Q (within return_radius / 2, every trail point before it passed), leave towards the
 *    goal. The goal cannot be reached if it lies on the obstacle's side of the loop, or if
 *    the robot met this obstacle on leaving the last Q and the loop has no point nearer the
 *    goal than that Q by a step of travel.
 *
 * The trail has a fixed capacity, IFGM_MAX_TRAIL points (the reference's grows without
 * bound). Once it is full no more points are laid: the loop can still close on the points
 * laid, and Q is the nearest of them. The port differs from the reference only on a first
 * pass longer than IFGM_MAX_TRAIL * return_radius / 2 of way driven before its loop closes:
 * 512 ft for the paper's robot (return_radius = r = 1 ft), where the oracle's standard
 * profile laid at most 300 points (IFGM, whose first pass spans its leaves;
 * examples/c/README.md). */
#ifndef IFGM_CIRCUIT_H
#define IFGM_CIRCUIT_H

#include "sight.h"

/* Most trail points laid on one first pass (48 bytes each, 24 in a float build). */
#ifndef IFGM_MAX_TRAIL
#define IFGM_MAX_TRAIL 1024
#endif

/* Where a follower is in Bug1's round of the obstacle it follows (CircuitPhase). */
typedef enum {
    IFGM_CIRCUIT_IDLE,        /* not following: moving to the goal, before any obstacle */
    IFGM_CIRCUIT_FIRST_PASS,  /* from H round the whole obstacle, laying the trail */
    IFGM_CIRCUIT_RETURN_TO_Q, /* the loop closed: retracing the trail to Q */
    IFGM_CIRCUIT_LEFT_AT_Q    /* left at Q towards the goal */
} ifgm_circuit_phase;

/* One point of the trail: the pose there, its distance to the goal, the way driven from
 * the round's start to it, and whether the robot was following an edge there. */
typedef struct {
    ifgm_real x, y, heading, goal_distance, travelled;
    int following;
} ifgm_trail_point;

typedef struct {
    ifgm_circuit_phase phase;
    ifgm_point q_point;   /* Q (NAN until the loop is closed) */
    ifgm_real q_distance; /* d(Q, T) (+inf until the loop is closed) */
    ifgm_real left_q;     /* d(Q, T) of the round before, when the robot left it at Q and met
                             this obstacle next; +inf otherwise */
    ifgm_real travelled;  /* the way driven since the round began (its odometer) */
    int has_last;         /* whether a pose was noted since the round began */
    ifgm_point last;      /* the position last noted */
    int laid;             /* trail points laid */
    int next;             /* on to Q: the trail point steered for */
    int q_index;          /* Q's trail point */
    ifgm_trail_point trail[IFGM_MAX_TRAIL];
} ifgm_circuit;

/* A new episode: no obstacle met yet. */
void ifgm_circuit_reset(ifgm_circuit *circuit);
/* An obstacle met: start the first pass. Met on the way from Q, the round remembers d(Q)
 * in left_q. */
void ifgm_circuit_on_hit(ifgm_circuit *circuit);
/* On the first pass, count the way driven since the last call and lay this step's pose on
 * the trail if it lies the trail's spacing beyond the last point laid and the trail has
 * room; `following`: whether the robot follows an edge here (only such points close a
 * loop). */
void ifgm_circuit_note(ifgm_circuit *circuit, const ifgm_sight *sight, int following);
/* On the first pass, the trail point the robot is back at (see above), or -1. */
int ifgm_circuit_closing(const ifgm_circuit *circuit, const ifgm_sight *sight);
/* Back at trail point `at` after the whole loop, followed with the edge on `side`: take Q
 * and start on to it. Returns whether the goal may yet be reached (see above). */
int ifgm_circuit_close(ifgm_circuit *circuit, const ifgm_sight *sight, int at,
                       ifgm_follow_side side);
/* On the way to Q after a whole loop. */
int ifgm_circuit_returning(const ifgm_circuit *circuit);
/* On to Q: the heading towards the first trail point, not beyond Q, more than return_radius
 * from the robot (the trail points passed are dropped). */
ifgm_real ifgm_circuit_heading_to_q(ifgm_circuit *circuit, const ifgm_sight *sight);
/* The robot, on its way, has come to Q. */
int ifgm_circuit_at_q(const ifgm_circuit *circuit, const ifgm_sight *sight);
/* Left at Q towards the goal. */
void ifgm_circuit_leave(ifgm_circuit *circuit);

/* Whether `goal` lies on the followed obstacle's side of the closed loop of the n trail
 * points `loop`, followed with the edge on `side`: a loop followed with the edge on the
 * right runs clockwise round an obstacle it encloses, anticlockwise inside an enclosure
 * (winding number and signed area; encloses). */
int ifgm_encloses(const ifgm_trail_point *loop, int n, ifgm_point goal, ifgm_follow_side side);

#endif
