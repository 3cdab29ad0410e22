/* Bug1's round of one obstacle: see circuit.h. */
#include "circuit.h"

/* The trail's spacing, as a fraction of return_radius: a path that passes within half a
 * return_radius of the earlier one comes within return_radius of one of its points
 * (TRAIL_SPACING_FRACTION). */
#define TRAIL_SPACING_FRACTION ((ifgm_real)0.5)
/* A place is passed again the same way when the headings differ by less than this, rad
 * (SAME_WAY): along a loop followed twice they differ by the follower's corner cutting, a
 * few degrees; where the way crosses itself between two obstacles, by far more. */
#define SAME_WAY (IFGM_PI / 4)

/* Forget the trail and Q: a new first pass (Circuit._start). */
static void start(ifgm_circuit *c)
{
    c->q_point.x = c->q_point.y = (ifgm_real)NAN;
    c->q_distance = IFGM_INF;
    c->travelled = 0;
    c->has_last = 0;
    c->laid = c->next = c->q_index = 0;
}

void ifgm_circuit_reset(ifgm_circuit *c)
{
    c->phase = IFGM_CIRCUIT_IDLE;
    c->left_q = IFGM_INF;
    start(c);
}

void ifgm_circuit_on_hit(ifgm_circuit *c)
{
    c->left_q = c->phase == IFGM_CIRCUIT_LEFT_AT_Q ? c->q_distance : IFGM_INF;
    c->phase = IFGM_CIRCUIT_FIRST_PASS;
    start(c);
}

void ifgm_circuit_note(ifgm_circuit *c, const ifgm_sight *s, int following)
{
    if (c->phase != IFGM_CIRCUIT_FIRST_PASS)
        return;
    if (c->has_last)
        c->travelled += hypot(s->pose[0] - c->last.x, s->pose[1] - c->last.y);
    c->has_last = 1;
    c->last.x = s->pose[0];
    c->last.y = s->pose[1];
    ifgm_real travelled = c->travelled;
    int n = c->laid;
    ifgm_real spacing = TRAIL_SPACING_FRACTION * s->body->tuning.return_radius;
    if (n && travelled < c->trail[n - 1].travelled + spacing)
        return;
    if (n == IFGM_MAX_TRAIL) /* full: the loop closes on the points laid (circuit.h) */
        return;
    ifgm_trail_point *p = &c->trail[n];
    p->x = s->pose[0];
    p->y = s->pose[1];
    p->heading = s->pose[2];
    p->goal_distance = s->goal_distance;
    p->travelled = travelled;
    p->following = following != 0;
    c->laid = n + 1;
}

int ifgm_circuit_closing(const ifgm_circuit *c, const ifgm_sight *s)
{
    if (c->phase != IFGM_CIRCUIT_FIRST_PASS)
        return -1;
    const ifgm_tuning *t = &s->body->tuning;
    ifgm_real old = c->travelled - t->min_loop, reach = t->return_radius;
    ifgm_real far2 = 4 * reach * reach, same_way = cos(SAME_WAY);
    /* The trail's distances driven rise: the points at least min_loop behind come first. */
    for (int i = 0; i < c->laid && c->trail[i].travelled <= old; i++) {
        const ifgm_trail_point *p = &c->trail[i];
        ifgm_real dx = p->x - s->pose[0], dy = p->y - s->pose[1];
        /* Twice return_radius away is beyond it whatever the rounding: skip the hypot. */
        if (p->following && dx * dx + dy * dy <= far2 && hypot(dx, dy) <= reach &&
            cos(p->heading - s->pose[2]) > same_way)
            return i;
    }
    return -1;
}

int ifgm_encloses(const ifgm_trail_point *loop, int n, ifgm_point goal, ifgm_follow_side side)
{
    int winding = 0;
    ifgm_real area = 0; /* twice the signed area: < 0 clockwise */
    for (int i = 0; i < n; i++) {
        const ifgm_trail_point *b = &loop[i + 1 < n ? i + 1 : 0];
        ifgm_real x = loop[i].x - goal.x, y = loop[i].y - goal.y;
        ifgm_real x2 = b->x - goal.x, y2 = b->y - goal.y;
        ifgm_real cross = x * y2 - x2 * y;
        if (y <= 0 && y2 > 0 && cross > 0)
            winding++; /* crosses the ray from the goal towards +x, upwards */
        else if (y > 0 && y2 <= 0 && cross < 0)
            winding--;
        /* numpy sums pairwise, this in order: the sign can differ only for a loop whose
         * signed area is within rounding of 0. */
        area += cross;
    }
    int goal_inside = winding != 0;
    int obstacle_inside = (area < 0) == (side == IFGM_FOLLOW_RIGHT);
    return goal_inside == obstacle_inside;
}

int ifgm_circuit_close(ifgm_circuit *c, const ifgm_sight *s, int at, ifgm_follow_side side)
{
    const ifgm_trail_point *loop = c->trail + at;
    int n = c->laid - at, best = 0;
    for (int i = 1; i < n; i++)
        if (loop[i].goal_distance < loop[best].goal_distance)
            best = i;
    c->q_point.x = loop[best].x;
    c->q_point.y = loop[best].y;
    c->q_distance = loop[best].goal_distance;
    c->next = at;
    c->q_index = at + best;
    c->phase = IFGM_CIRCUIT_RETURN_TO_Q;
    if (ifgm_encloses(loop, n, s->body->goal, side))
        return 0; /* the obstacle gone round surrounds the goal, or the robot went round
                     the inside of an enclosure with the goal outside */
    /* Met on leaving the last Q: this round must find a nearer Q, by a step of travel. */
    return c->q_distance < c->left_q - s->body->speed * s->body->dt;
}

int ifgm_circuit_returning(const ifgm_circuit *c)
{
    return c->phase == IFGM_CIRCUIT_RETURN_TO_Q;
}

ifgm_real ifgm_circuit_heading_to_q(ifgm_circuit *c, const ifgm_sight *s)
{
    ifgm_real reach = s->body->tuning.return_radius;
    while (c->next < c->q_index &&
           hypot(c->trail[c->next].x - s->pose[0], c->trail[c->next].y - s->pose[1]) <= reach)
        c->next++;
    const ifgm_trail_point *target = &c->trail[c->next];
    return atan2(target->y - s->pose[1], target->x - s->pose[0]);
}

int ifgm_circuit_at_q(const ifgm_circuit *c, const ifgm_sight *s)
{
    ifgm_real spacing = TRAIL_SPACING_FRACTION * s->body->tuning.return_radius;
    return c->next >= c->q_index &&
           hypot(c->q_point.x - s->pose[0], c->q_point.y - s->pose[1]) <= spacing;
}

void ifgm_circuit_leave(ifgm_circuit *c)
{
    c->phase = IFGM_CIRCUIT_LEFT_AT_Q;
}
