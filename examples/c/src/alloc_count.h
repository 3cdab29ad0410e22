/* Count the heap allocations a program makes, to pin that the planners make none.
 *
 * Link the program with GNU ld's -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free:
 * every call to these four from the program's own objects (the planners' among them) then
 * goes through this file, which counts the calls made between alloc_count_start and
 * alloc_count_stop and passes each on to the C library. Calls made inside the C library
 * itself are not seen; the planners call nothing there but <math.h>. */
#ifndef IFGM_ALLOC_COUNT_H
#define IFGM_ALLOC_COUNT_H

/* Start counting from zero. */
void alloc_count_start(void);

/* Stop counting; return the calls counted since alloc_count_start. */
long alloc_count_stop(void);

/* Whether the program was linked with the wraps: 1 if a malloc and a free made here are
 * counted, else 0 (and every count would be 0 whatever the program does). */
int alloc_count_works(void);

#endif
