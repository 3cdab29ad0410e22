/* The boundary followers: see boundary.h. */
#include "boundary.h"

#include "equations.h"
#include "tuning.h"

const char IFGM_MOVE_TO_GOAL[] = "move_to_goal";
const char IFGM_OBSTACLE_AVOIDANCE[] = "obstacle_avoidance";
const char IFGM_GOAL_UNREACHABLE[] = "goal_unreachable";

/* The goal counts as in view this far inside the view's edge (Sight.goal_in_view). */
#define IN_VIEW_MARGIN (10 * (IFGM_PI / 180))
/* Largest correction of the tangent heading towards or away from the edge. */
#define MAX_CORRECTION (IFGM_PI / 3)
/* The guard's search step round a blocked heading, and the steps each way. */
#define GUARD_STEP (IFGM_PI / 12)
#define GUARD_STEPS 6
/* The goal counts as dead ahead within this angle (freer_side). */
#define GOAL_AHEAD ((ifgm_real)1e-6)

int ifgm_body_init(ifgm_body *b, const ifgm_episode *e, const ifgm_tuning *given)
{
    int status = ifgm_resolve_tuning(&b->tuning, e, given);
    if (status != IFGM_OK)
        return status;
    b->goal.x = e->goal[0];
    b->goal.y = e->goal[1];
    b->radius = e->radius;
    b->speed = e->speed;
    b->fov = e->fov;
    b->range_max = e->range_max;
    b->turn_limit = e->max_turn_rate * e->dt;
    b->dt = e->dt;
    b->standoff = b->radius + b->tuning.standoff_margin;
    b->half_width = b->radius + b->tuning.corridor_margin;
    b->encounter = b->standoff + b->tuning.hit_margin;
    return IFGM_OK;
}

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

void ifgm_sight_init(ifgm_sight *s, const ifgm_body *body, const ifgm_real pose[3],
                     const ifgm_memory *memory, ifgm_real bearing)
{
    s->body = body;
    s->pose[0] = pose[0];
    s->pose[1] = pose[1];
    s->pose[2] = pose[2];
    s->x = memory->x + memory->start;
    s->y = memory->y + memory->start;
    s->n = memory->end - memory->start;
    s->bearing = bearing;
    s->goal_distance = hypot(body->goal.x - pose[0], body->goal.y - pose[1]);
    s->free_length = (ifgm_real)NAN;
}

ifgm_real ifgm_goal_free_length(ifgm_sight *s)
{
    if (isnan(s->free_length))
        s->free_length = ifgm_free_length(s->x, s->y, s->n, s->pose[0], s->pose[1], s->bearing,
                                          s->body->half_width);
    return s->free_length;
}

int ifgm_goal_blocked(ifgm_sight *s)
{
    ifgm_real reach = s->body->encounter < s->goal_distance ? s->body->encounter
                                                             : s->goal_distance;
    return ifgm_goal_free_length(s) < reach;
}

int ifgm_goal_in_view(const ifgm_sight *s)
{
    ifgm_real half = s->body->fov / 2;
    if (half > IFGM_PAPER_HALF_FOV)
        half = IFGM_PAPER_HALF_FOV;
    return fabs(ifgm_wrap_angle(s->bearing - s->pose[2])) <= half - IN_VIEW_MARGIN;
}

int ifgm_path_free(ifgm_sight *s)
{
    if (!ifgm_goal_in_view(s))
        return 0;
    ifgm_real view = s->body->tuning.view_range;
    ifgm_real needed = view < s->goal_distance ? view : s->goal_distance;
    return ifgm_goal_free_length(s) >= needed;
}

void ifgm_follower_reset(ifgm_follower *f, const ifgm_real start[3])
{
    f->following = 0;
    f->side = IFGM_FOLLOW_RIGHT;
    f->hit.x = f->hit.y = 0;
    f->travelled = 0;
    f->last.x = start[0];
    f->last.y = start[1];
}

void ifgm_follower_start(ifgm_follower *f, const ifgm_real here[3], ifgm_follow_side side)
{
    f->following = 1;
    f->hit.x = here[0];
    f->hit.y = here[1];
    f->travelled = 0;
    f->side = side;
}

/* The robot is at `here`: add the way from the last position while following. */
static void follower_track(ifgm_follower *f, const ifgm_real here[3])
{
    if (f->following)
        f->travelled += hypot(here[0] - f->last.x, here[1] - f->last.y);
    f->last.x = here[0];
    f->last.y = here[1];
}

/* Back at the hit point (within return_radius) after a loop of at least min_loop. */
static int back_at_hit(const ifgm_follower *f, const ifgm_real here[3], const ifgm_tuning *t)
{
    return f->travelled >= t->min_loop &&
           hypot(here[0] - f->hit.x, here[1] - f->hit.y) <= t->return_radius;
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

ifgm_command ifgm_guard(ifgm_command command, const ifgm_sight *s)
{
    if (command.speed <= 0 || command.stop)
        return command;
    const ifgm_body *b = s->body;
    for (int k = 0; k <= GUARD_STEPS; k++) {
        for (int sign = 1; sign >= -1; sign -= 2) {
            if (k == 0 && sign < 0)
                break;
            ifgm_real heading = ifgm_wrap_angle(command.heading + (sign * k) * GUARD_STEP);
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
    ifgm_real range_max = s->body->range_max;
    if (free >= d && d <= range_max)
        return d;
    ifgm_real room = (free < range_max ? free : range_max) - s->body->encounter;
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

static int boundary_init(ifgm_boundary_planner *p, ifgm_rule rule, const ifgm_episode *e,
                         const ifgm_tuning *tuning)
{
    int status = ifgm_body_init(&p->body, e, tuning);
    if (status == IFGM_OK)
        status = ifgm_check_capacity(&p->rays, e, &p->body);
    if (status != IFGM_OK)
        return status;
    p->rule = rule;
    p->progress.d_min = IFGM_INF;
    p->progress.step_length = p->body.tuning.step_length;
    ifgm_follower_reset(&p->follower, e->start);
    ifgm_memory_clear(&p->memory, p->body.tuning.memory_horizon);
    return IFGM_OK;
}

int distbug_init(distbug_planner *p, const ifgm_episode *e, const ifgm_tuning *tuning)
{
    return boundary_init(p, IFGM_RULE_DISTBUG, e, tuning);
}

int iba_init(iba_planner *p, const ifgm_episode *e, const ifgm_tuning *tuning)
{
    return boundary_init(p, IFGM_RULE_IBA, e, tuning);
}

/* Follow the nearest remembered edge; move to goal if the edge is forgotten. */
static ifgm_command follow(ifgm_boundary_planner *p, const ifgm_sight *s, const char *branch)
{
    ifgm_real heading;
    if (!ifgm_follow_heading(&p->follower, s, &heading)) {
        p->follower.following = 0;
        return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, "edge_lost");
    }
    return ifgm_steer(heading, s, IFGM_OBSTACLE_AVOIDANCE, branch);
}

/* Move to goal or follow the edge (BoundaryPlanner.decide). */
static ifgm_command boundary_decide(ifgm_boundary_planner *p, const ifgm_observation *o,
                                    ifgm_sight *s)
{
    ifgm_follower *f = &p->follower;
    ifgm_progress *rule = &p->progress;
    int iba = p->rule == IFGM_RULE_IBA;
    if (!f->following) {
        if (!ifgm_goal_blocked(s))
            return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, "move_to_goal");
        ifgm_follow_side side = iba ? ifgm_freer_side(o->ranges, o->n, o->range_max,
                                                      p->rays.angle, p->rays.beam, s->pose,
                                                      s->bearing)
                                    : IFGM_FOLLOW_RIGHT; /* the Bug family turns left */
        ifgm_follower_start(f, o->pose, side);
        ifgm_real d_hit = hypot(p->body.goal.x - f->hit.x, p->body.goal.y - f->hit.y);
        rule->d_min = (iba && rule->d_min < d_hit) ? rule->d_min : d_hit;
        return follow(p, s, "follow_edge");
    }
    if (s->goal_distance < rule->d_min)
        rule->d_min = s->goal_distance;
    if (ifgm_progress_made(rule, s) || (iba && ifgm_free_path_leads_on(rule, s))) {
        f->following = 0;
        return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, iba ? "leave" : "leave_distbug");
    }
    if (back_at_hit(f, o->pose, &p->body.tuning)) {
        ifgm_command stop = {s->pose[2], 0, IFGM_OBSTACLE_AVOIDANCE, "loop_closed",
                             IFGM_GOAL_UNREACHABLE};
        return stop;
    }
    return follow(p, s, "follow_edge");
}

static ifgm_command boundary_step(ifgm_boundary_planner *p, const ifgm_observation *o)
{
    if (ifgm_rays_for(&p->rays, o->angle_min, o->angle_increment, o->n) != IFGM_OK) {
        ifgm_command stop = {o->pose[2], 0, IFGM_OBSTACLE_AVOIDANCE, "bad_scan", "bad_scan"};
        return stop;
    }
    ifgm_scan_points_of(&p->points, o->ranges, o->n, o->range_min, p->body.tuning.view_range,
                        p->rays.angle, p->rays.cos, p->rays.sin);
    ifgm_memory_add(&p->memory, o->t, o->pose, &p->points);
    follower_track(&p->follower, o->pose);
    ifgm_sight s;
    ifgm_sight_init(&s, &p->body, o->pose, &p->memory,
                    atan2(p->body.goal.y - o->pose[1], p->body.goal.x - o->pose[0]));
    return ifgm_guard(boundary_decide(p, o, &s), &s);
}

ifgm_command distbug_step(distbug_planner *p, const ifgm_observation *o)
{
    return boundary_step(p, o);
}

ifgm_command iba_step(iba_planner *p, const ifgm_observation *o)
{
    return boundary_step(p, o);
}
