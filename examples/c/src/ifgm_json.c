/* ifgm_json: a planner of the port speaking the oracle's JSON-lines protocol
 * (docs/oracle-protocol.md) on stdin and stdout, as `ifgm-ref serve` does for the Python
 * planners.
 *
 *     ifgm_json [--planner NAME]      NAME: a name of ifgm_planner_kinds (default ifgm)
 *     ifgm-ref oracle --cmd "examples/c/build/ifgm_json --planner iba"
 *
 * Every `reset` starts the planner afresh (its storage zeroed, then its init); every `observe`
 * is one step; every reply is flushed at once. Unknown fields are ignored; an unknown name in
 * `params` is ignored with one warning line on stderr.
 *
 * Exit status: 0 after `bye`; 2 on a usage error, a malformed or out-of-order message, the
 * end of input before `bye`, or an episode the planner's init rejects (its status, named by
 * ifgm_status_text), as `ifgm-ref serve` does; 1 when the reply cannot be written or a
 * step returns a command JSON cannot carry. Each failure writes
 * one line "ifgm_json: error: ..." on stderr.
 *
 * Memory: the line and its tokens are static; the planner's storage, ifgm_planner_max_size()
 * bytes, is allocated once at start. Nothing is allocated while the session runs. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "json.h"
#include "planners.h"
#include "protocol.h"

/* The longest line read, bytes (newline excluded): a scan of IFGM_MAX_RAYS ranges of 25
 * characters each is about 28 KB, so this leaves room for any field a later protocol adds. */
#define MAX_LINE (1024 * 1024)
/* Tokens of one message: its ranges, and room for every other field; a scan of more ranges
 * than IFGM_MAX_RAYS still parses, to be reported as such. */
#define MAX_TOKENS (4 * IFGM_MAX_RAYS + 1024)
/* Longest piece of an offending line quoted in a message, bytes (wire.py's QUOTE_LIMIT). */
#define QUOTE_LIMIT 200

enum { EXIT_OK = 0, EXIT_PLANNER_FAILED = 1, EXIT_BAD_INPUT = 2 };
/* What a message's answer returns when the session goes on. */
enum { GO_ON = -1 };

static char line[MAX_LINE + 1];
static json_token tokens[MAX_TOKENS];
static ifgm_episode episode;
static ifgm_tuning tuning;
static ifgm_observation observation;

/* One session: the planner, and where the input is. */
typedef struct {
    const ifgm_planner_kind *kind;
    void *planner;
    size_t planner_size;
    int ready;  /* a reset has been answered */
    long count; /* lines read */
} session;

static void report(const char *kind, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fprintf(stderr, "ifgm_json: %s: ", kind);
    vfprintf(stderr, format, args);
    fputc('\n', stderr);
    va_end(args);
}

/* Read one line of in into line, its newline dropped (a last line without one counts).
 * Returns its length, -1 at the end of input, -2 if it is longer than MAX_LINE. */
static long read_line(FILE *in)
{
    long length = 0;
    int c;
    while ((c = getc(in)) != EOF && c != '\n') {
        if (length == MAX_LINE)
            return -2;
        line[length++] = (char)c;
    }
    line[length] = '\0';
    return (c == EOF && length == 0) ? -1 : length;
}

static int is_blank(const char *text, long length)
{
    return (long)strspn(text, " \t\r") == length;
}

/* The line, quoted for a message: at most QUOTE_LIMIT bytes, control bytes escaped. */
static const char *quoted(long length)
{
    static char out[4 * QUOTE_LIMIT + 64];
    size_t n = 0;
    out[n++] = '\'';
    for (long i = 0; i < length && i < QUOTE_LIMIT; i++) {
        unsigned char c = (unsigned char)line[i];
        n += (size_t)(c < 0x20 ? sprintf(out + n, "\\x%02x", c) : sprintf(out + n, "%c", c));
    }
    out[n++] = '\'';
    out[n] = '\0';
    if (length > QUOTE_LIMIT)
        sprintf(out + n, "... (%ld bytes)", length);
    return out;
}

static int answer_reset(session *s, const json_document *doc)
{
    protocol_error error;
    char unknown[256];
    if (protocol_read_reset(doc, 0, &episode, &tuning, &error) != 0) {
        report("error", "line %ld (reset): %s", s->count, error.text);
        return EXIT_BAD_INPUT;
    }
    if (protocol_unknown_params(doc, 0, unknown, sizeof unknown) > 0)
        report("warning", "line %ld (reset): ignoring unknown parameter(s) %s", s->count,
               unknown);
    memset(s->planner, 0, s->planner_size);
    int status = s->kind->init(s->planner, &episode, &tuning);
    if (status != IFGM_OK) {
        report("error", "line %ld (reset): %s", s->count, ifgm_status_text(status));
        return EXIT_BAD_INPUT;
    }
    s->ready = 1;
    if (protocol_write_ready(stdout) != 0 || fflush(stdout) != 0) {
        report("error", "line %ld (reset): cannot write the reply", s->count);
        return EXIT_PLANNER_FAILED;
    }
    return GO_ON;
}

static int answer_observe(session *s, const json_document *doc)
{
    protocol_error error;
    if (!s->ready) {
        report("error", "line %ld (observe): observe before the first reset", s->count);
        return EXIT_BAD_INPUT;
    }
    if (protocol_read_observe(doc, 0, &observation, &error) != 0) {
        report("error", "line %ld (observe): %s", s->count, error.text);
        return EXIT_BAD_INPUT;
    }
    ifgm_command command = s->kind->step(s->planner, &observation);
    if (protocol_write_command(stdout, &command, &error) != 0 || fflush(stdout) != 0) {
        report("error", "line %ld (observe): %s", s->count, error.text);
        return EXIT_PLANNER_FAILED;
    }
    return GO_ON;
}

/* Answer one line; return an exit status to end the session with, or GO_ON. */
static int answer(session *s, long length)
{
    json_document doc;
    json_error syntax;
    protocol_error error;
    protocol_type type;
    if (json_parse(&doc, line, (size_t)length, tokens, MAX_TOKENS, &syntax) != 0) {
        report("error", "line %ld is not JSON: %s (%s at byte %zu)", s->count, quoted(length),
               syntax.message, syntax.offset);
        return EXIT_BAD_INPUT;
    }
    if (protocol_type_of(&doc, 0, &type, &error) != 0) {
        report("error", "line %ld: %s", s->count, error.text);
        return EXIT_BAD_INPUT;
    }
    switch (type) {
    case PROTOCOL_RESET:
        return answer_reset(s, &doc);
    case PROTOCOL_OBSERVE:
        return answer_observe(s, &doc);
    case PROTOCOL_BYE:
        return EXIT_OK;
    default:
        report("error", "line %ld: type '%s', but should be 'reset', 'observe' or 'bye' (the "
               "program sends ready and command, the oracle does not)", s->count,
               type == PROTOCOL_READY ? "ready" : "command");
        return EXIT_BAD_INPUT;
    }
}

static int run(session *s)
{
    for (;;) {
        long length = read_line(stdin);
        s->count++;
        if (length == -1) {
            report("error", "end of input after %ld line(s), before bye", s->count - 1);
            return EXIT_BAD_INPUT;
        }
        if (length == -2) {
            report("error", "line %ld is longer than %d bytes", s->count, MAX_LINE);
            return EXIT_BAD_INPUT;
        }
        if (is_blank(line, length))
            continue; /* a blank line carries nothing; the oracle never sends one */
        int status = answer(s, length);
        if (status != GO_ON)
            return status;
    }
}

static void usage(FILE *out)
{
    fputs("usage: ifgm_json [--planner NAME]\n\n"
          "Run a planner of the C port as a program speaking the oracle's JSON-lines protocol\n"
          "(docs/oracle-protocol.md) on stdin and stdout.\n\n"
          "options:\n"
          "  --planner NAME  the planner, one of:",
          out);
    for (const ifgm_planner_kind *k = ifgm_planner_kinds; k->name != NULL; k++)
        fprintf(out, " %s", k->name);
    fputs(" (default: ifgm)\n  --help          show this message and exit\n", out);
}

/* The planner the arguments name; NULL after a usage error or --help (*status says which). */
static const ifgm_planner_kind *chosen(int argc, char **argv, int *status)
{
    const char *name = "ifgm";
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            *status = EXIT_OK;
            return NULL;
        }
        if (strcmp(argv[i], "--planner") == 0 && i + 1 < argc) {
            name = argv[++i];
        } else {
            report("error", "%s '%s' (usage: ifgm_json [--planner NAME])",
                   strcmp(argv[i], "--planner") == 0 ? "no NAME after" : "unrecognized argument",
                   argv[i]);
            *status = EXIT_BAD_INPUT;
            return NULL;
        }
    }
    const ifgm_planner_kind *kind = ifgm_planner_kind_named(name);
    if (kind == NULL) {
        fprintf(stderr, "ifgm_json: error: unknown planner '%s'; known: ", name);
        for (const ifgm_planner_kind *k = ifgm_planner_kinds; k->name != NULL; k++)
            fprintf(stderr, "%s%s", k == ifgm_planner_kinds ? "" : ", ", k->name);
        fputc('\n', stderr);
        *status = EXIT_BAD_INPUT;
    }
    return kind;
}

int main(int argc, char **argv)
{
    int status = EXIT_OK;
    session s = {chosen(argc, argv, &status), NULL, ifgm_planner_max_size(), 0, 0};
    if (s.kind == NULL)
        return status;
    s.planner = malloc(s.planner_size);
    if (s.planner == NULL) {
        report("error", "cannot allocate the planner's %zu bytes", s.planner_size);
        return EXIT_PLANNER_FAILED;
    }
    status = run(&s);
    free(s.planner);
    return status;
}
