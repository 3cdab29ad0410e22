/* Heap allocation counting by GNU ld's --wrap: see alloc_count.h. */
#include "alloc_count.h"

#include <stdlib.h>

void *__real_malloc(size_t size);
void *__real_calloc(size_t count, size_t size);
void *__real_realloc(void *memory, size_t size);
void __real_free(void *memory);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t count, size_t size);
void *__wrap_realloc(void *memory, size_t size);
void __wrap_free(void *memory);

/* volatile: malloc and free update them behind the compiler's back (it takes them to be
 * the C library's, which cannot see these statics) */
static volatile int counting;
static volatile long calls;

void *__wrap_malloc(size_t size)
{
    calls += counting;
    return __real_malloc(size);
}

void *__wrap_calloc(size_t count, size_t size)
{
    calls += counting;
    return __real_calloc(count, size);
}

void *__wrap_realloc(void *memory, size_t size)
{
    calls += counting;
    return __real_realloc(memory, size);
}

void __wrap_free(void *memory)
{
    calls += counting;
    __real_free(memory);
}

void alloc_count_start(void)
{
    calls = 0;
    counting = 1;
}

long alloc_count_stop(void)
{
    counting = 0;
    return calls;
}

int alloc_count_works(void)
{
    void *volatile memory; /* volatile: the compiler may not drop the pair */
    alloc_count_start();
    memory = malloc(1);
    free(memory);
    return alloc_count_stop() == 2;
}
