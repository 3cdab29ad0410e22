/* Checking the port against the test vectors (docs/vectors-format.md), as
 * ifgm_ref/oracle/vectors/check.py checks a Python implementation: the equation cases against
 * the functions of equations.h (vectors_equations.c), the reference traces against the
 * planners of planners.h (vectors_traces.c). Mismatches are printed on stdout in check.py's
 * style, "quantity = actual, but should be expected (tolerance) [where]", and counted.
 *
 * A host tool's module (ifgm_vectors): it reads the whole file, allocates freely, and is no
 * part of the planners. */
#ifndef IFGM_VECTORS_H
#define IFGM_VECTORS_H

#include "json.h"

/* One run of the checks over a parsed vectors file. */
typedef struct {
    const json_document *doc; /* the file; token 0 is its top-level object */
    const char *precision;    /* which tolerance set: "double" or "float32" */
    int cases;                /* equation cases checked (each with all its forms) */
    int steps;                /* trace steps replayed */
    int mismatches;           /* mismatches reported */
    int skipped;              /* functions or traces the port lacks, skipped with a warning */
} vectors_check;

/* How close an output must be to its expected value: one quantity's tolerance, for the
 * check's precision. */
typedef struct {
    double absolute, relative;
    int periodic; /* compared modulo 2 pi */
} vectors_tolerance;

/* The tolerance of quantity (a key of the file's `tolerances`) for check's precision:
 * 0 and *tolerance, or -1 after reporting the file's lack of it as a mismatch. */
int vectors_tolerance_of(vectors_check *check, const char *quantity,
                         vectors_tolerance *tolerance);

/* Whether actual passes for expected: finite, and |actual - expected| (its remainder modulo
 * 2 pi if periodic) at most absolute + relative * |expected|. */
int vectors_allows(const vectors_tolerance *tolerance, double expected, double actual);

/* The tolerance as check.py writes it in a message: "tolerance 1e-09, modulo 2 pi". */
const char *vectors_describe(const vectors_tolerance *tolerance, char out[64]);

/* Print one mismatch (a printf format and its arguments, without the newline) and count it. */
void vectors_mismatch(vectors_check *check, const char *format, ...);

/* Print a warning that something the port lacks is skipped, and count it. */
void vectors_skip(vectors_check *check, const char *format, ...);

/* Check every form of every equation case (`equations`). */
void vectors_check_equations(vectors_check *check);

/* Replay every trace (`traces`) through a fresh planner of its kind; report each trace's
 * first mismatch. */
void vectors_check_traces(vectors_check *check);

#endif
