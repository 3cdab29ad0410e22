/* The JSON-lines protocol's messages and the port's structs: see protocol.h. */
#include "protocol.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* The derived angles of `reset.sensor` and the scan's `angle_max` must agree with the
 * others to this, rad (wire.py's ANGLE_TOLERANCE and LaserScan's check). */
#define ANGLE_TOLERANCE 1e-9

/* The planners' parameters by their protocol names. */
#define TUNING_FIELD(name) {#name, offsetof(ifgm_tuning, name)}
static const struct {
    const char *name;
    size_t offset;
} tuning_fields[] = {
    TUNING_FIELD(standoff_margin), TUNING_FIELD(corridor_margin), TUNING_FIELD(hit_margin),
    TUNING_FIELD(memory_horizon),  TUNING_FIELD(return_radius),   TUNING_FIELD(min_loop),
    TUNING_FIELD(view_range),      TUNING_FIELD(step_length),     TUNING_FIELD(d_th),
    TUNING_FIELD(d_obs),           TUNING_FIELD(d_look),          TUNING_FIELD(w_g),
    TUNING_FIELD(w_d),             TUNING_FIELD(jump),            TUNING_FIELD(preempt_margin),
    TUNING_FIELD(turn_done),       TUNING_FIELD(alpha),           TUNING_FIELD(beta),
    TUNING_FIELD(inflation_margin),
};
#define TUNING_FIELDS (sizeof tuning_fields / sizeof tuning_fields[0])

static const char *const type_names[] = {"reset", "ready", "observe", "command", "bye"};

static int failf(protocol_error *error, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(error->text, sizeof error->text, format, args);
    va_end(args);
    return -1;
}

/* What token is, for "got ...": a number's text (1e400 is one), a string quoted, else its
 * type ("null", "object", ...). */
static const char *shown(const json_document *doc, int token, char out[48])
{
    if (json_is(doc, token, JSON_STRING)) {
        char text[40];
        size_t length = json_string_copy(doc, token, text, sizeof text);
        snprintf(out, 48, "'%s'%s", text, length >= sizeof text ? "..." : "");
        return out;
    }
    if (!json_is(doc, token, JSON_NUMBER))
        return json_type_name(doc, token);
    const json_token *t = &doc->tokens[token];
    int length = (int)(t->end - t->start);
    snprintf(out, 48, "%.*s%s", length < 40 ? length : 40, doc->text + t->start,
             length > 40 ? "..." : "");
    return out;
}

/* Member name of object as a token that exists; -1 and error "where.name: missing". */
static int member(const json_document *doc, int object, const char *where, const char *name,
                  protocol_error *error)
{
    int token = json_member(doc, object, name);
    return token >= 0 ? token : failf(error, "%s.%s: missing", where, name);
}

/* The finite number at token (named where, e.g. "reset.goal[1]"): 0, or -1 and error. */
static int finite_at(const json_document *doc, int token, const char *where, double *out,
                     protocol_error *error)
{
    char text[48];
    if (json_number(doc, token, out) != 0 || !isfinite(*out))
        return failf(error, "%s: must be a finite number, got %s", where, shown(doc, token, text));
    return 0;
}

/* Member name of object as a finite number. */
static int double_member(const json_document *doc, int object, const char *where,
                         const char *name, double *out, protocol_error *error)
{
    char path[64];
    int token = member(doc, object, where, name, error);
    snprintf(path, sizeof path, "%s.%s", where, name);
    return token < 0 ? -1 : finite_at(doc, token, path, out, error);
}

/* The same, stored in an ifgm_real (rounded to float in a float build). */
static int number(const json_document *doc, int object, const char *where, const char *name,
                  ifgm_real *out, protocol_error *error)
{
    double value;
    if (double_member(doc, object, where, name, &value, error) != 0)
        return -1;
    *out = (ifgm_real)value;
    return 0;
}

/* Member name of object as an array of count finite numbers. */
static int numbers(const json_document *doc, int object, const char *where, const char *name,
                   ifgm_real *out, int count, protocol_error *error)
{
    int array = member(doc, object, where, name, error);
    if (array < 0)
        return -1;
    if (!json_is(doc, array, JSON_ARRAY))
        return failf(error, "%s.%s: must be an array of %d numbers, got %s", where, name, count,
                     json_type_name(doc, array));
    if (json_size(doc, array) != count)
        return failf(error, "%s.%s: must be an array of %d numbers, got %d", where, name, count,
                     json_size(doc, array));
    int i = 0;
    for (int e = json_first(doc, array); e >= 0; e = json_next(doc, e), i++) {
        char path[64];
        double value;
        snprintf(path, sizeof path, "%s.%s[%d]", where, name, i);
        if (finite_at(doc, e, path, &value, error) != 0)
            return -1;
        out[i] = (ifgm_real)value;
    }
    return 0;
}

/* Member name of object as an object. */
static int object_member(const json_document *doc, int object, const char *where,
                         const char *name, protocol_error *error)
{
    int token = member(doc, object, where, name, error);
    if (token >= 0 && !json_is(doc, token, JSON_OBJECT))
        return failf(error, "%s.%s: must be an object, got %s", where, name,
                     json_type_name(doc, token));
    return token;
}

int protocol_type_of(const json_document *doc, int message, protocol_type *type,
                     protocol_error *error)
{
    if (!json_is(doc, message, JSON_OBJECT))
        return failf(error, "message: must be a JSON object, got %s", json_type_name(doc, message));
    int token = member(doc, message, "message", "type", error);
    if (token < 0)
        return -1;
    for (int t = PROTOCOL_RESET; t <= PROTOCOL_BYE; t++) {
        if (json_string_equals(doc, token, type_names[t])) {
            *type = (protocol_type)t;
            return 0;
        }
    }
    char text[48];
    return failf(error, "message.type: %s, but should be one of reset, ready, observe, command, "
                 "bye", shown(doc, token, text));
}

/* That message is an object of type expected. */
static int expect_type(const json_document *doc, int message, protocol_type expected,
                       protocol_error *error)
{
    protocol_type type;
    if (protocol_type_of(doc, message, &type, error) != 0)
        return -1;
    if (type != expected)
        return failf(error, "type '%s', but should be '%s'", type_names[type],
                     type_names[expected]);
    return 0;
}

/* A derived angle of `reset.sensor` as computed from the others, within ANGLE_TOLERANCE. */
static int agrees(double got, double want, const char *where, protocol_error *error)
{
    if (fabs(got - want) <= ANGLE_TOLERANCE)
        return 0;
    return failf(error, "%s: %.17g, but should be %.17g", where, got, want);
}

static int read_sensor(const json_document *doc, int sensor, ifgm_episode *episode,
                       protocol_error *error)
{
    const char *where = "reset.sensor";
    double fov, rays, angle_min, angle_max, angle_increment;
    if (double_member(doc, sensor, where, "fov", &fov, error) != 0 ||
        double_member(doc, sensor, where, "rays", &rays, error) != 0 ||
        number(doc, sensor, where, "range_min", &episode->range_min, error) != 0 ||
        number(doc, sensor, where, "range_max", &episode->range_max, error) != 0 ||
        double_member(doc, sensor, where, "angle_min", &angle_min, error) != 0 ||
        double_member(doc, sensor, where, "angle_max", &angle_max, error) != 0 ||
        double_member(doc, sensor, where, "angle_increment", &angle_increment, error) != 0)
        return -1;
    if (rays != floor(rays) || rays < 2 || rays > INT_MAX)
        return failf(error, "reset.sensor.rays: must be an integer >= 2, got %.17g", rays);
    if (agrees(angle_min, -0.5 * fov, "reset.sensor.angle_min", error) != 0 ||
        agrees(angle_max, 0.5 * fov, "reset.sensor.angle_max", error) != 0 ||
        agrees(angle_increment, fov / (rays - 1), "reset.sensor.angle_increment", error) != 0)
        return -1;
    episode->fov = (ifgm_real)fov;
    episode->rays = (int)rays;
    episode->angle_min = (ifgm_real)angle_min;
    episode->angle_increment = (ifgm_real)angle_increment;
    return 0;
}

/* The index in tuning_fields of the parameter named by key token, or -1. */
static int tuning_index(const json_document *doc, int key)
{
    for (size_t i = 0; i < TUNING_FIELDS; i++)
        if (json_string_equals(doc, key, tuning_fields[i].name))
            return (int)i;
    return -1;
}

static int read_params(const json_document *doc, int params, ifgm_tuning *tuning,
                       protocol_error *error)
{
    ifgm_tuning_unset(tuning);
    for (int key = json_first(doc, params); key >= 0; key = json_next(doc, key)) {
        int i = tuning_index(doc, key);
        if (i < 0)
            continue; /* protocol_unknown_params names it */
        char path[64];
        double value;
        snprintf(path, sizeof path, "reset.params.%s", tuning_fields[i].name);
        if (finite_at(doc, key + 1, path, &value, error) != 0)
            return -1;
        *(ifgm_real *)((char *)tuning + tuning_fields[i].offset) = (ifgm_real)value;
    }
    return 0;
}

/* The robot's optional dynamics (RobotParams' braking, acceleration and response, and the
 * latency noise field): each absent one takes its default (b and A infinite, the paper's
 * robot; no response time, no latency). b and A are any numbers, as Python reads them (1e400
 * is an infinity: the default), their domain left to the init; the response a finite
 * number; the latency an integer >= 0. */
static int read_dynamics(const json_document *doc, int robot, ifgm_episode *episode,
                         protocol_error *error)
{
    const char *where = "reset.robot";
    const char *limits[] = {"braking", "acceleration"};
    ifgm_real *values[] = {&episode->braking, &episode->acceleration};
    char text[48];
    double value;
    episode->braking = episode->acceleration = IFGM_INF;
    episode->response = 0;
    episode->latency = 0;
    for (int i = 0; i < 2; i++) {
        int token = json_member(doc, robot, limits[i]);
        if (token < 0)
            continue;
        if (json_number(doc, token, &value) != 0)
            return failf(error, "%s.%s: must be a number, got %s", where, limits[i],
                         shown(doc, token, text));
        *values[i] = (ifgm_real)value;
    }
    if (json_member(doc, robot, "response") >= 0 &&
        number(doc, robot, where, "response", &episode->response, error) != 0)
        return -1;
    if (json_member(doc, robot, "latency") >= 0) {
        if (double_member(doc, robot, where, "latency", &value, error) != 0)
            return -1;
        if (value != floor(value) || value < 0 || value > INT_MAX)
            return failf(error, "reset.robot.latency: must be an integer >= 0, got %.17g", value);
        episode->latency = (int)value;
    }
    return 0;
}

int protocol_read_reset(const json_document *doc, int message, ifgm_episode *episode,
                        ifgm_tuning *tuning, protocol_error *error)
{
    const char *where = "reset";
    int robot, sensor, params;
    if (expect_type(doc, message, PROTOCOL_RESET, error) != 0 ||
        numbers(doc, message, where, "start", episode->start, 3, error) != 0 ||
        numbers(doc, message, where, "goal", episode->goal, 2, error) != 0 ||
        (robot = object_member(doc, message, where, "robot", error)) < 0 ||
        number(doc, robot, "reset.robot", "radius", &episode->radius, error) != 0 ||
        number(doc, robot, "reset.robot", "speed", &episode->speed, error) != 0 ||
        number(doc, robot, "reset.robot", "max_turn_rate", &episode->max_turn_rate, error) != 0 ||
        read_dynamics(doc, robot, episode, error) != 0 ||
        (sensor = object_member(doc, message, where, "sensor", error)) < 0 ||
        read_sensor(doc, sensor, episode, error) != 0 ||
        number(doc, message, where, "dt", &episode->dt, error) != 0 ||
        number(doc, message, where, "goal_tolerance", &episode->goal_tolerance, error) != 0 ||
        (params = object_member(doc, message, where, "params", error)) < 0)
        return -1;
    return read_params(doc, params, tuning, error);
}

int protocol_unknown_params(const json_document *doc, int message, char *names, size_t size)
{
    int params = json_member(doc, message, "params"), count = 0;
    size_t used = 0;
    if (size > 0)
        names[0] = '\0';
    if (!json_is(doc, params, JSON_OBJECT))
        return 0;
    for (int key = json_first(doc, params); key >= 0; key = json_next(doc, key)) {
        if (tuning_index(doc, key) >= 0)
            continue;
        char name[64];
        json_string_copy(doc, key, name, sizeof name);
        if (used < size) {
            int n = snprintf(names + used, size - used, "%s'%s'", count ? ", " : "", name);
            used += n > 0 ? (size_t)n : 0;
        }
        count++;
    }
    return count;
}

/* Read `scan.ranges` (null: +INFINITY) into observation. */
static int read_ranges(const json_document *doc, int scan, ifgm_observation *observation,
                       protocol_error *error)
{
    int ranges = member(doc, scan, "observe.scan", "ranges", error);
    if (ranges < 0)
        return -1;
    if (!json_is(doc, ranges, JSON_ARRAY))
        return failf(error, "observe.scan.ranges: must be an array, got %s",
                     json_type_name(doc, ranges));
    if (json_size(doc, ranges) > IFGM_MAX_RAYS)
        return failf(error, "observe.scan.ranges: %d ranges, but this build holds at most "
                     "IFGM_MAX_RAYS = %d", json_size(doc, ranges), IFGM_MAX_RAYS);
    observation->n = 0;
    for (int e = json_first(doc, ranges); e >= 0; e = json_next(doc, e)) {
        double value = INFINITY;
        char text[48];
        if (!json_is(doc, e, JSON_NULL) && (json_number(doc, e, &value) != 0 || !isfinite(value)))
            return failf(error, "observe.scan.ranges[%d]: must be a finite number or null, got %s",
                         observation->n, shown(doc, e, text));
        observation->ranges[observation->n++] = (ifgm_real)value;
    }
    return 0;
}

/* The scan's angles (in double, before any rounding to float) against its n ranges, as
 * LaserScan checks them: at least 2 ranges, angle_max = angle_min + angle_increment (n - 1)
 * (math.isclose with rel_tol and abs_tol ANGLE_TOLERANCE). */
static int check_scan_angles(const double angles[3], int n, protocol_error *error)
{
    double expected = angles[0] + angles[2] * (n - 1), angle_max = angles[1];
    double tol = fmax(ANGLE_TOLERANCE, ANGLE_TOLERANCE * fmax(fabs(expected), fabs(angle_max)));
    if (n < 2 || fabs(angle_max - expected) > tol)
        return failf(error, "observe.scan: angle_max=%.17g, but should be angle_min + "
                     "angle_increment * (len(ranges) - 1) = %.17g for %d ranges",
                     angle_max, expected, n);
    return 0;
}

int protocol_read_observe(const json_document *doc, int message, ifgm_observation *observation,
                          protocol_error *error)
{
    const char *where = "observe.scan";
    int scan;
    double angles[3]; /* angle_min, angle_max, angle_increment */
    if (expect_type(doc, message, PROTOCOL_OBSERVE, error) != 0 ||
        number(doc, message, "observe", "t", &observation->t, error) != 0 ||
        numbers(doc, message, "observe", "pose", observation->pose, 3, error) != 0 ||
        numbers(doc, message, "observe", "goal", observation->goal, 2, error) != 0 ||
        (scan = object_member(doc, message, "observe", "scan", error)) < 0 ||
        double_member(doc, scan, where, "angle_min", &angles[0], error) != 0 ||
        double_member(doc, scan, where, "angle_max", &angles[1], error) != 0 ||
        double_member(doc, scan, where, "angle_increment", &angles[2], error) != 0 ||
        number(doc, scan, where, "range_min", &observation->range_min, error) != 0 ||
        number(doc, scan, where, "range_max", &observation->range_max, error) != 0 ||
        read_ranges(doc, scan, observation, error) != 0 ||
        check_scan_angles(angles, observation->n, error) != 0)
        return -1;
    observation->angle_min = (ifgm_real)angles[0];
    observation->angle_increment = (ifgm_real)angles[2];
    return 0;
}

int protocol_read_command(const json_document *doc, int message, protocol_command *command,
                          protocol_error *error)
{
    if (expect_type(doc, message, PROTOCOL_COMMAND, error) != 0 ||
        double_member(doc, message, "command", "heading", &command->heading, error) != 0 ||
        double_member(doc, message, "command", "speed", &command->speed, error) != 0)
        return -1;
    int branch = json_member(doc, message, "branch");
    if (branch >= 0 && !json_is(doc, branch, JSON_STRING) && !json_is(doc, branch, JSON_NULL))
        return failf(error, "command.branch: must be a string or null, got %s",
                     json_type_name(doc, branch));
    command->branch = json_is(doc, branch, JSON_STRING) ? branch : -1;
    return 0;
}

int protocol_write_ready(FILE *out)
{
    fputs("{\"type\": \"ready\"}\n", out);
    return ferror(out) ? -1 : 0;
}

void protocol_format_number(char out[PROTOCOL_NUMBER_SIZE], double x)
{
    for (int digits = 1; digits <= 17; digits++) {
        snprintf(out, PROTOCOL_NUMBER_SIZE, "%.*g", digits, x);
        if (strtod(out, NULL) == x)
            break; /* 17 digits always read back: a NaN ends there too */
    }
    if (strspn(out, "-0123456789") == strlen(out))
        strcat(out, ".0");
}

/* s as a JSON string: quotes, backslashes and control characters escaped. */
static void write_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s != '\0'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(out, "\\%c", c);
        else if (c < 0x20)
            fprintf(out, "\\u%04x", c);
        else
            fputc(c, out);
    }
    fputc('"', out);
}

int protocol_write_command(FILE *out, const ifgm_command *command, protocol_error *error)
{
    const char *names[] = {"behaviour", "branch", "stop"};
    const char *values[] = {command->behaviour, command->branch, command->stop};
    double heading = command->heading, speed = command->speed;
    char heading_text[PROTOCOL_NUMBER_SIZE], speed_text[PROTOCOL_NUMBER_SIZE];
    if (!isfinite(heading) || !isfinite(speed))
        return failf(error, "step returned heading=%.17g, speed=%.17g, which JSON cannot carry",
                     heading, speed);
    protocol_format_number(heading_text, heading);
    protocol_format_number(speed_text, speed);
    fprintf(out, "{\"type\": \"command\", \"heading\": %s, \"speed\": %s", heading_text,
            speed_text);
    for (int i = 0; i < 3; i++) {
        if (values[i] != NULL) {
            fprintf(out, ", \"%s\": ", names[i]);
            write_string(out, values[i]);
        }
    }
    fputs("}\n", out);
    return ferror(out) ? failf(error, "cannot write the reply") : 0;
}
