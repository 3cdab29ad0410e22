/* What every planner of the port is given and answers: the JSON-lines protocol's `reset`,
 * `observe` and `command` messages (docs/oracle-protocol.md) as C structs.
 *
 * Units: one consistent length unit (feet in the paper's worlds), seconds, radians. Frames
 * follow REP-103: world angles counter-clockwise from +x; scan angles in the robot frame,
 * positive to the left. Nothing here allocates: every array has a compile-time size. */
#ifndef IFGM_TYPES_H
#define IFGM_TYPES_H

#include "real.h"

/* Most rays one scan may have (the paper's sensor has 76; a 270-degree LiDAR about 1081). */
#ifndef IFGM_MAX_RAYS
#define IFGM_MAX_RAYS 1100
#endif

/* A planner's settings: the `reset` message. */
typedef struct {
    ifgm_real radius;        /* robot radius, length */
    ifgm_real speed;         /* top speed, length/s */
    ifgm_real max_turn_rate; /* rad/s */
    /* The robot's dynamics, optional in `reset.robot` (the braking governor, governor.h): its
     * guaranteed braking b and largest acceleration A, length/s^2 (+INFINITY, the default:
     * at once, the paper's robot; b finite needs A finite), its response time, s (default
     * 0), and its latency, whole steps of dt (default 0), which adds to the response. */
    ifgm_real braking, acceleration, response;
    int latency;
    ifgm_real fov;           /* sensor field of view, rad */
    int rays;                /* rays per scan, both ends of the field of view included */
    ifgm_real range_min, range_max;
    ifgm_real angle_min, angle_increment; /* of ray 0, and between rays, rad */
    ifgm_real dt;                         /* time step, s */
    ifgm_real goal_tolerance;             /* length */
    ifgm_real goal[2];                    /* world frame */
    ifgm_real start[3];                   /* x, y, theta */
} ifgm_episode;

/* The planners' parameters by their protocol names (`reset.params`; docs/parameters.md).
 * A field left NAN (ifgm_tuning_unset) takes its default, a formula in the robot and the
 * sensor. */
typedef struct {
    /* boundary followers: Bug family, DistBug, IBA, IFGM */
    ifgm_real standoff_margin, corridor_margin, hit_margin, memory_horizon, return_radius,
        min_loop, view_range;
    ifgm_real step_length; /* DistBug, IBA, IFGM */
    /* IFGM */
    ifgm_real d_th, d_obs, d_look, w_g, w_d, jump, preempt_margin, turn_done;
    /* FGM */
    ifgm_real alpha, beta, inflation_margin;
} ifgm_tuning;

/* One step: the `observe` message. A range of +INFINITY is no return within range_max
 * (JSON null); -INFINITY a return nearer than range_min (REP 117); NAN a sensor error. */
typedef struct {
    ifgm_real t;
    ifgm_real pose[3]; /* x, y, theta (world frame) */
    ifgm_real goal[2];
    ifgm_real angle_min, angle_increment, range_min, range_max;
    int n; /* number of ranges */
    ifgm_real ranges[IFGM_MAX_RAYS];
} ifgm_observation;

/* The decision: the `command` message. The strings are static; NULL means absent. */
typedef struct {
    ifgm_real heading; /* world frame, rad */
    ifgm_real speed;   /* in [0, robot speed] */
    const char *behaviour;
    const char *branch;
    const char *stop;
} ifgm_command;

/* Status of an init: 0, or one of these (ifgm_status_text names it). */
enum {
    IFGM_OK = 0,
    IFGM_BAD_EPISODE = -1,   /* a robot or sensor value out of its domain */
    IFGM_BAD_PARAMETER = -2, /* a parameter out of its domain (d_th <= 2 r, weights, ...) */
    IFGM_TOO_MANY_RAYS = -3, /* more rays than IFGM_MAX_RAYS */
    IFGM_NARROW_VIEW = -4,   /* fewer than two rays in the paper's 135-degree view */
    IFGM_MEMORY_FULL = -5,   /* the remembered scans would not fit IFGM_MAX_POINTS */
    IFGM_LONG_RESPONSE = -6  /* the response time spans more than IFGM_MAX_EARLIER + 1 steps */
};

/* Every parameter unset: each takes its default at init. */
void ifgm_tuning_unset(ifgm_tuning *tuning);

/* A sentence naming a status. */
const char *ifgm_status_text(int status);

#endif
