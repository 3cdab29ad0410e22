/* The number type of the port: double by default, float with -DIFGM_FLOAT.
 *
 * Everything the planners compute is an ifgm_real. <tgmath.h> (C99) picks the float or the
 * double version of each math function from its argument, so the same source builds both. */
#ifndef IFGM_REAL_H
#define IFGM_REAL_H

#include <tgmath.h>

#ifdef IFGM_FLOAT
typedef float ifgm_real;
#else
typedef double ifgm_real;
#endif

#define IFGM_PI ((ifgm_real)3.14159265358979323846)

/* The reference's tolerances for rounding (1e-9: a ray on a beam's border, two side beams
 * equally open) absorb double's rounding; float rounds about 1e8 times coarser (1e-7
 * relative), so a float build widens them to 1e-5 or its ties fall either way. */
#ifdef IFGM_FLOAT
#define IFGM_ROUNDING ((ifgm_real)1e-5)
#else
#define IFGM_ROUNDING ((ifgm_real)1e-9)
#endif
#define IFGM_INF ((ifgm_real)INFINITY)

#endif
