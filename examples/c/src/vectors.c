/* The vectors' tolerances and the reports of mismatches: see vectors.h. */
#include "vectors.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

/* 2 pi in double: the period of the compared directions (Python's 2.0 * math.pi). */
static const double TWO_PI = 2.0 * 3.14159265358979323846;

int vectors_tolerance_of(vectors_check *check, const char *quantity,
                         vectors_tolerance *tolerance)
{
    const json_document *doc = check->doc;
    int entry = json_member(doc, json_member(doc, 0, "tolerances"), quantity);
    int set = json_member(doc, entry, check->precision);
    int periodic = json_member(doc, entry, "periodic");
    if (json_number(doc, json_member(doc, set, "abs"), &tolerance->absolute) != 0 ||
        json_number(doc, json_member(doc, set, "rel"), &tolerance->relative) != 0 ||
        !(json_is(doc, periodic, JSON_TRUE) || json_is(doc, periodic, JSON_FALSE))) {
        vectors_mismatch(check, "the file has no tolerances.%s.%s {abs, rel} and periodic",
                         quantity, check->precision);
        return -1;
    }
    tolerance->periodic = json_is(doc, periodic, JSON_TRUE);
    return 0;
}

int vectors_allows(const vectors_tolerance *tolerance, double expected, double actual)
{
    if (!isfinite(actual))
        return 0;
    double difference = actual - expected;
    if (tolerance->periodic)
        difference = remainder(difference, TWO_PI);
    return fabs(difference) <= tolerance->absolute + tolerance->relative * fabs(expected);
}

const char *vectors_describe(const vectors_tolerance *tolerance, char out[64])
{
    int n = snprintf(out, 64, "tolerance %g", tolerance->absolute);
    if (tolerance->relative != 0)
        n += snprintf(out + n, 64 - (size_t)n, " + %g * |expected|", tolerance->relative);
    if (tolerance->periodic)
        snprintf(out + n, 64 - (size_t)n, ", modulo 2 pi");
    return out;
}

void vectors_mismatch(vectors_check *check, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vprintf(format, args);
    va_end(args);
    putchar('\n');
    check->mismatches++;
}

void vectors_skip(vectors_check *check, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fputs("ifgm_vectors: warning: ", stderr);
    vfprintf(stderr, format, args);
    va_end(args);
    fputc('\n', stderr);
    check->skipped++;
}
