/* The planners of the port, by their protocol names, for programs that pick one at run time
 * (the JSON-lines program, the benchmark). Each planner is a struct the caller owns (static
 * storage: nothing is allocated) with an init and a step function:
 *
 *     static ifgm_planner planner;                    // ifgm.h
 *     int status = ifgm_init(&planner, &episode, &tuning);
 *     ifgm_command command = ifgm_step(&planner, &observation);
 */
#ifndef IFGM_PLANNERS_H
#define IFGM_PLANNERS_H

#include <stddef.h>

#include "types.h"

typedef struct {
    const char *name; /* `ifgm-ref planners` name: "ifgm", "iba", "distbug", "fgm" */
    size_t size;      /* sizeof the planner's struct */
    int (*init)(void *planner, const ifgm_episode *episode, const ifgm_tuning *tuning);
    ifgm_command (*step)(void *planner, const ifgm_observation *observation);
} ifgm_planner_kind;

/* The planners, ended by an entry whose name is NULL. */
extern const ifgm_planner_kind ifgm_planner_kinds[];

/* The planner named `name`, or NULL. */
const ifgm_planner_kind *ifgm_planner_kind_named(const char *name);

/* The largest planner struct: a buffer this big (and aligned like a double) holds any. */
size_t ifgm_planner_max_size(void);

#endif
