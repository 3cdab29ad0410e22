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
#define IFGM_INF ((ifgm_real)INFINITY)

#endif
