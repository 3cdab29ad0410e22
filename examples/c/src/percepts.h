/* Percepts: what a planner makes of one scan and of the scans it has just seen (section 4
 * of the paper: returns "resolved into rectangular coordinates", obstacles as clusters of
 * them, the gaps between consecutive obstacles). The reference is ifgm_ref/paper/percepts/ and
 * ifgm_ref/core/laserscan.py; docs/flowchart.md and docs/errata.md (rows 11, 16-20, 30) say
 * what each percept means. Nothing here knows the map, and nothing allocates: the caller
 * owns every struct (they are large: keep them in static storage, not on the stack).
 *
 * Port choices (the reference's results to the last bit or two):
 * - distances compared with a threshold, and nearest points, use squared distances;
 * - the remembered points are kept as two arrays, x and y (structure of arrays). */
#ifndef IFGM_PERCEPTS_H
#define IFGM_PERCEPTS_H

#include "types.h"

/* Most obstacle points remembered (the paper's sensor: 76 rays x 82 scans = 6,232). */
#ifndef IFGM_MAX_POINTS
#define IFGM_MAX_POINTS 65536
#endif
/* Most scans remembered (memory_horizon / dt + 2: 82 for the paper's robot). */
#ifndef IFGM_MAX_SCANS
#define IFGM_MAX_SCANS 512
#endif

/* The paper's beams (section 4, Figure 2; errata rows 11 and 30), robot frame, REP-103. */
#define IFGM_FRONT_HALF_WIDTH ((ifgm_real)22.5 * (IFGM_PI / 180))
#define IFGM_PAPER_HALF_FOV (3 * IFGM_FRONT_HALF_WIDTH)
/* Rays land on the +-22.5 degree borders only to within rounding: this keeps them front. */
#define IFGM_BORDER_TOLERANCE IFGM_ROUNDING

typedef enum { IFGM_BEAM_NONE, IFGM_BEAM_RIGHT, IFGM_BEAM_FRONT, IFGM_BEAM_LEFT } ifgm_beam;
typedef enum { IFGM_SIDE_RIGHT, IFGM_SIDE_LEFT, IFGM_SIDE_BOTH } ifgm_side;

typedef struct {
    ifgm_real x, y;
} ifgm_point;

/* One sensor's ray geometry, worked out when the sensor first appears (the reference caches
 * it per sensor too): every ray's angle, cosine, sine and beam, and the rays of the paper's
 * 135-degree view (LaserScan.window), whose angles count from the view's first ray. */
typedef struct {
    ifgm_real angle_min, angle_increment;
    int n;
    ifgm_real angle[IFGM_MAX_RAYS], cos[IFGM_MAX_RAYS], sin[IFGM_MAX_RAYS];
    unsigned char beam[IFGM_MAX_RAYS]; /* ifgm_beam of each ray */
    int view_first, view_n; /* the view: rays view_first .. view_first + view_n - 1 */
    ifgm_real view_angle[IFGM_MAX_RAYS], view_cos[IFGM_MAX_RAYS], view_sin[IFGM_MAX_RAYS];
    unsigned char view_beam[IFGM_MAX_RAYS]; /* ifgm_beam of each view ray */
} ifgm_rays;

/* Work out `rays` for a sensor, unless it holds that sensor already. Returns IFGM_OK or
 * IFGM_TOO_MANY_RAYS. (A view of fewer than two rays is IFGM's error, not the rays'.) */
int ifgm_rays_for(ifgm_rays *rays, ifgm_real angle_min, ifgm_real angle_increment, int n);

/* The beam of a robot-frame angle: borders +-22.5 degrees front, beyond +-67.5 none. */
ifgm_beam ifgm_beam_of(ifgm_real angle);

/* The returns of one scan as robot-frame points, in ray order. */
typedef struct {
    int n;
    int ray[IFGM_MAX_RAYS];         /* the ray of each point */
    ifgm_real angle[IFGM_MAX_RAYS]; /* its robot-frame angle */
    ifgm_real range[IFGM_MAX_RAYS];
    ifgm_real x[IFGM_MAX_RAYS], y[IFGM_MAX_RAYS];
} ifgm_scan_points;

/* The points of `ranges` (n rays with the given angles, cosines and sines) as a sensor that
 * sees no farther than `limit` reports them (LaserScan.limited): a return beyond `limit`
 * or +inf or NAN gives no point, -inf (nearer than range_min) a point at
 * min(range_min, limit). */
void ifgm_scan_points_of(ifgm_scan_points *out, const ifgm_real *ranges, int n,
                         ifgm_real range_min, ifgm_real limit, const ifgm_real *angle,
                         const ifgm_real *cos_a, const ifgm_real *sin_a);

/* The obstacle points of the last `horizon` seconds, world frame, oldest first
 * (PerceptMemory): a short-lived record of the robot's own percepts, not a map. */
typedef struct {
    ifgm_real horizon, period; /* period: the time between scans */
    int start, end; /* the live points are x[start..end), y[start..end) */
    int scan_first, scan_count; /* a ring of the remembered scans' times and sizes */
    ifgm_real scan_t[IFGM_MAX_SCANS];
    int scan_size[IFGM_MAX_SCANS];
    ifgm_real x[IFGM_MAX_POINTS], y[IFGM_MAX_POINTS];
} ifgm_memory;

/* Forget everything; remember `horizon` seconds of scans taken every `period` from now on. */
void ifgm_memory_clear(ifgm_memory *memory, ifgm_real horizon, ifgm_real period);
/* Remember `points` (robot frame) seen at time t from `pose`; forget the scans seen more
 * than `horizon` before t, the edge decided half a period out (the scan exactly `horizon`
 * old is kept, whatever the rounding of the times). If they do not fit the buffers (an episode whose times jump, on
 * a build sized too small), the oldest scans are forgotten first. */
void ifgm_memory_add(ifgm_memory *memory, ifgm_real t, const ifgm_real pose[3],
                     const ifgm_scan_points *points);

/* One obstacle: the points begin .. end - 1 of a scan's points (rays first .. last). */
typedef struct {
    int first, last, begin, end;
    ifgm_real nearest; /* range of its nearest return */
    ifgm_side side;    /* all returns right of the heading, left of it, or some of each */
} ifgm_cluster;

/* Group the points into obstacles, right to left: a missing ray or a step wider than
 * `jump` starts a new one (cluster_points). Writes at most points->n clusters; returns how
 * many. */
int ifgm_cluster_points(const ifgm_scan_points *points, ifgm_real jump, ifgm_cluster *out);

/* The gap between two consecutive obstacles: their closest pair of returns, robot frame. */
typedef struct {
    ifgm_point right, left;
    ifgm_real width;
} ifgm_gap;

/* The gaps between consecutive clusters, right to left (gaps_between, our reading: the
 * nearest points); returns how many (n_clusters - 1, or 0). */
int ifgm_gaps_between(const ifgm_scan_points *points, const ifgm_cluster *clusters,
                      int n_clusters, ifgm_gap *out);

/* How far the corridor of `half_width` from (ox, oy) along `direction` is free of the n
 * points (x, y): the distance along its axis to the first point inside it, +inf if none;
 * points behind the origin do not count (free_length). */
ifgm_real ifgm_free_length(const ifgm_real *x, const ifgm_real *y, int n, ifgm_real ox,
                           ifgm_real oy, ifgm_real direction, ifgm_real half_width);

/* How far a disc of `radius` at (ox, oy) can move along `direction` before it touches one
 * of the points: +inf if never, 0 if one is inside it already (disc_travel). */
ifgm_real ifgm_disc_travel(const ifgm_real *x, const ifgm_real *y, int n, ifgm_real ox,
                           ifgm_real oy, ifgm_real direction, ifgm_real radius);

/* The index of the point nearest (ox, oy), the first of equals; -1 if n is 0. */
int ifgm_nearest_point(const ifgm_real *x, const ifgm_real *y, int n, ifgm_real ox,
                       ifgm_real oy);

/* The index of the point nearest (ox, oy) among those within `reach` of (cx, cy); -1 if
 * none is. */
int ifgm_nearest_point_near(const ifgm_real *x, const ifgm_real *y, int n, ifgm_real ox,
                            ifgm_real oy, ifgm_real cx, ifgm_real cy, ifgm_real reach);

/* A robot-frame point in the world frame, seen from `pose` (to_world). */
ifgm_point ifgm_to_world(ifgm_real px, ifgm_real py, const ifgm_real pose[3]);

#endif
