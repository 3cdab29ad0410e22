/* Parameter defaults and domains: see tuning.h. */
#include "tuning.h"

void ifgm_tuning_unset(ifgm_tuning *t)
{
    ifgm_real *fields[] = {&t->standoff_margin, &t->corridor_margin, &t->hit_margin,
                           &t->memory_horizon,  &t->return_radius,   &t->min_loop,
                           &t->view_range,      &t->step_length,     &t->d_th,
                           &t->d_obs,           &t->d_look,          &t->w_g,
                           &t->w_d,             &t->jump,            &t->preempt_margin,
                           &t->turn_done,       &t->alpha,           &t->beta,
                           &t->inflation_margin};
    for (unsigned i = 0; i < sizeof fields / sizeof fields[0]; i++)
        *fields[i] = (ifgm_real)NAN;
}

const char *ifgm_status_text(int status)
{
    switch (status) {
    case IFGM_OK:
        return "ok";
    case IFGM_BAD_EPISODE:
        return "a robot, sensor or episode value is out of its domain (radius, speed, turn "
               "rate, range_max, dt and goal_tolerance must be finite and > 0, rays >= 2; "
               "braking and acceleration > 0, acceleration finite where braking is, "
               "response >= 0)";
    case IFGM_BAD_PARAMETER:
        return "a parameter is out of its domain (each must be a finite number > 0; IFGM's "
               "d_th must exceed the robot's diameter)";
    case IFGM_TOO_MANY_RAYS:
        return "the scan has more rays than IFGM_MAX_RAYS (rebuild with a larger one)";
    case IFGM_NARROW_VIEW:
        return "fewer than two rays lie in the paper's 135-degree view";
    case IFGM_MEMORY_FULL:
        return "memory_horizon / dt scans of this sensor do not fit IFGM_MAX_POINTS or "
               "IFGM_MAX_SCANS (rebuild with larger ones)";
    case IFGM_LONG_RESPONSE:
        return "the robot's response time spans more time steps than IFGM_MAX_EARLIER + 1 "
               "(rebuild with a larger one)";
    default:
        return "unknown status";
    }
}

static int positive(ifgm_real value)
{
    return isfinite(value) && value > 0;
}

/* `*value` = `fallback` if unset; whether the result is in its domain. */
static int resolve(ifgm_real *value, ifgm_real fallback, int zero_allowed)
{
    if (isnan(*value))
        *value = fallback;
    return positive(*value) || (zero_allowed && *value == 0);
}

int ifgm_resolve_tuning(ifgm_tuning *out, const ifgm_episode *e, const ifgm_tuning *given)
{
    ifgm_real r = e->radius, v = e->speed, w = e->max_turn_rate, dt = e->dt;
    ifgm_real range = e->range_max, fov = e->fov;
    if (!positive(r) || !positive(v) || !positive(w) || !positive(dt) || !positive(range) ||
        !positive(fov) || !positive(e->goal_tolerance) || e->rays < 2)
        return IFGM_BAD_EPISODE;
    /* The robot's dynamics (RobotParams): b and A infinite or > 0, b finite only with A
     * finite, the response finite and >= 0, the latency >= 0. */
    if (!(e->braking == IFGM_INF || positive(e->braking)) ||
        !(e->acceleration == IFGM_INF || positive(e->acceleration)) ||
        (e->braking != IFGM_INF && e->acceleration == IFGM_INF) || !isfinite(e->response) ||
        e->response < 0 || e->latency < 0)
        return IFGM_BAD_EPISODE;
    *out = *given;
    ifgm_real standoff = 2 * r / 3, narrow = IFGM_PI * r / (2 * fov);
    int ok = resolve(&out->standoff_margin, standoff > narrow ? standoff : narrow, 0) &
             resolve(&out->corridor_margin, r / 4, 0) & resolve(&out->hit_margin, r / 2, 0) &
             resolve(&out->memory_horizon, 8, 0) & resolve(&out->return_radius, r, 0) &
             resolve(&out->min_loop, 12 * r, 0) &
             resolve(&out->view_range, range < 15 * r ? range : 15 * r, 0) &
             resolve(&out->step_length, 2 * r, 0) & resolve(&out->d_th, 3 * r, 0) &
             resolve(&out->d_obs, r + v / 2, 0) & resolve(&out->d_look, 8 * r, 0) &
             resolve(&out->w_g, 9 * r, 0) & resolve(&out->w_d, 1, 0) &
             resolve(&out->jump, 2 * r, 0) & resolve(&out->preempt_margin, r / 2, 0) &
             resolve(&out->turn_done, w * dt / 2, 0) & resolve(&out->alpha, 8 * r, 1) &
             resolve(&out->beta, 1, 1) & resolve(&out->inflation_margin, r / 2, 1);
    return ok ? IFGM_OK : IFGM_BAD_PARAMETER;
}
