/* The vectors' reference traces replayed through the port's planners: see vectors.h.
 *
 * Each trace is replayed open loop, as check.py's replay_traces does: a fresh planner of the
 * trace's kind is reset with the recorded `reset` (its params hold every parameter), then
 * stepped through the recorded observations; each command's heading (modulo 2 pi) and speed
 * are compared with the recorded ones within the file's tolerances, and its branch for
 * equality when the planner reports one. The first mismatch of a trace ends its replay. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "planners.h"
#include "protocol.h"
#include "vectors.h"

static ifgm_episode episode;
static ifgm_tuning tuning;
static ifgm_observation observation;

/* A planner's storage and the tolerances of the compared command fields. */
typedef struct {
    void *planner;
    size_t size;
    vectors_tolerance heading, speed;
} replayer;

/* Compare got with the recorded command want at the step described by where; report the
 * first difference and return -1, or return 0. */
static int compare(vectors_check *check, const replayer *r, const ifgm_command *got,
                   const protocol_command *want, const char *where)
{
    const char *names[] = {"heading", "speed"};
    const vectors_tolerance *tolerances[] = {&r->heading, &r->speed};
    double actual[] = {got->heading, got->speed}, expected[] = {want->heading, want->speed};
    char a[PROTOCOL_NUMBER_SIZE], e[PROTOCOL_NUMBER_SIZE], tolerance[64], branch[64];
    for (int i = 0; i < 2; i++) {
        if (vectors_allows(tolerances[i], expected[i], actual[i]))
            continue;
        protocol_format_number(a, actual[i]);
        protocol_format_number(e, expected[i]);
        vectors_mismatch(check, "%s=%s, but should be %s (%s) %s", names[i], a, e,
                         vectors_describe(tolerances[i], tolerance), where);
        return -1;
    }
    if (got->branch == NULL || want->branch < 0 ||
        json_string_equals(check->doc, want->branch, got->branch))
        return 0;
    json_string_copy(check->doc, want->branch, branch, sizeof branch);
    vectors_mismatch(check, "branch='%s', but should be '%s' %s", got->branch, branch, where);
    return -1;
}

/* Step the planner through the steps of trace id, up to the first mismatch. */
static void step_through(vectors_check *check, const replayer *r, const ifgm_planner_kind *kind,
                        int steps, const char *id)
{
    const json_document *doc = check->doc;
    int i = 0;
    for (int s = json_first(doc, steps); s >= 0; s = json_next(doc, s), i++) {
        int observe = json_member(doc, s, "observe");
        int recorded = json_member(doc, s, "command");
        protocol_error error;
        protocol_command want;
        char where[160], t[PROTOCOL_NUMBER_SIZE], branch[64] = "None";
        double time = 0;
        check->steps++;
        json_number(doc, json_member(doc, observe, "t"), &time);
        protocol_format_number(t, time);
        json_string_copy(doc, json_member(doc, recorded, "branch"), branch, sizeof branch);
        snprintf(where, sizeof where, "[trace %s step %d, t=%s s, branch %s]", id, i, t, branch);
        if (protocol_read_observe(doc, observe, &observation, &error) != 0 ||
            protocol_read_command(doc, recorded, &want, &error) != 0) {
            vectors_mismatch(check, "the file's step: %s %s", error.text, where);
            return;
        }
        ifgm_command got = kind->step(r->planner, &observation);
        if (compare(check, r, &got, &want, where) != 0)
            return;
    }
}

/* Replay one trace through a fresh planner. */
static void replay(vectors_check *check, const replayer *r, int trace)
{
    const json_document *doc = check->doc;
    char id[64], name[32], unknown[256];
    protocol_error error;
    json_string_copy(doc, json_member(doc, trace, "id"), id, sizeof id);
    json_string_copy(doc, json_member(doc, trace, "planner"), name, sizeof name);
    const ifgm_planner_kind *kind = ifgm_planner_kind_named(name);
    if (kind == NULL) {
        vectors_skip(check, "the port has no planner '%s': trace %s is skipped", name, id);
        return;
    }
    int reset = json_member(doc, trace, "reset");
    if (protocol_read_reset(doc, reset, &episode, &tuning, &error) != 0) {
        vectors_mismatch(check, "the file's reset: %s [trace %s]", error.text, id);
        return;
    }
    if (protocol_unknown_params(doc, reset, unknown, sizeof unknown) > 0)
        vectors_skip(check, "trace %s: the port has no parameter(s) %s", id, unknown);
    memset(r->planner, 0, r->size);
    int status = kind->init(r->planner, &episode, &tuning);
    if (status != IFGM_OK) {
        vectors_mismatch(check, "reset failed: %s [trace %s]", ifgm_status_text(status), id);
        return;
    }
    step_through(check, r, kind, json_member(doc, trace, "steps"), id);
}

void vectors_check_traces(vectors_check *check)
{
    replayer r = {NULL, ifgm_planner_max_size(), {0, 0, 0}, {0, 0, 0}};
    if (vectors_tolerance_of(check, "heading", &r.heading) != 0 ||
        vectors_tolerance_of(check, "speed", &r.speed) != 0)
        return;
    r.planner = malloc(r.size);
    if (r.planner == NULL) {
        vectors_mismatch(check, "cannot allocate the planner's %zu bytes", r.size);
        return;
    }
    int traces = json_member(check->doc, 0, "traces");
    for (int t = json_first(check->doc, traces); t >= 0; t = json_next(check->doc, t))
        replay(check, &r, t);
    free(r.planner);
}
