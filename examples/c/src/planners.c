/* The planner table: see planners.h. */
#include "planners.h"

#include <string.h>

#include "boundary_planner.h"
#include "fgm.h"
#include "ifgm.h"

static int ifgm_init_any(void *p, const ifgm_episode *e, const ifgm_tuning *t)
{
    return ifgm_init((ifgm_planner *)p, e, t);
}

static ifgm_command ifgm_step_any(void *p, const ifgm_observation *o)
{
    return ifgm_step((ifgm_planner *)p, o);
}

static int iba_init_any(void *p, const ifgm_episode *e, const ifgm_tuning *t)
{
    return iba_init((iba_planner *)p, e, t);
}

static ifgm_command iba_step_any(void *p, const ifgm_observation *o)
{
    return iba_step((iba_planner *)p, o);
}

static int distbug_init_any(void *p, const ifgm_episode *e, const ifgm_tuning *t)
{
    return distbug_init((distbug_planner *)p, e, t);
}

static ifgm_command distbug_step_any(void *p, const ifgm_observation *o)
{
    return distbug_step((distbug_planner *)p, o);
}

static int fgm_init_any(void *p, const ifgm_episode *e, const ifgm_tuning *t)
{
    return fgm_init((fgm_planner *)p, e, t);
}

static ifgm_command fgm_step_any(void *p, const ifgm_observation *o)
{
    return fgm_step((fgm_planner *)p, o);
}

const ifgm_planner_kind ifgm_planner_kinds[] = {
    {"ifgm", sizeof(ifgm_planner), ifgm_init_any, ifgm_step_any},
    {"iba", sizeof(iba_planner), iba_init_any, iba_step_any},
    {"distbug", sizeof(distbug_planner), distbug_init_any, distbug_step_any},
    {"fgm", sizeof(fgm_planner), fgm_init_any, fgm_step_any},
    {0, 0, 0, 0}};

const ifgm_planner_kind *ifgm_planner_kind_named(const char *name)
{
    for (const ifgm_planner_kind *k = ifgm_planner_kinds; k->name; k++)
        if (strcmp(k->name, name) == 0)
            return k;
    return 0;
}

size_t ifgm_planner_max_size(void)
{
    size_t size = 0;
    for (const ifgm_planner_kind *k = ifgm_planner_kinds; k->name; k++)
        if (k->size > size)
            size = k->size;
    return size;
}
