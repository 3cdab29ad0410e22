/* IFGM: see ifgm.h. The step reads as docs/flowchart.md does: percepts (perceive), atoms
 * (read, which changes nothing), the branch (decide), the branch carried out (act). */
#include "ifgm.h"

#include "equations.h"

/* The dead-end rule's step, and at most four steps: 45, 90, 135, 180 degrees (section 4). */
#define DEAD_END_STEP (IFGM_PI / 4)
#define DEAD_END_MAX_STEPS 4

static const char *const BRANCH_NAMES[IFGM_BRANCHES] = {
    "goal_reached",  "move_to_goal",  "case1_gap",         "case2_narrow_gap",
    "case2_one_sided", "too_close",   "case3_preempt",     "follow_edge",
    "dead_end_turn", "path_regenerated", "dead_end_escape", "dead_end_handover"};

const char *ifgm_branch_name(ifgm_branch branch)
{
    return BRANCH_NAMES[branch];
}

/* Figure 3's yes/no facts (flowchart.Atoms). */
typedef struct {
    int at_goal, turning, avoiding, blocked, free, close, wide, one_sided, dead_end, preempt;
} atoms;

/* What read() makes of one step: the atoms and the percepts behind them. */
typedef struct {
    atoms a;
    const ifgm_gap *gap; /* the chosen gap, or NULL */
    int has_gap_mid;     /* its middle, world frame, if wider than d_th */
    ifgm_point gap_mid;
    int has_preemptor; /* Case-3's obstacle of most impact */
    ifgm_point preemptor;
    int short_look;
} reading;

int ifgm_init(ifgm_planner *p, const ifgm_episode *e, const ifgm_tuning *tuning)
{
    int status = ifgm_body_init(&p->body, e, tuning);
    if (status == IFGM_OK)
        status = ifgm_check_capacity(&p->rays, e, &p->body);
    if (status != IFGM_OK)
        return status;
    if (p->rays.view_n < 2)
        return IFGM_NARROW_VIEW;
    if (p->body.tuning.d_th <= 2 * e->radius)
        return IFGM_BAD_PARAMETER;
    p->iba.d_min = IFGM_INF;
    p->iba.step_length = p->body.tuning.step_length;
    ifgm_follower_reset(&p->follower);
    ifgm_circuit_reset(&p->circuit);
    if (ifgm_governor_reset(&p->governor, e) != IFGM_OK)
        return IFGM_LONG_RESPONSE;
    ifgm_memory_clear(&p->memory, p->body.tuning.memory_horizon, e->dt);
    /* Within the tolerance plus one step of travel the robot drives onto the goal. */
    p->goal_tolerance = e->goal_tolerance + e->speed * e->dt;
    ifgm_state fresh = {0};
    fresh.mode = IFGM_MODE_MOVE_TO_GOAL;
    p->state = fresh;
    p->last_branch = IFGM_MOVE_TO_GOAL_BRANCH;
    return IFGM_OK;
}

/* theta_d of eq. (3), world frame; at the goal itself, the heading. */
static ifgm_real goal_bearing(const ifgm_planner *p, const ifgm_real pose[3])
{
    ifgm_real here[2] = {pose[0], pose[1]}, goal[2] = {p->body.goal.x, p->body.goal.y};
    ifgm_real bearing;
    return eq3_goal_angle(here, goal, &bearing) == 0 ? bearing : pose[2];
}

/* The remembered point nearest the robot; with `near`, among those within jump of it. */
static int nearest_remembered(const ifgm_planner *p, const ifgm_sight *s, const ifgm_point *near,
                              ifgm_point *out)
{
    int i = near ? ifgm_nearest_point_near(s->x, s->y, s->n, s->pose[0], s->pose[1], near->x,
                                           near->y, p->body.tuning.jump)
                 : ifgm_nearest_point(s->x, s->y, s->n, s->pose[0], s->pose[1]);
    if (i < 0)
        return 0;
    out->x = s->x[i];
    out->y = s->y[i];
    return 1;
}

/* The view's points: the scan's own when the view is the whole scan (the paper's sensor). */
static const ifgm_scan_points *view_points(const ifgm_planner *p)
{
    return p->rays.view_n != p->rays.n ? &p->view_points : &p->points;
}

/* IBA's leaving rules (errata row 24): a free path, or DistBug's progress rule -- but not
 * while following the wall round from outside after a dead end. Beside them, Bug1's round
 * (circuit.h; errata row 34): one round from the first obstacle met until the robot leaves
 * at a Q, its trail laid in every mode, so that it also closes when IFGM leaves an edge by
 * IBA's rules, meets the same obstacles again and goes the same way round; once the loop
 * closes, only Q is left from. IFGM has no "goal unreachable": a loop that shows the goal
 * cannot be reached is left at its Q all the same, and the next round follows the other
 * side (IFGMPlanner.may_leave). */
static int leaving(ifgm_planner *p, ifgm_sight *s)
{
    ifgm_circuit *circuit = &p->circuit;
    if (ifgm_circuit_returning(circuit)) {
        if (!ifgm_circuit_at_q(circuit, s))
            return 0;
        ifgm_circuit_leave(circuit);
        return 1;
    }
    int back_at = ifgm_circuit_closing(circuit, s);
    if (back_at >= 0) {
        ifgm_follow_side side = p->follower.side;
        if (!ifgm_circuit_close(circuit, s, back_at, side)) { /* no way on this way round */
            p->state.has_turn_other_way = 1;
            p->state.turn_other_way =
                side == IFGM_FOLLOW_RIGHT ? IFGM_FOLLOW_LEFT : IFGM_FOLLOW_RIGHT;
        }
        return 0;
    }
    int progress = ifgm_progress_made(&p->iba, s) && !p->state.escaped;
    return ifgm_free_path_leads_on(&p->iba, s) || progress;
}

/* Remember the scan; work out the 135-degree view, its obstacles and gaps; count the way
 * followed; lay Bug1's trail (in every mode); while following, track the followed point and
 * ask the leaving rules. Returns 0 on a scan the build cannot hold. */
static int perceive(ifgm_planner *p, const ifgm_observation *o, ifgm_sight *s, int *may_leave)
{
    if (ifgm_rays_for(&p->rays, o->angle_min, o->angle_increment, o->n) != IFGM_OK ||
        p->rays.view_n < 2)
        return 0;
    const ifgm_rays *rays = &p->rays;
    ifgm_real view_range = p->body.tuning.view_range;
    ifgm_scan_points_of(&p->points, o->ranges, o->n, o->range_min, view_range, rays->angle,
                        rays->cos, rays->sin);
    ifgm_memory_add(&p->memory, o->t, o->pose, &p->points);
    const ifgm_real *window = o->ranges + rays->view_first;
    for (int j = 0; j < rays->view_n; j++)
        p->view_ranges[j] = window[j] > view_range ? IFGM_INF : window[j];
    p->view_range_max = view_range < o->range_max ? view_range : o->range_max;
    if (rays->view_n != rays->n)
        ifgm_scan_points_of(&p->view_points, window, rays->view_n, o->range_min, view_range,
                            rays->view_angle, rays->view_cos, rays->view_sin);
    const ifgm_scan_points *view = view_points(p);
    p->n_clusters = ifgm_cluster_points(view, p->body.tuning.jump, p->clusters);
    p->n_gaps = ifgm_gaps_between(view, p->clusters, p->n_clusters, p->gaps);
    ifgm_sight_init(s, &p->body, o->pose, &p->memory, goal_bearing(p, o->pose));
    ifgm_circuit_note(&p->circuit, s, p->state.mode == IFGM_MODE_FOLLOWING);
    *may_leave = 0;
    if (p->state.mode == IFGM_MODE_FOLLOWING) {
        ifgm_state *st = &p->state;
        ifgm_point tracked;
        int found = st->has_followed && nearest_remembered(p, s, &st->followed, &tracked);
        if (!found)
            found = nearest_remembered(p, s, 0, &tracked);
        st->has_followed = found;
        if (found)
            st->followed = tracked;
        if (s->goal_distance < p->iba.d_min)
            p->iba.d_min = s->goal_distance;
        *may_leave = leaving(p, s);
    }
    return 1;
}

/* A robot-frame gap's middle (eq. (1)) in the world frame. */
static ifgm_point gap_middle(const ifgm_gap *g, const ifgm_real pose[3])
{
    ifgm_real right[2] = {g->right.x, g->right.y}, left[2] = {g->left.x, g->left.y}, mid[2];
    eq1_gap_midpoint(right, left, mid);
    return ifgm_to_world(mid[0], mid[1], pose);
}

/* The maximum gap -- but the one steered through at the last step while it stays wider
 * than d_th (errata row 19): of the gaps wider than d_th whose middle lies within jump of
 * the last one, the one whose middle is nearest it. */
static void choose_gap(const ifgm_planner *p, const ifgm_real pose[3], reading *r)
{
    const ifgm_tuning *t = &p->body.tuning;
    r->gap = 0;
    r->has_gap_mid = 0;
    if (p->n_gaps == 0)
        return;
    const ifgm_gap *chosen = &p->gaps[0];
    for (int k = 1; k < p->n_gaps; k++)
        if (p->gaps[k].width > chosen->width)
            chosen = &p->gaps[k];
    if (p->state.has_gap_mid) {
        ifgm_real kept = t->jump;
        for (int k = 0; k < p->n_gaps; k++) {
            ifgm_point mid = gap_middle(&p->gaps[k], pose);
            ifgm_real apart = hypot(mid.x - p->state.gap_mid.x, mid.y - p->state.gap_mid.y);
            if (p->gaps[k].width > t->d_th && apart <= kept) {
                chosen = &p->gaps[k];
                kept = apart;
            }
        }
    }
    r->gap = chosen;
    if (chosen->width > t->d_th) {
        r->has_gap_mid = 1;
        r->gap_mid = gap_middle(chosen, pose);
    }
}

/* Case-3: an obstacle apart from the followed one and nearer than it by preempt_margin;
 * of several, the nearest. Its nearest return, world frame. */
static int find_preemptor(const ifgm_planner *p, const ifgm_real pose[3], ifgm_point *out)
{
    const ifgm_tuning *t = &p->body.tuning;
    const ifgm_point f = p->state.followed;
    const ifgm_scan_points *v = view_points(p);
    ifgm_real reach = hypot(f.x - pose[0], f.y - pose[1]) - t->preempt_margin;
    ifgm_real best = IFGM_INF, jump2 = t->jump * t->jump;
    int found = 0;
    for (int k = 0; k < p->n_clusters; k++) {
        const ifgm_cluster *c = &p->clusters[k];
        if (c->nearest >= reach)
            continue;
        ifgm_real apart = IFGM_INF;
        int nearest_i = c->begin;
        for (int i = c->begin; i < c->end; i++) {
            ifgm_point w = ifgm_to_world(v->x[i], v->y[i], pose);
            ifgm_real d2 = (w.x - f.x) * (w.x - f.x) + (w.y - f.y) * (w.y - f.y);
            if (d2 < apart)
                apart = d2;
            if (v->range[i] < v->range[nearest_i])
                nearest_i = i;
        }
        if (apart > jump2 && c->nearest < best) {
            best = c->nearest;
            *out = ifgm_to_world(v->x[nearest_i], v->y[nearest_i], pose);
            found = 1;
        }
    }
    return found;
}

/* The flowchart's atoms for this step's percepts in this state; changes nothing. */
static reading read(const ifgm_planner *p, ifgm_sight *s, int may_leave)
{
    const ifgm_tuning *t = &p->body.tuning;
    const ifgm_state *st = &p->state;
    reading r = {0};
    choose_gap(p, s->pose, &r);
    ifgm_real nearest = IFGM_INF;
    int left = 0, right = 0, both = 0;
    for (int k = 0; k < p->n_clusters; k++) {
        const ifgm_cluster *c = &p->clusters[k];
        if (c->nearest < nearest)
            nearest = c->nearest;
        left |= c->side == IFGM_SIDE_LEFT;
        right |= c->side == IFGM_SIDE_RIGHT;
        both |= c->side == IFGM_SIDE_BOTH;
    }
    int gap_wide = r.gap && r.gap->width > t->d_th;
    ifgm_real free_ahead = ifgm_goal_free_length(s);
    r.short_look = st->short_look && !(free_ahead >= t->d_look); /* in the open again */
    int front_near = 0, enclosed = 1;
    for (int j = 0; j < p->rays.view_n; j++) {
        ifgm_real range = p->view_ranges[j];
        front_near |= p->rays.view_beam[j] == IFGM_BEAM_FRONT && range <= t->d_look;
        enclosed &= range <= t->view_range; /* every ray returns: the view is closed */
    }
    int following = st->mode == IFGM_MODE_FOLLOWING;
    r.has_preemptor = following && st->has_followed && find_preemptor(p, s->pose, &r.preemptor);
    r.a.at_goal = s->goal_distance <= p->goal_tolerance;
    r.a.turning = st->mode == IFGM_MODE_DEAD_END_TURN || st->mode == IFGM_MODE_ESCAPING;
    r.a.avoiding = following;
    /* Looking short, an obstacle is met as IBA meets one (errata row 34): in the corridor
     * within the encounter distance, and the nearest ahead -- not the one just left. */
    r.a.blocked = r.short_look ? ifgm_meets_obstacle(s)
                               : free_ahead < (t->d_look < s->goal_distance ? t->d_look
                                                                            : s->goal_distance);
    r.a.free = following && may_leave;
    r.a.close = nearest <= t->d_obs;
    r.a.wide = gap_wide && !r.short_look; /* Case-1 needs a gap measured from afar */
    r.a.one_sided = p->n_clusters > 0 && !both && (left != right);
    r.a.dead_end = front_near && enclosed && !gap_wide;
    r.a.preempt = r.has_preemptor;
    return r;
}

/* Figure 3: the one branch whose guard holds (flowchart.GUARDS, as one decision tree). */
static ifgm_branch decide(const atoms *a)
{
    if (a->at_goal)
        return IFGM_GOAL_REACHED;
    if (a->turning)
        return IFGM_DEAD_END_TURN;
    if (a->avoiding)
        return a->free ? IFGM_PATH_REGENERATED
                       : (a->preempt ? IFGM_CASE3_PREEMPT : IFGM_FOLLOW_EDGE);
    if (!a->blocked)
        return IFGM_MOVE_TO_GOAL_BRANCH;
    if (a->dead_end)
        return IFGM_DEAD_END_TURN;
    if (a->close)
        return IFGM_TOO_CLOSE;
    if (a->one_sided)
        return IFGM_CASE2_ONE_SIDED;
    return a->wide ? IFGM_CASE1_GAP : IFGM_CASE2_NARROW_GAP;
}

static ifgm_command command_of(ifgm_real heading, ifgm_real speed, ifgm_branch branch)
{
    ifgm_command c = {heading, speed, IFGM_OBSTACLE_AVOIDANCE, BRANCH_NAMES[branch], 0};
    return c;
}

/* The freer side of the 135-degree view (IBA's bidirectional choice). */
static ifgm_follow_side view_freer_side(const ifgm_planner *p, const ifgm_sight *s)
{
    return ifgm_freer_side(p->view_ranges, p->rays.view_n, p->view_range_max,
                           p->rays.view_angle, p->rays.view_beam, s->pose, s->bearing);
}

/* Follow the edge with IBA -- after a whole loop, retrace it to Q (Bug1's round, errata
 * row 34); if the edge is forgotten, head for the goal instead. */
static ifgm_command follow(ifgm_planner *p, const ifgm_sight *s, ifgm_branch branch)
{
    ifgm_real heading;
    if (ifgm_circuit_returning(&p->circuit))
        heading = ifgm_circuit_heading_to_q(&p->circuit, s);
    else if (!ifgm_follow_heading(&p->follower, s, &heading)) {
        p->state.mode = IFGM_MODE_MOVE_TO_GOAL;
        return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, BRANCH_NAMES[branch]);
    }
    return ifgm_steer(heading, s, IFGM_OBSTACLE_AVOIDANCE, BRANCH_NAMES[branch]);
}

/* IBA takes over: follow the nearest obstacle on the freer side -- or on the other side
 * than a round that found no way on -- nothing pre-empted. A round of Bug1's already on
 * its first pass goes on: it spans the edges IFGM leaves by IBA's rules (errata row 34). */
static void start_following(ifgm_planner *p, const ifgm_sight *s)
{
    ifgm_state *st = &p->state;
    ifgm_follow_side side = st->has_turn_other_way ? st->turn_other_way : view_freer_side(p, s);
    ifgm_follower_start(&p->follower, s->pose, side);
    ifgm_real d_hit = hypot(p->body.goal.x - s->pose[0], p->body.goal.y - s->pose[1]);
    if (d_hit < p->iba.d_min) /* one yardstick for the episode (errata row 31) */
        p->iba.d_min = d_hit;
    if (p->circuit.phase != IFGM_CIRCUIT_FIRST_PASS)
        ifgm_circuit_on_hit(&p->circuit);
    st->mode = IFGM_MODE_FOLLOWING;
    st->has_turn = st->has_escape_from = 0;
    st->short_look = st->escaped = 0;
    st->has_followed = nearest_remembered(p, s, 0, &st->followed);
    st->stack_n = 0;
    st->has_turn_other_way = 0;
}

/* Case-3 recursion: once the pre-empting obstacle is no longer the nearest, resume the one
 * it interrupted, on the side it was followed on. */
static void resume_if_back(ifgm_planner *p, const ifgm_sight *s)
{
    ifgm_state *st = &p->state;
    ifgm_point nearest;
    if (st->stack_n > 0 && nearest_remembered(p, s, 0, &nearest) && st->has_followed &&
        hypot(st->followed.x - nearest.x, st->followed.y - nearest.y) > p->body.tuning.jump) {
        st->stack_n--;
        p->follower.side = st->stack_side[st->stack_n];
        st->followed = nearest;
    }
}

/* Case-3: push the followed obstacle, avoid the new one. */
static void preempt(ifgm_planner *p, const ifgm_sight *s, ifgm_point preemptor)
{
    ifgm_state *st = &p->state;
    if (st->stack_n == IFGM_MAX_STACK) { /* forget the oldest */
        for (int k = 1; k < IFGM_MAX_STACK; k++) {
            st->stack_point[k - 1] = st->stack_point[k];
            st->stack_side[k - 1] = st->stack_side[k];
        }
        st->stack_n--;
    }
    st->stack_point[st->stack_n] = st->followed;
    st->stack_side[st->stack_n] = p->follower.side;
    st->stack_n++;
    st->followed = preemptor;
    p->follower.side = view_freer_side(p, s);
}

static ifgm_real dead_end_target(const ifgm_state *st)
{
    return ifgm_wrap_angle(st->turn_start + (st->turn_sign * st->turn_steps) * DEAD_END_STEP);
}

/* Whether a ray of the view's `beam` returns within d_look (IFGMPlanner.side_walls). */
static int side_wall(const ifgm_planner *p, ifgm_beam beam)
{
    for (int j = 0; j < p->rays.view_n; j++)
        if (p->rays.view_beam[j] == beam && p->view_ranges[j] <= p->body.tuning.d_look)
            return 1;
    return 0;
}

/* The dead end in its three phases, each labelled: turn in 45-degree steps until the way
 * ahead is free (dead_end_turn); go that way (dead_end_escape); once out, follow the nearest
 * wall round from outside (dead_end_handover). Section 4, dead end; errata row 32. */
static ifgm_command dead_end(ifgm_planner *p, const ifgm_sight *s)
{
    ifgm_state *st = &p->state;
    const ifgm_body *b = &p->body;
    if (!st->has_turn) { /* entering the dead end: turn towards the freer beam */
        st->has_turn = 1;
        st->has_escape_from = 0;
        st->walled[0] = st->walled[1] = 0;
        st->turn_start = s->pose[2];
        st->turn_sign = view_freer_side(p, s) == IFGM_FOLLOW_RIGHT ? 1 : -1;
        st->turn_steps = 1;
        st->mode = IFGM_MODE_DEAD_END_TURN;
    }
    ifgm_real target = dead_end_target(st);
    int turning = !st->has_escape_from;
    if (turning && fabs(ifgm_wrap_angle(s->pose[2] - target)) > b->tuning.turn_done)
        return command_of(target, 0, IFGM_DEAD_END_TURN);
    ifgm_real ahead =
        ifgm_free_length(s->x, s->y, s->n, s->pose[0], s->pose[1], s->pose[2], b->half_width);
    if (turning) {
        if (ahead < b->tuning.view_range && st->turn_steps < DEAD_END_MAX_STEPS) {
            st->turn_steps++;
            return command_of(dead_end_target(st), 0, IFGM_DEAD_END_TURN);
        }
        st->has_escape_from = 1; /* free (or 180 degrees): go */
        st->escape_from.x = s->pose[0];
        st->escape_from.y = s->pose[1];
        st->mode = IFGM_MODE_ESCAPING;
    }
    /* The escape ends at the end of the wall: where a side beam that has seen a wall since
     * the robot started driving out sees none within d_look (section 5.2; errata row 34). */
    int wall_ended = 0;
    for (int k = 0; k < 2; k++) {
        int now = side_wall(p, k ? IFGM_BEAM_RIGHT : IFGM_BEAM_LEFT);
        st->walled[k] |= now;
        wall_ended |= st->walled[k] && !now;
    }
    ifgm_real out = hypot(st->escape_from.x - s->pose[0], st->escape_from.y - s->pose[1]);
    if (out < b->tuning.d_look && ahead > b->encounter && !wall_ended)
        return command_of(target, b->speed, IFGM_DEAD_END_ESCAPE);
    start_following(p, s);
    st->escaped = 1;
    ifgm_point followed;
    if (nearest_remembered(p, s, 0, &followed)) {
        ifgm_real to = atan2(followed.y - s->pose[1], followed.x - s->pose[0]);
        ifgm_real rel = ifgm_wrap_angle(to - s->pose[2]);
        p->follower.side = rel > 0 ? IFGM_FOLLOW_LEFT : IFGM_FOLLOW_RIGHT;
    }
    return follow(p, s, IFGM_DEAD_END_HANDOVER);
}

/* Case-1: the final heading through the gap by eqs. (1)-(4), world frame. */
static ifgm_real gap_heading(const ifgm_planner *p, const ifgm_sight *s, const ifgm_gap *g)
{
    const ifgm_tuning *t = &p->body.tuning;
    ifgm_real right[2] = {g->right.x, g->right.y}, left[2] = {g->left.x, g->left.y}, mid[2];
    ifgm_real theta_g, heading;
    eq1_gap_midpoint(right, left, mid);
    if (eq2_gap_angle(mid[0], mid[1], &theta_g) != 0) /* a gap's middle at the robot */
        theta_g = 0;
    theta_g += s->pose[2];
    if (eq4_final_heading(theta_g, s->bearing, t->w_g, t->w_d, t->d_th, s->pose[2], &heading))
        heading = s->bearing; /* the weights are checked at init: never taken */
    return heading;
}

/* Carry out the branch, moving the state on. */
static ifgm_command act(ifgm_planner *p, ifgm_sight *s, const reading *r, ifgm_branch branch)
{
    ifgm_state *st = &p->state;
    switch (branch) {
    case IFGM_GOAL_REACHED: {
        ifgm_real speed = s->goal_distance / p->body.dt;
        ifgm_command c = {s->bearing, p->body.speed < speed ? p->body.speed : speed,
                          IFGM_MOVE_TO_GOAL, BRANCH_NAMES[branch], 0};
        return c;
    }
    case IFGM_MOVE_TO_GOAL_BRANCH:
        st->mode = IFGM_MODE_MOVE_TO_GOAL;
        return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, BRANCH_NAMES[branch]);
    case IFGM_PATH_REGENERATED:
        /* Left by the progress rule with an obstacle still ahead, or at Bug1's Q: meet it
         * at IBA's short encounter distance, not d_look (errata rows 24 and 34). */
        st->mode = IFGM_MODE_MOVE_TO_GOAL;
        st->short_look = p->circuit.phase == IFGM_CIRCUIT_LEFT_AT_Q || !ifgm_path_free(s);
        st->escaped = 0;
        st->has_followed = 0;
        st->stack_n = 0;
        return ifgm_steer(s->bearing, s, IFGM_MOVE_TO_GOAL, BRANCH_NAMES[branch]);
    case IFGM_CASE1_GAP:
        st->mode = IFGM_MODE_THROUGH_GAP;
        return ifgm_steer(gap_heading(p, s, r->gap), s, IFGM_OBSTACLE_AVOIDANCE,
                          BRANCH_NAMES[branch]);
    case IFGM_DEAD_END_TURN:
        return dead_end(p, s);
    case IFGM_CASE3_PREEMPT:
        preempt(p, s, r->preemptor);
        break;
    case IFGM_FOLLOW_EDGE:
        resume_if_back(p, s);
        break;
    default: /* Case-2 (narrow gap, one-sided) or too close: IBA takes over */
        start_following(p, s);
        break;
    }
    return follow(p, s, branch);
}

ifgm_command ifgm_step(ifgm_planner *p, const ifgm_observation *o)
{
    ifgm_sight s;
    int may_leave;
    if (!perceive(p, o, &s, &may_leave)) {
        ifgm_command stop = {o->pose[2], 0, IFGM_OBSTACLE_AVOIDANCE, 0, "bad_scan"};
        return stop;
    }
    reading r = read(p, &s, may_leave);
    p->state.has_gap_mid = r.has_gap_mid;
    p->state.gap_mid = r.gap_mid;
    p->state.short_look = r.short_look;
    p->last_branch = decide(&r.a);
    ifgm_command command = ifgm_keep_clear(act(p, &s, &r, p->last_branch), &s);
    return ifgm_govern(&p->governor, command, o, p->rays.cos, p->rays.sin);
}
