/* The boundary followers: see boundary.h. */
#include "boundary.h"

#include "equations.h"

const char IFGM_MOVE_TO_GOAL[] = "move_to_goal";
const char IFGM_OBSTACLE_AVOIDANCE[] = "obstacle_avoidance";
const char IFGM_GOAL_UNREACHABLE[] = "goal_unreachable";

/* Largest correction of the tangent heading towards or away from the edge. */
#define MAX_CORRECTION (IFGM_PI / 3)
/* The clearance filter's search step round a blocked heading, and the steps each way. */
#define CLEAR_STEP (IFGM_PI / 12)
#define CLEAR_STEPS 6
/* The goal counts as dead ahead within this angle (freer_side). */
#define GOAL_AHEAD ((ifgm_real)1e-6)

int ifgm_check_capacity(ifgm_rays *rays, const ifgm_episode *e, const ifgm_body *body)
{
    if (e->rays > IFGM_MAX_RAYS)
        return IFGM_TOO_MANY_RAYS;
    ifgm_real scans = floor(body->tuning.memory_horizon / e->dt) + 2;
    if (scans > IFGM_MAX_SCANS || scans * e->rays > IFGM_MAX_POINTS)
        return IFGM_MEMORY_FULL;
    rays->n = -1;
    return ifgm_rays_for(rays, e->angle_min, e->angle_increment, e->rays);
}

void ifgm_follower_reset(ifgm_follower *f)
{
    f->following = 0;
    f->side = IFGM_FOLLOW_RIGHT;
    f->hit.x = f->hit.y = 0;
}

void ifgm_follower_start(ifgm_follower *f, const ifgm_real here[3], ifgm_follow_side side)
{
    f->following = 1;
    f->hit.x = here[0];
    f->hit.y = here[1];
    f->side = side;
}

int ifgm_follow_heading(const ifgm_follower *f, const ifgm_sight *s, ifgm_real *heading)
{
    int i = ifgm_nearest_point(s->x, s->y, s->n, s->pose[0], s->pose[1]);
    if (i < 0)
        return 0;
    ifgm_real dx = s->x[i] - s->pose[0], dy = s->y[i] - s->pose[1];
    ifgm_real to_edge = atan2(dy, dx);
    ifgm_real correction = (1 / s->body->radius) * (sqrt(dx * dx + dy * dy) - s->body->standoff);
    if (correction > MAX_CORRECTION)
        correction = MAX_CORRECTION;
    if (correction < -MAX_CORRECTION)
        correction = -MAX_CORRECTION;
    /* Edge on the right: the tangent is the direction to the edge turned left by 90 deg. */
    *heading = ifgm_wrap_angle(to_edge - f->side * (IFGM_PI / 2 - correction));
    return 1;
}

ifgm_real ifgm_turn_speed(ifgm_real error, ifgm_real speed)
{
    ifgm_real c = cos(error);
    return speed * (c > 0 ? c : 0);
}

ifgm_command ifgm_steer(ifgm_real heading, const ifgm_sight *s, const char *behaviour,
                        const char *branch)
{
    ifgm_command c;
    c.heading = heading;
    c.speed = ifgm_turn_speed(ifgm_wrap_angle(heading - s->pose[2]), s->body->speed);
    c.behaviour = behaviour;
    c.branch = branch;
    c.stop = 0;
    return c;
}

ifgm_command ifgm_keep_clear(ifgm_command command, const ifgm_sight *s)
{
    if (command.speed <= 0 || command.stop)
        return command;
    const ifgm_body *b = s->body;
    for (int k = 0; k <= CLEAR_STEPS; k++) {
        for (int sign = 1; sign >= -1; sign -= 2) {
            if (k == 0 && sign < 0)
                break;
            ifgm_real heading = ifgm_wrap_angle(command.heading + (sign * k) * CLEAR_STEP);
            ifgm_real error = ifgm_wrap_angle(heading - s->pose[2]);
            ifgm_real speed = k ? ifgm_turn_speed(error, b->speed) : b->speed;
            if (command.speed < speed)
                speed = command.speed;
            ifgm_real turn = error;
            if (turn > b->turn_limit)
                turn = b->turn_limit;
            if (turn < -b->turn_limit)
                turn = -b->turn_limit;
            ifgm_real free = ifgm_disc_travel(s->x, s->y, s->n, s->pose[0], s->pose[1],
                                              s->pose[2] + turn, b->half_width);
            if (free >= speed * b->dt) {
                if (k == 0)
                    return command;
                command.heading = heading;
                command.speed = speed;
                return command;
            }
        }
    }
    command.speed = 0;
    return command;
}

/* Mean range of one beam, no return counting as range_max and -inf as 0 (beam_openness). */
static ifgm_real beam_openness(const ifgm_real *ranges, int n, ifgm_real range_max,
                               const unsigned char *beam, ifgm_beam which)
{
    ifgm_real sum = 0;
    int count = 0;
    for (int i = 0; i < n; i++) {
        if (beam[i] != which)
            continue;
        ifgm_real r = ranges[i] == IFGM_INF ? range_max : ranges[i];
        sum += r < 0 ? 0 : r;
        count++;
    }
    return count ? sum / count : 0;
}

/* The first ray of the least range (NAN first, as numpy's argmin). */
static int argmin_range(const ifgm_real *ranges, int n)
{
    int best = 0;
    for (int i = 0; i < n; i++) {
        if (isnan(ranges[i]))
            return i;
        if (ranges[i] < ranges[best])
            best = i;
    }
    return best;
}

ifgm_follow_side ifgm_freer_side(const ifgm_real *ranges, int n, ifgm_real range_max,
                                 const ifgm_real *angle, const unsigned char *beam,
                                 const ifgm_real pose[3], ifgm_real bearing)
{
    ifgm_real left = beam_openness(ranges, n, range_max, beam, IFGM_BEAM_LEFT);
    ifgm_real right = beam_openness(ranges, n, range_max, beam, IFGM_BEAM_RIGHT);
    ifgm_real larger = fabs(left) > fabs(right) ? fabs(left) : fabs(right);
    int goes_left;
    ifgm_real relative = ifgm_wrap_angle(bearing - pose[2]);
    if (!(fabs(left - right) <= IFGM_ROUNDING * larger)) /* math.isclose, rel_tol 1e-9 */
        goes_left = left > right;
    else if (fabs(relative) > GOAL_AHEAD)
        goes_left = relative > 0;
    else
        goes_left = angle[argmin_range(ranges, n)] < 0;
    return goes_left ? IFGM_FOLLOW_RIGHT : IFGM_FOLLOW_LEFT;
}

ifgm_real ifgm_free_range(ifgm_sight *s)
{
    if (!ifgm_goal_in_view(s))
        return 0;
    ifgm_real d = s->goal_distance, free = ifgm_goal_free_length(s);
    ifgm_real seen = s->body->tuning.view_range; /* the planner knows nothing beyond it */
    if (free >= d && d <= seen)
        return d;
    ifgm_real room = (free < seen ? free : seen) - s->body->encounter;
    return room > 0 ? room : 0;
}

int ifgm_progress_made(const ifgm_progress *rule, ifgm_sight *s)
{
    ifgm_real reach = s->goal_distance - ifgm_free_range(s);
    return reach <= 0 || reach <= rule->d_min - rule->step_length;
}

int ifgm_free_path_leads_on(const ifgm_progress *rule, ifgm_sight *s)
{
    if (!ifgm_path_free(s))
        return 0;
    ifgm_real free = ifgm_goal_free_length(s), view = s->body->tuning.view_range;
    return s->goal_distance - (free < view ? free : view) <= rule->d_min;
}
