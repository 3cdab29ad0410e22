/* The braking governor: every planner's command, slowed so that a robot with mass stops in
 * time (errata row 36). The reference is ifgm_ref/planners/governor.py; each function names
 * the one whose arithmetic it repeats, in the same order, so that the port's commands are the
 * reference's to the last bit or two. docs/port-guide.md, section 6, states the rules.
 *
 * The robot brakes at least at b, speeds up at most at A (length/s^2) and may go on for a
 * response time tau (s) under its last command; a command is let through when, moving for
 * tau towards the last command, then for one period eps (the time step) towards this one,
 * each as hard as allowed, then braking, the robot still stops within the room free in the
 * fan of headings it may face (the present one, the command's, the last command's, and the
 * present one turned on at the last period's rate for the response time, at least a period:
 * a robot braking while it turns may carry its turn past the command), measured in the scan
 * it was handed. The governor keeps the heading as far as the robot's
 * grip allows (a turn of at most b / u eps in a period at speed u) and takes the largest
 * speed up to the planner's that fits, and no more than A eps above its bound on the robot's
 * speed; if none does (not even braking), it brakes along the
 * last command's heading, and standing it may turn. With b infinite (the paper's robot, the
 * default) it returns every command unchanged. Nothing here allocates. */
#ifndef IFGM_GOVERNOR_H
#define IFGM_GOVERNOR_H

#include "types.h"

/* Most commands before the last that the robot may still follow during its response time
 * (GovernorState.earlier): a response time of up to IFGM_MAX_EARLIER + 1 periods. A longer
 * one fails the planner's init (IFGM_LONG_RESPONSE). */
#ifndef IFGM_MAX_EARLIER
#define IFGM_MAX_EARLIER 16
#endif

/* The clearance kept beyond the robot's disc from what lies ahead, in robot radii
 * (Limits.MARGIN: the planners' corridor margin, r / 4). */
#define IFGM_GOVERNOR_MARGIN ((ifgm_real)0.25)

/* What the governor knows of the robot (Limits): its radius r and top speed (a length and a
 * length/s), b and A (length/s^2, +INFINITY: at once), the period eps (the time step, s) and
 * the response time tau (s). */
typedef struct {
    ifgm_real radius, top_speed, braking, acceleration, period, response;
} ifgm_limits;

/* What the governor carries from one step to the next (GovernorState): a bound on the
 * robot's speed (0 at the start), the heading and speed it last let through (no heading and
 * 0 before the first command), for a response time longer than a period, the speeds of the
 * commands before the last that the robot may still follow (oldest first), and the robot's
 * heading (the observed pose's theta) at the last decision (none before the first), from
 * which its present turn is read. */
typedef struct {
    ifgm_real speed_bound;
    int has_heading;
    ifgm_real heading;
    ifgm_real speed;
    int n_earlier;
    ifgm_real earlier[IFGM_MAX_EARLIER];
    int has_theta;
    ifgm_real theta;
} ifgm_governor_state;

/* A planner's governor for one episode (BrakingGovernor): the limits and the state. */
typedef struct {
    ifgm_limits limits;
    ifgm_governor_state state;
} ifgm_governor;

/* The limits of an episode's robot and time step (Limits.of): the response time is the
 * robot's `response` plus its `latency` in steps of dt. */
ifgm_limits ifgm_limits_of(const ifgm_episode *episode);
/* Whether the robot stops at once (b infinite): the governor then does nothing. */
int ifgm_stops_at_once(const ifgm_limits *limits);
/* The state at the start of an episode: at rest, no command yet. */
ifgm_governor_state ifgm_governor_at_rest(void);
/* GovernorState.following: the fastest command the robot may still follow during its
 * response time (the last one's speed, or an earlier one's). */
ifgm_real ifgm_governor_following(const ifgm_governor_state *state);
/* How many commands before the last the robot may still follow: ceil(tau / eps - 1e-9) - 1,
 * at least 0. */
int ifgm_earlier_kept(const ifgm_limits *limits);

/* _ramp: the most a robot at most at `speed` may travel in `duration` towards `target` (up
 * at A, never past it or the top speed; down at b, never below it); *end is the bound on its
 * speed then. */
ifgm_real ifgm_ramp(ifgm_real speed, ifgm_real target, ifgm_real duration,
                    const ifgm_limits *limits, ifgm_real *end);
/* _period: how far the robot may travel before it stands, once its response time is over,
 * from a speed of at most `bound`: one period towards `speed`, then braking at b. */
ifgm_real ifgm_period_distance(ifgm_real bound, ifgm_real speed, const ifgm_limits *limits);
/* stopping_distance: how far the robot may travel before it stands when it is commanded
 * `speed` for one period and then brakes: tau towards the fastest command it may still
 * follow (ifgm_governor_following), then ifgm_period_distance. */
ifgm_real ifgm_stopping_distance(const ifgm_governor_state *state, ifgm_real speed,
                                 const ifgm_limits *limits);
/* _root: the root of a c^2 + p c + q where it rises, at least 0 (0 if q >= 0). */
ifgm_real ifgm_root(ifgm_real a, ifgm_real p, ifgm_real q);
/* safe_speed: the largest speed in [0, top speed] whose stopping distance fits in `room`,
 * in *speed, and 1; 0 (and *speed untouched) when none does, not even braking. */
int ifgm_safe_speed(ifgm_real room, const ifgm_governor_state *state, const ifgm_limits *limits,
                    ifgm_real *speed);

/* fan_room for one robot-frame point (x, y): how far the disc of `radius` may go along any
 * path whose heading stays in [low, high] (robot frame, low <= 0 <= high) before it meets
 * the point, +INFINITY if never. A point ahead (its distance across the fan below `radius`)
 * is kept `radius + margin` away unless it is already within `radius + margin / 2`. */
ifgm_real ifgm_point_room(ifgm_real x, ifgm_real y, ifgm_real low, ifgm_real high,
                          ifgm_real radius, ifgm_real margin);
/* fan_room over the returns of a scan (scan_points: +INFINITY and NAN give no point, -INFINITY
 * a point at range_min): the least room of its points, at least 0; +INFINITY with no point.
 * `cos_a` and `sin_a` are the cosines and sines of the rays' angles, angle_min +
 * angle_increment i, or NULL to compute them here. */
ifgm_real ifgm_fan_room(const ifgm_observation *observation, const ifgm_real *cos_a,
                        const ifgm_real *sin_a, ifgm_real low, ifgm_real high, ifgm_real radius,
                        ifgm_real margin);
/* _fan: the robot-frame headings the robot may face until it stops: the present one (0),
 * `heading`'s (world frame), the state's last heading's, and, when the state holds the
 * robot's heading at the last decision, the turn since then carried on for the response time
 * (at least a period): wrap(theta - state theta) * max(1, tau / eps); least in *low,
 * greatest in *high. */
void ifgm_fan(ifgm_real heading, const ifgm_observation *observation,
              const ifgm_governor_state *state, const ifgm_limits *limits, ifgm_real *low,
              ifgm_real *high);
/* _room: the room the robot of the limits' radius has to stop in when it turns towards
 * `heading`, keeping `margin` more: the fan's, and no farther than range_max - radius -
 * margin (at least 0). `cos_a`, `sin_a` as for ifgm_fan_room. */
ifgm_real ifgm_governor_room(ifgm_real heading, const ifgm_observation *observation,
                             const ifgm_governor_state *state, const ifgm_limits *limits,
                             ifgm_real margin, const ifgm_real *cos_a, const ifgm_real *sin_a);
/* next_state: the state one period after `state` when `heading` and `speed` were let
 * through with the robot at heading *theta (the observed pose's theta; NULL: none, as
 * next_state's theta=None). */
ifgm_governor_state ifgm_governor_next(const ifgm_governor_state *state, ifgm_real heading,
                                       ifgm_real speed, const ifgm_limits *limits,
                                       const ifgm_real *theta);

/* _within_grip: `heading`, or the nearest one (world frame) a robot at `bound` facing `theta`
 * can turn to in a period without asking its tyres for more sideways than b: a turn of at most
 * b / bound * eps (u w <= b). */
ifgm_real ifgm_within_grip(ifgm_real heading, ifgm_real theta, ifgm_real bound,
                           const ifgm_limits *limits);

/* Start an episode (BrakingGovernor.reset): the robot's limits, at rest. IFGM_OK, or
 * IFGM_LONG_RESPONSE if the response time spans more commands than IFGM_MAX_EARLIER + 1. */
int ifgm_governor_reset(ifgm_governor *governor, const ifgm_episode *episode);
/* govern: `command` as the robot may carry it out and stop in time, and the state moved on.
 * A robot that stops at once, and a command that stops the episode, pass unchanged (the
 * state too). `cos_a`, `sin_a` as for ifgm_fan_room. */
ifgm_command ifgm_govern(ifgm_governor *governor, ifgm_command command,
                         const ifgm_observation *observation, const ifgm_real *cos_a,
                         const ifgm_real *sin_a);

#endif
