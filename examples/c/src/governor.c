/* The braking governor: see governor.h. Each function names the function of
 * ifgm_ref/planners/governor.py whose arithmetic it repeats. Python's min(a, b) and max(a, b)
 * keep the first of equals (py_min, py_max); numpy's minimum and maximum are the same here,
 * where nothing is NAN; Python's x**2 is pow(x, 2), numpy's array ** 2 is x * x. */
#include "governor.h"

#include <stddef.h>

#include "equations.h"

static ifgm_real py_min(ifgm_real a, ifgm_real b)
{
    return b < a ? b : a;
}

static ifgm_real py_max(ifgm_real a, ifgm_real b)
{
    return b > a ? b : a;
}

/* numpy's float remainder (np.mod) by b > 0: the sign of the divisor, +0.0 for a zero. */
static ifgm_real np_mod(ifgm_real a, ifgm_real b)
{
    ifgm_real m = fmod(a, b);
    if (m != 0) {
        if (m < 0)
            m += b;
    } else {
        m = 0;
    }
    return m;
}

ifgm_limits ifgm_limits_of(const ifgm_episode *e)
{
    ifgm_limits limits;
    limits.radius = e->radius;
    limits.top_speed = e->speed;
    limits.braking = e->braking;
    limits.acceleration = e->acceleration;
    limits.period = e->dt;
    limits.response = e->response + (ifgm_real)e->latency * e->dt;
    return limits;
}

int ifgm_stops_at_once(const ifgm_limits *limits)
{
    return limits->braking == IFGM_INF;
}

ifgm_governor_state ifgm_governor_at_rest(void)
{
    ifgm_governor_state state;
    state.speed_bound = 0;
    state.has_heading = 0;
    state.heading = 0;
    state.speed = 0;
    state.n_earlier = 0;
    state.has_theta = 0;
    state.theta = 0;
    return state;
}

ifgm_real ifgm_governor_following(const ifgm_governor_state *state)
{
    ifgm_real fastest = state->speed; /* max(speed, *earlier): the first of equals */
    for (int k = 0; k < state->n_earlier; k++)
        fastest = py_max(fastest, state->earlier[k]);
    return fastest;
}

int ifgm_earlier_kept(const ifgm_limits *limits)
{
    const ifgm_real periods = ceil(limits->response / limits->period - (ifgm_real)1e-9);
    return periods > IFGM_MAX_EARLIER + 1 ? IFGM_MAX_EARLIER + 1
           : periods > 1                  ? (int)periods - 1
                                          : 0;
}

ifgm_real ifgm_ramp(ifgm_real speed, ifgm_real target, ifgm_real duration,
                    const ifgm_limits *limits, ifgm_real *end)
{
    target = py_min(target, limits->top_speed);
    const ifgm_real rate = target >= speed ? limits->acceleration : -limits->braking;
    const ifgm_real ramp = target != speed ? py_min(duration, (target - speed) / rate) : 0;
    *end = speed + rate * ramp;
    return speed * ramp + rate * pow(ramp, (ifgm_real)2) / 2 + *end * (duration - ramp);
}

ifgm_real ifgm_period_distance(ifgm_real bound, ifgm_real speed, const ifgm_limits *limits)
{
    ifgm_real end;
    const ifgm_real travel = ifgm_ramp(bound, speed, limits->period, limits, &end);
    return travel + pow(end, (ifgm_real)2) / (2 * limits->braking);
}

ifgm_real ifgm_stopping_distance(const ifgm_governor_state *state, ifgm_real speed,
                                 const ifgm_limits *limits)
{
    ifgm_real bound;
    const ifgm_real late = ifgm_ramp(state->speed_bound, ifgm_governor_following(state),
                                     limits->response, limits, &bound);
    return late + ifgm_period_distance(bound, speed, limits);
}

ifgm_real ifgm_root(ifgm_real a, ifgm_real p, ifgm_real q)
{
    if (q >= 0)
        return 0;
    const ifgm_real s = sqrt(p * p - 4 * a * q);
    return py_max(0, p > 0 ? -2 * q / (p + s) : (s - p) / (2 * a));
}

int ifgm_safe_speed(ifgm_real room, const ifgm_governor_state *state, const ifgm_limits *limits,
                    ifgm_real *speed)
{
    const ifgm_real top = limits->top_speed, b = limits->braking, a = limits->acceleration,
                    eps = limits->period;
    ifgm_real bound;
    const ifgm_real late = ifgm_ramp(state->speed_bound, ifgm_governor_following(state),
                                     limits->response, limits, &bound);
    room -= late;
    if (ifgm_period_distance(bound, top, limits) <= room) {
        *speed = top;
        return 1;
    }
    if (ifgm_period_distance(bound, bound, limits) <= room) { /* speed up to c < bound + A eps */
        /* c eps - (c - u)^2/(2A) + c^2/(2b) = room */
        *speed = ifgm_root((1 / b - 1 / a) / 2, eps + bound / a,
                           -pow(bound, (ifgm_real)2) / (2 * a) - room);
        return 1;
    }
    const ifgm_real low = py_max(0, bound - b * eps);
    if (ifgm_period_distance(bound, low, limits) > room)
        return 0;
    /* slow to c > bound - b eps: u^2/(2b) + c eps - c (u - c)/b = room */
    *speed = ifgm_root(1 / b, eps - bound / b, pow(bound, (ifgm_real)2) / (2 * b) - room);
    return 1;
}

ifgm_real ifgm_point_room(ifgm_real x, ifgm_real y, ifgm_real low, ifgm_real high,
                          ifgm_real radius, ifgm_real margin)
{
    const ifgm_real half_pi = IFGM_PI / 2, two_pi = 2 * IFGM_PI;
    const ifgm_real rho = hypot(x, y);
    ifgm_real delta = 0; /* the angle from the fan to the point */
    if (!(high - low >= IFGM_PI)) {
        const ifgm_real phi = atan2(y, x);
        const ifgm_real past_high = np_mod(phi - high, two_pi);
        const ifgm_real before_low = np_mod(low - phi, two_pi);
        const int inside = phi >= low && phi <= high;
        delta = inside ? 0 : py_min(past_high, before_low);
    }
    const ifgm_real across = rho * sin(py_min(delta, half_pi));
    const ifgm_real along = rho * cos(delta);
    const int ahead = across < radius && rho >= radius + margin / 2;
    const ifgm_real kept = ahead ? radius + margin : radius;
    const ifgm_real reach = sqrt(py_max(kept * kept - across * across, 0));
    const int met = delta < half_pi && across < kept;
    return met ? along - reach : (rho < kept ? 0 : IFGM_INF);
}

ifgm_real ifgm_fan_room(const ifgm_observation *o, const ifgm_real *cos_a,
                        const ifgm_real *sin_a, ifgm_real low, ifgm_real high, ifgm_real radius,
                        ifgm_real margin)
{
    ifgm_real room = IFGM_INF;
    for (int i = 0; i < o->n; i++) {
        ifgm_real r = o->ranges[i];
        if (r == -IFGM_INF)
            r = o->range_min;
        if (!isfinite(r))
            continue; /* no return, or a sensor error */
        ifgm_real c, s;
        if (cos_a != NULL && sin_a != NULL) {
            c = cos_a[i];
            s = sin_a[i];
        } else {
            const ifgm_real angle = o->angle_min + o->angle_increment * (ifgm_real)i;
            c = cos(angle);
            s = sin(angle);
        }
        const ifgm_real here = ifgm_point_room(r * c, r * s, low, high, radius, margin);
        if (here < room)
            room = here;
    }
    return py_max(0, room);
}

void ifgm_fan(ifgm_real heading, const ifgm_observation *o, const ifgm_governor_state *state,
              const ifgm_limits *limits, ifgm_real *low, ifgm_real *high)
{
    const ifgm_real theta = o->pose[2];
    ifgm_real turns[4];
    int n = 0;
    turns[n++] = 0;
    turns[n++] = ifgm_wrap_angle(heading - theta);
    if (state->has_heading)
        turns[n++] = ifgm_wrap_angle(state->heading - theta);
    if (state->has_theta) { /* the present turn, carried on for tau (at least a period) */
        const ifgm_real carried = py_max(1, limits->response / limits->period);
        turns[n++] = ifgm_wrap_angle(theta - state->theta) * carried;
    }
    *low = *high = turns[0];
    for (int k = 1; k < n; k++) {
        *low = py_min(*low, turns[k]);
        *high = py_max(*high, turns[k]);
    }
}

ifgm_real ifgm_governor_room(ifgm_real heading, const ifgm_observation *o,
                             const ifgm_governor_state *state, const ifgm_limits *limits,
                             ifgm_real margin, const ifgm_real *cos_a, const ifgm_real *sin_a)
{
    ifgm_real low, high;
    ifgm_fan(heading, o, state, limits, &low, &high);
    const ifgm_real radius = limits->radius;
    const ifgm_real room = ifgm_fan_room(o, cos_a, sin_a, low, high, radius, margin);
    return py_min(room, py_max(0, o->range_max - radius - margin));
}

ifgm_governor_state ifgm_governor_next(const ifgm_governor_state *state, ifgm_real heading,
                                       ifgm_real speed, const ifgm_limits *limits,
                                       const ifgm_real *theta)
{
    const ifgm_real eps = limits->period;
    const ifgm_real tau = py_min(limits->response, eps);
    ifgm_real bound, next_bound;
    ifgm_ramp(state->speed_bound, ifgm_governor_following(state), tau, limits, &bound);
    ifgm_ramp(bound, speed, eps - tau, limits, &next_bound);
    ifgm_governor_state next;
    next.speed_bound = next_bound;
    next.has_heading = 1;
    next.heading = heading;
    next.speed = py_min(speed, limits->top_speed);
    /* the last `kept` of the earlier speeds and the last command's (older ones still in
     * effect); ifgm_governor_reset made sure they fit */
    const int kept = ifgm_earlier_kept(limits);
    const int from = state->n_earlier + 1 > kept ? state->n_earlier + 1 - kept : 0;
    next.n_earlier = 0;
    for (int k = from; k < state->n_earlier; k++)
        next.earlier[next.n_earlier++] = state->earlier[k];
    if (kept > 0)
        next.earlier[next.n_earlier++] = state->speed;
    next.has_theta = theta != NULL;
    next.theta = theta != NULL ? *theta : 0;
    return next;
}

ifgm_real ifgm_within_grip(ifgm_real heading, ifgm_real theta, ifgm_real bound,
                           const ifgm_limits *limits)
{
    if (bound <= 0)
        return heading;
    const ifgm_real turn = limits->braking / bound * limits->period;
    const ifgm_real error = ifgm_wrap_angle(heading - theta);
    return fabs(error) <= turn ? heading : ifgm_wrap_angle(theta + copysign(turn, error));
}

int ifgm_governor_reset(ifgm_governor *governor, const ifgm_episode *episode)
{
    governor->limits = ifgm_limits_of(episode);
    governor->state = ifgm_governor_at_rest();
    if (!ifgm_stops_at_once(&governor->limits) &&
        ifgm_earlier_kept(&governor->limits) > IFGM_MAX_EARLIER)
        return IFGM_LONG_RESPONSE;
    return IFGM_OK;
}

ifgm_command ifgm_govern(ifgm_governor *governor, ifgm_command command,
                         const ifgm_observation *o, const ifgm_real *cos_a,
                         const ifgm_real *sin_a)
{
    const ifgm_limits *limits = &governor->limits;
    ifgm_governor_state *state = &governor->state;
    if (ifgm_stops_at_once(limits) || command.stop != NULL)
        return command;
    const ifgm_real bound = state->speed_bound;
    ifgm_real heading = ifgm_within_grip(command.heading, o->pose[2], bound, limits);
    ifgm_real speed, allowed;
    const ifgm_real room = ifgm_governor_room(heading, o, state, limits,
                                              limits->radius * IFGM_GOVERNOR_MARGIN, cos_a, sin_a);
    if (ifgm_safe_speed(room, state, limits, &allowed)) {
        /* and no more than A eps above the speed bound: what the robot can reach */
        const ifgm_real reach = bound + limits->acceleration * limits->period;
        speed = py_min(py_min(command.speed, allowed), reach);
    } else { /* brake along the last command's heading, whose fan the stop fits in; turn at rest */
        speed = 0;
        if (ifgm_stopping_distance(state, 0, limits) > 0 && state->has_heading)
            heading = state->heading;
    }
    if (!(heading == command.heading && speed == command.speed)) { /* _with */
        command.heading = heading;
        command.speed = speed;
    }
    *state = ifgm_governor_next(state, heading, speed, limits, &o->pose[2]);
    return command;
}
