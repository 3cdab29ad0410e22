/* Percepts: see percepts.h. */
#include "percepts.h"

#include <string.h>

ifgm_beam ifgm_beam_of(ifgm_real angle)
{
    if (fabs(angle) > IFGM_PAPER_HALF_FOV + IFGM_BORDER_TOLERANCE)
        return IFGM_BEAM_NONE;
    if (angle > IFGM_FRONT_HALF_WIDTH + IFGM_BORDER_TOLERANCE)
        return IFGM_BEAM_LEFT;
    if (angle < -IFGM_FRONT_HALF_WIDTH - IFGM_BORDER_TOLERANCE)
        return IFGM_BEAM_RIGHT;
    return IFGM_BEAM_FRONT;
}

int ifgm_rays_for(ifgm_rays *rays, ifgm_real angle_min, ifgm_real angle_increment, int n)
{
    if (rays->n == n && rays->angle_min == angle_min && rays->angle_increment == angle_increment)
        return IFGM_OK;
    if (n > IFGM_MAX_RAYS)
        return IFGM_TOO_MANY_RAYS;
    int first = -1, last = -1;
    for (int i = 0; i < n; i++) {
        ifgm_real a = angle_min + angle_increment * i;
        rays->angle[i] = a;
        rays->cos[i] = cos(a);
        rays->sin[i] = sin(a);
        rays->beam[i] = (unsigned char)ifgm_beam_of(a);
        if (fabs(a) <= IFGM_PAPER_HALF_FOV + IFGM_BORDER_TOLERANCE) {
            if (first < 0)
                first = i;
            last = i;
        }
    }
    int inside = first < 0 ? 0 : last - first + 1;
    rays->view_first = (inside == n || first < 0) ? 0 : first;
    rays->view_n = inside;
    for (int j = 0; j < inside; j++) {
        /* A window is a scan of its own: its angles count from its first ray. */
        ifgm_real a = inside == n ? rays->angle[j] : rays->angle[first] + angle_increment * j;
        rays->view_angle[j] = a;
        rays->view_cos[j] = cos(a);
        rays->view_sin[j] = sin(a);
        rays->view_beam[j] = (unsigned char)ifgm_beam_of(a);
    }
    rays->angle_min = angle_min;
    rays->angle_increment = angle_increment;
    rays->n = n;
    return IFGM_OK;
}

void ifgm_scan_points_of(ifgm_scan_points *out, const ifgm_real *ranges, int n,
                         ifgm_real range_min, ifgm_real limit, const ifgm_real *angle,
                         const ifgm_real *cos_a, const ifgm_real *sin_a)
{
    ifgm_real nearest = range_min < limit ? range_min : limit;
    int k = 0;
    for (int i = 0; i < n; i++) {
        ifgm_real r = ranges[i];
        if (r == -IFGM_INF)
            r = nearest;
        else if (!(r <= limit)) /* beyond the limit, +inf, NAN: no return */
            continue;
        out->ray[k] = i;
        out->angle[k] = angle[i];
        out->range[k] = r;
        out->x[k] = r * cos_a[i];
        out->y[k] = r * sin_a[i];
        k++;
    }
    out->n = k;
}

void ifgm_memory_clear(ifgm_memory *memory, ifgm_real horizon, ifgm_real period)
{
    memory->horizon = horizon;
    memory->period = period;
    memory->start = memory->end = 0;
    memory->scan_first = memory->scan_count = 0;
}

/* Forget the oldest remembered scan. */
static void forget_oldest(ifgm_memory *m)
{
    m->start += m->scan_size[m->scan_first];
    m->scan_first = (m->scan_first + 1) % IFGM_MAX_SCANS;
    m->scan_count--;
}

void ifgm_memory_add(ifgm_memory *m, ifgm_real t, const ifgm_real pose[3],
                     const ifgm_scan_points *points)
{
    int n = points->n;
    if (m->end + n > IFGM_MAX_POINTS) { /* move the live points to the front */
        while (m->scan_count > 0 && (m->end - m->start) + n > IFGM_MAX_POINTS)
            forget_oldest(m);
        int live = m->end - m->start;
        memmove(m->x, m->x + m->start, (size_t)live * sizeof m->x[0]);
        memmove(m->y, m->y + m->start, (size_t)live * sizeof m->y[0]);
        m->start = 0;
        m->end = live;
    }
    if (m->scan_count == IFGM_MAX_SCANS)
        forget_oldest(m);
    ifgm_real c = cos(pose[2]), s = sin(pose[2]);
    for (int i = 0; i < n; i++) {
        m->x[m->end + i] = pose[0] + c * points->x[i] - s * points->y[i];
        m->y[m->end + i] = pose[1] + s * points->x[i] + c * points->y[i];
    }
    m->end += n;
    int slot = (m->scan_first + m->scan_count) % IFGM_MAX_SCANS;
    m->scan_t[slot] = t;
    m->scan_size[slot] = n;
    m->scan_count++;
    while (m->scan_count > 0 && m->scan_t[m->scan_first] < t - m->horizon - m->period / 2)
        forget_oldest(m);
}

static ifgm_side side_of(ifgm_real first_angle, ifgm_real last_angle)
{
    if (last_angle < 0)
        return IFGM_SIDE_RIGHT;
    if (first_angle > 0)
        return IFGM_SIDE_LEFT;
    return IFGM_SIDE_BOTH;
}

int ifgm_cluster_points(const ifgm_scan_points *p, ifgm_real jump, ifgm_cluster *out)
{
    int count = 0;
    ifgm_real jump2 = jump * jump;
    for (int a = 0; a < p->n;) {
        int b = a + 1;
        ifgm_real nearest = p->range[a];
        while (b < p->n && p->ray[b] - p->ray[b - 1] <= 1) {
            ifgm_real dx = p->x[b] - p->x[b - 1], dy = p->y[b] - p->y[b - 1];
            if (dx * dx + dy * dy > jump2)
                break;
            if (p->range[b] < nearest)
                nearest = p->range[b];
            b++;
        }
        ifgm_cluster *c = &out[count++];
        c->first = p->ray[a];
        c->last = p->ray[b - 1];
        c->begin = a;
        c->end = b;
        c->nearest = nearest;
        c->side = side_of(p->angle[a], p->angle[b - 1]);
        a = b;
    }
    return count;
}

int ifgm_gaps_between(const ifgm_scan_points *p, const ifgm_cluster *clusters, int n_clusters,
                      ifgm_gap *out)
{
    for (int k = 0; k + 1 < n_clusters; k++) {
        const ifgm_cluster *a = &clusters[k], *b = &clusters[k + 1];
        int best_i = a->begin, best_j = b->begin;
        ifgm_real best = IFGM_INF;
        for (int i = a->begin; i < a->end; i++)
            for (int j = b->begin; j < b->end; j++) {
                ifgm_real dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j];
                ifgm_real d2 = dx * dx + dy * dy;
                if (d2 < best) {
                    best = d2;
                    best_i = i;
                    best_j = j;
                }
            }
        ifgm_gap *g = &out[k];
        g->right.x = p->x[best_i];
        g->right.y = p->y[best_i];
        g->left.x = p->x[best_j];
        g->left.y = p->y[best_j];
        g->width = hypot(g->left.x - g->right.x, g->left.y - g->right.y);
    }
    return n_clusters > 1 ? n_clusters - 1 : 0;
}

/* The offset of (x, y) from (ox, oy) in the frame facing (cos, sin) = (c, s): how far
 * along that direction, and how far to its left. */
static void along_across(ifgm_real x, ifgm_real y, ifgm_real ox, ifgm_real oy, ifgm_real c,
                         ifgm_real s, ifgm_real *along, ifgm_real *across)
{
    ifgm_real dx = x - ox, dy = y - oy;
    *along = c * dx + s * dy;
    *across = -s * dx + c * dy;
}

ifgm_real ifgm_free_length(const ifgm_real *x, const ifgm_real *y, int n, ifgm_real ox,
                           ifgm_real oy, ifgm_real direction, ifgm_real half_width)
{
    ifgm_real c = cos(direction), s = sin(direction), best = IFGM_INF, along, across;
    for (int i = 0; i < n; i++) {
        along_across(x[i], y[i], ox, oy, c, s, &along, &across);
        if (along >= 0 && fabs(across) < half_width && along < best)
            best = along;
    }
    return best;
}

ifgm_real ifgm_disc_travel(const ifgm_real *x, const ifgm_real *y, int n, ifgm_real ox,
                           ifgm_real oy, ifgm_real direction, ifgm_real radius)
{
    ifgm_real c = cos(direction), s = sin(direction), best = IFGM_INF, along, across;
    for (int i = 0; i < n; i++) {
        along_across(x[i], y[i], ox, oy, c, s, &along, &across);
        if (along >= 0 && fabs(across) < radius) {
            ifgm_real touch = along - sqrt(radius * radius - across * across);
            if (touch < best)
                best = touch;
        }
    }
    return best < 0 ? 0 : best;
}

int ifgm_nearest_point(const ifgm_real *x, const ifgm_real *y, int n, ifgm_real ox,
                       ifgm_real oy)
{
    int best_i = -1;
    ifgm_real best = IFGM_INF;
    for (int i = 0; i < n; i++) {
        ifgm_real dx = x[i] - ox, dy = y[i] - oy, d2 = dx * dx + dy * dy;
        if (d2 < best) {
            best = d2;
            best_i = i;
        }
    }
    return best_i;
}

int ifgm_nearest_point_near(const ifgm_real *x, const ifgm_real *y, int n, ifgm_real ox,
                            ifgm_real oy, ifgm_real cx, ifgm_real cy, ifgm_real reach)
{
    int best_i = -1;
    ifgm_real best = IFGM_INF, reach2 = reach * reach;
    for (int i = 0; i < n; i++) {
        ifgm_real ex = x[i] - cx, ey = y[i] - cy;
        if (ex * ex + ey * ey > reach2)
            continue;
        ifgm_real dx = x[i] - ox, dy = y[i] - oy, d2 = dx * dx + dy * dy;
        if (d2 < best) {
            best = d2;
            best_i = i;
        }
    }
    return best_i;
}

ifgm_point ifgm_to_world(ifgm_real px, ifgm_real py, const ifgm_real pose[3])
{
    ifgm_real c = cos(pose[2]), s = sin(pose[2]);
    ifgm_point w = {pose[0] + c * px - s * py, pose[1] + s * px + c * py};
    return w;
}
