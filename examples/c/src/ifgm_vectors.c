/* ifgm_vectors: check the C port against the test vectors (docs/vectors-format.md).
 *
 *     ifgm-ref vectors --out vectors.json
 *     ifgm_vectors vectors.json [--precision double|float32]
 *
 * Checks every equation case against equations.h and replays every trace through the planner
 * it names (vectors.h), printing each mismatch on stdout in the style of
 * ifgm_ref/oracle/vectors/check.py, then one summary line:
 *
 *     177 equation cases, 359 trace steps: 0 mismatches (double tolerances)
 *
 * --precision picks the file's tolerance set; the default is the build's (double, or float32
 * with -DIFGM_FLOAT). Exit status: 0 without a mismatch, 1 with one or more, 2 on a usage
 * error or a file that cannot be read or is not a version-1 vectors file. A host tool: it
 * reads the whole file into memory. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "json.h"
#include "vectors.h"

#define FORMAT_NAME "ifgm-ref-vectors"
#define FORMAT_VERSION 1

enum { EXIT_OK = 0, EXIT_MISMATCH = 1, EXIT_BAD_INPUT = 2 };

/* The arguments: the file, and the precision whose tolerances apply. */
typedef struct {
    const char *path;
    const char *precision;
} arguments;

static const char USAGE[] = "usage: ifgm_vectors VECTORS.json [--precision double|float32]\n";

/* Read the arguments: 0, or an exit status after --help or a usage error. */
static int read_arguments(int argc, char **argv, arguments *args)
{
#ifdef IFGM_FLOAT
    args->precision = "float32";
#else
    args->precision = "double";
#endif
    args->path = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            fputs(USAGE, stdout);
            return EXIT_OK;
        }
        if (strcmp(argv[i], "--precision") == 0 && i + 1 < argc &&
            (strcmp(argv[i + 1], "double") == 0 || strcmp(argv[i + 1], "float32") == 0)) {
            args->precision = argv[++i];
        } else if (argv[i][0] != '-' && args->path == NULL) {
            args->path = argv[i];
        } else {
            fprintf(stderr, "ifgm_vectors: error: unrecognized argument '%s'\n%s", argv[i],
                    USAGE);
            return EXIT_BAD_INPUT;
        }
    }
    if (args->path == NULL) {
        fprintf(stderr, "ifgm_vectors: error: no VECTORS.json given\n%s", USAGE);
        return EXIT_BAD_INPUT;
    }
    return -1;
}

/* The whole file at path, NUL-terminated, its length in *length; NULL if it cannot be read
 * (reported). The caller frees it. */
static char *read_file(const char *path, size_t *length)
{
    FILE *in = fopen(path, "rb");
    size_t size = 1 << 20;
    char *text = malloc(size + 1);
    *length = 0;
    if (in == NULL || text == NULL) {
        fprintf(stderr, "ifgm_vectors: error: cannot read %s\n", path);
        if (in != NULL)
            fclose(in);
        free(text);
        return NULL;
    }
    size_t n;
    while ((n = fread(text + *length, 1, size - *length, in)) > 0) {
        *length += n;
        if (*length < size)
            continue;
        char *bigger = realloc(text, 2 * size + 1);
        if (bigger == NULL) {
            fprintf(stderr, "ifgm_vectors: error: %s does not fit in memory\n", path);
            free(text);
            fclose(in);
            return NULL;
        }
        text = bigger;
        size *= 2;
    }
    fclose(in);
    text[*length] = '\0';
    return text;
}

/* Whether doc is a vectors file this tool reads (reported if not). */
static int is_vectors(const json_document *doc, const char *path)
{
    int format = json_member(doc, 0, "format");
    double version = 0;
    if (!json_string_equals(doc, json_member(doc, format, "name"), FORMAT_NAME) ||
        json_number(doc, json_member(doc, format, "version"), &version) != 0 ||
        version != FORMAT_VERSION) {
        fprintf(stderr, "ifgm_vectors: error: %s: format is not {\"name\": \"%s\", \"version\": "
                "%d}\n", path, FORMAT_NAME, FORMAT_VERSION);
        return 0;
    }
    if (!json_is(doc, json_member(doc, 0, "equations"), JSON_OBJECT) ||
        !json_is(doc, json_member(doc, 0, "traces"), JSON_ARRAY) ||
        !json_is(doc, json_member(doc, 0, "tolerances"), JSON_OBJECT)) {
        fprintf(stderr, "ifgm_vectors: error: %s: no equations, traces or tolerances\n", path);
        return 0;
    }
    return 1;
}

/* Check the parsed file; the exit status. */
static int check_file(const json_document *doc, const arguments *args)
{
    vectors_check check = {doc, args->precision, 0, 0, 0, 0};
    if (!is_vectors(doc, args->path))
        return EXIT_BAD_INPUT;
    vectors_check_equations(&check);
    vectors_check_traces(&check);
    printf("%d equation cases, %d trace steps: %d mismatch%s", check.cases, check.steps,
           check.mismatches, check.mismatches == 1 ? "" : "es");
    printf(" (%s tolerances", args->precision);
    if (check.skipped > 0)
        printf("; %d skipped: see the warnings", check.skipped);
    printf(")\n");
    return check.mismatches == 0 ? EXIT_OK : EXIT_MISMATCH;
}

int main(int argc, char **argv)
{
    arguments args;
    int status = read_arguments(argc, argv, &args);
    if (status >= 0)
        return status;
    size_t length;
    char *text = read_file(args.path, &length);
    if (text == NULL)
        return EXIT_BAD_INPUT;
    int capacity = (int)(length / 2 + 1); /* json.h: enough for any text of this length */
    json_token *tokens = malloc((size_t)capacity * sizeof *tokens);
    json_document doc;
    json_error error;
    if (tokens == NULL) {
        fprintf(stderr, "ifgm_vectors: error: %s does not fit in memory\n", args.path);
        status = EXIT_BAD_INPUT;
    } else if (json_parse(&doc, text, length, tokens, capacity, &error) != 0) {
        fprintf(stderr, "ifgm_vectors: error: %s is not JSON: %s at byte %zu\n", args.path,
                error.message, error.offset);
        status = EXIT_BAD_INPUT;
    } else {
        status = check_file(&doc, &args);
    }
    free(tokens);
    free(text);
    return status;
}
