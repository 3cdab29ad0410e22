/* DistBug and IBA: see boundary_planner.h. */
#include "boundary_planner.h"

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
    ifgm_follower_reset(&p->follower);
    ifgm_circuit_reset(&p->circuit);
    if (ifgm_governor_reset(&p->governor, e) != IFGM_OK)
        return IFGM_LONG_RESPONSE;
    ifgm_memory_clear(&p->memory, p->body.tuning.memory_horizon, e->dt);
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

/* Stop where the robot stands: the goal cannot be reached (`branch` says how it knows). */
static ifgm_command unreachable(const ifgm_sight *s, const char *branch)
{
    ifgm_command stop = {s->pose[2], 0, IFGM_OBSTACLE_AVOIDANCE, branch, IFGM_GOAL_UNREACHABLE};
    return stop;
}

/* Move to goal or follow the edge (BoundaryPlanner.decide): the rule's leaving point, or
 * else Bug1's after a whole loop (circuit.h). */
static ifgm_command boundary_decide(ifgm_boundary_planner *p, const ifgm_observation *o,
                                    ifgm_sight *s)
{
    ifgm_follower *f = &p->follower;
    ifgm_progress *rule = &p->progress;
    ifgm_circuit *circuit = &p->circuit;
    int iba = p->rule == IFGM_RULE_IBA;
    if (!f->following) {
        if (!ifgm_meets_obstacle(s))
            return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, "move_to_goal");
        ifgm_follow_side side = iba ? ifgm_freer_side(o->ranges, o->n, o->range_max,
                                                      p->rays.angle, p->rays.beam, s->pose,
                                                      s->bearing)
                                    : IFGM_FOLLOW_RIGHT; /* the Bug family turns left */
        ifgm_follower_start(f, o->pose, side);
        ifgm_real d_hit = hypot(p->body.goal.x - f->hit.x, p->body.goal.y - f->hit.y);
        rule->d_min = (iba && rule->d_min < d_hit) ? rule->d_min : d_hit;
        ifgm_circuit_on_hit(circuit);
        return follow(p, s, "follow_edge");
    }
    ifgm_circuit_note(circuit, s, 1);
    if (s->goal_distance < rule->d_min)
        rule->d_min = s->goal_distance;
    if (ifgm_progress_made(rule, s) || (iba && ifgm_free_path_leads_on(rule, s))) {
        f->following = 0;
        return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, iba ? "leave" : "leave_distbug");
    }
    if (ifgm_circuit_returning(circuit)) {
        ifgm_real heading = ifgm_circuit_heading_to_q(circuit, s);
        if (!ifgm_circuit_at_q(circuit, s))
            return ifgm_steer(heading, s, IFGM_OBSTACLE_AVOIDANCE, "follow_to_q");
        ifgm_circuit_leave(circuit);
        f->following = 0;
        return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, "leave_at_q");
    }
    int back_at = ifgm_circuit_closing(circuit, s);
    if (back_at >= 0) {
        if (!ifgm_circuit_close(circuit, s, back_at, f->side))
            return unreachable(s, "goal_enclosed");
        return follow(p, s, "loop_closed");
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
    ifgm_sight s;
    ifgm_sight_init(&s, &p->body, o->pose, &p->memory,
                    atan2(p->body.goal.y - o->pose[1], p->body.goal.x - o->pose[0]));
    ifgm_command command = ifgm_keep_clear(boundary_decide(p, o, &s), &s);
    return ifgm_govern(&p->governor, command, o, p->rays.cos, p->rays.sin);
}

ifgm_command distbug_step(distbug_planner *p, const ifgm_observation *o)
{
    return boundary_step(p, o);
}

ifgm_command iba_step(iba_planner *p, const ifgm_observation *o)
{
    return boundary_step(p, o);
}
