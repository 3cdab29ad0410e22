/* The robot and its sight of the goal: see sight.h. */
#include "sight.h"

#include "equations.h"
#include "tuning.h"

/* The goal counts as in view this far inside the view's edge (Sight.goal_in_view). */
#define IN_VIEW_MARGIN (10 * (IFGM_PI / 180))

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

int ifgm_nearest_ahead(const ifgm_sight *s)
{
    int i = ifgm_nearest_point(s->x, s->y, s->n, s->pose[0], s->pose[1]);
    if (i < 0)
        return 0;
    ifgm_real dx = s->x[i] - s->pose[0], dy = s->y[i] - s->pose[1];
    return cos(s->bearing) * dx + sin(s->bearing) * dy > 0;
}

int ifgm_goal_approachable(const ifgm_sight *s)
{
    const ifgm_body *b = s->body;
    ifgm_real travel = ifgm_disc_travel(s->x, s->y, s->n, s->pose[0], s->pose[1], s->bearing,
                                        b->half_width);
    return travel >= b->speed * b->dt;
}

int ifgm_meets_obstacle(ifgm_sight *s)
{
    return ifgm_goal_blocked(s) && (ifgm_nearest_ahead(s) || !ifgm_goal_approachable(s));
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
