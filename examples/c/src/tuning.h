/* Every planner parameter is a formula in the robot and the sensor (docs/parameters.md,
 * ifgm_ref/planners/tuning.py; errata row 29): r the radius, v the speed, w the turn rate,
 * dt the time step, R the sensor's range, fov its field of view. */
#ifndef IFGM_TUNING_H
#define IFGM_TUNING_H

#include "types.h"

/* `out` = `given`, each unset (NAN) field replaced by its default for the episode. Returns
 * IFGM_OK, IFGM_BAD_EPISODE when the robot or sensor is out of its domain, or
 * IFGM_BAD_PARAMETER when a value is not a finite number > 0 (FGM's alpha, beta and
 * inflation_margin may be 0). */
int ifgm_resolve_tuning(ifgm_tuning *out, const ifgm_episode *episode, const ifgm_tuning *given);

#endif
