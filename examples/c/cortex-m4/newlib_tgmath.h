/* For a build against newlib (arm-none-eabi-gcc's C library): include this first
 * (-include cortex-m4/newlib_tgmath.h).
 *
 * GCC's <tgmath.h> names, for every type-generic function, its complex variants too, so each
 * must be declared. newlib's <complex.h> (3.3, 4.x) declares these long double ones only on
 * Cygwin, and `cos(x)` fails to compile ("'ccosl' undeclared"). The port never calls them
 * (every argument is real: the real function is picked); declaring them is enough. */
#ifndef IFGM_NEWLIB_TGMATH_H
#define IFGM_NEWLIB_TGMATH_H

long double _Complex cacosl(long double _Complex);
long double _Complex ccosl(long double _Complex);
long double _Complex csinl(long double _Complex);
long double _Complex ctanl(long double _Complex);
long double _Complex cacoshl(long double _Complex);
long double _Complex casinhl(long double _Complex);
long double _Complex catanhl(long double _Complex);
long double _Complex ccoshl(long double _Complex);
long double _Complex csinhl(long double _Complex);
long double _Complex ctanhl(long double _Complex);
long double _Complex cexpl(long double _Complex);
long double _Complex clogl(long double _Complex);
long double _Complex cpowl(long double _Complex, long double _Complex);

#endif
