/* ifgm_bench: the wall-clock cost of one decision of a planner of the port.
 *
 *     ifgm_bench --planner NAME [--repeats N] EPISODES.jsonl
 *     ifgm_bench --dump OUT.bin EPISODES.jsonl
 *
 * EPISODES.jsonl holds recorded sessions of the JSON-lines protocol (docs/oracle-protocol.md):
 * each episode a `reset` line, then its `observe` lines, each optionally followed by the
 * `command` the reference planner answered (benchmarks/bench_c.py writes them). Every line is
 * parsed before anything is timed.
 *
 * Timing: each pass re-initialises the planner at every episode and steps it through the
 * episode's observations, timing each step alone between two clock_gettime(CLOCK_MONOTONIC)
 * readings, less the timer's own cost (the median of 10,001 empty readings, measured at
 * start: some 20-60 ns here). The report gives, over the passes, the median and the best of
 * the per-pass median and 90th percentile (linear interpolation, as numpy's percentile), and
 * the median per branch. Every pass must answer the same commands, bit for bit (a planner
 * whose init forgets part of the last episode would not), and where the file has the
 * reference's commands, the report says how far the port's are from them: the decisions
 * timed are the episode's own. The heap calls made by init and step over every pass are
 * counted (alloc_count.h): a planner of the port allocates nothing.
 *
 * Output: one JSON object on stdout (see print_report).
 *
 * --dump writes the parsed structs as raw bytes, for benchmarks/cortex_m4.py to hand to the
 * Cortex-M4 build in an emulator (a float build's structs, which hold only floats and ints,
 * have the same layout on x86-64 and on 32-bit ARM): "IFGMDUMP", then int32 sizeof
 * ifgm_episode, ifgm_tuning and ifgm_observation and the number of episodes, then each
 * episode's episode, tuning, int32 number of observations and observations. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "alloc_count.h"
#include "planners.h"
#include "protocol.h"

/* Empty timer readings whose median is the timer's cost. */
#define TIMER_SAMPLES 10001
#define PI 3.14159265358979323846
/* Distinct branch names a planner may answer. */
#define MAX_BRANCHES 32

typedef struct {
    ifgm_episode episode;
    ifgm_tuning tuning;
    int first, count; /* its observations: steps[first .. first + count) */
} episode_record;

typedef struct {
    ifgm_observation observation;
    int has_reference; /* the reference's command follows the observation in the file */
    double heading, speed;
    char branch[48];
} step_record;

typedef struct {
    episode_record *episodes;
    step_record *steps;
    int n_episodes, n_steps;
} recording;

static void die(const char *what, const char *detail)
{
    fprintf(stderr, "ifgm_bench: %s%s%s\n", what, detail ? ": " : "", detail ? detail : "");
    exit(2);
}

static void *grow(void *array, int count, size_t size)
{
    /* room for one more at every power of two */
    if (count & (count - 1))
        return array;
    array = realloc(array, (size_t)(count ? 2 * count : 1) * size);
    if (!array)
        die("out of memory", NULL);
    return array;
}

static char *read_file(const char *path, size_t *length)
{
    FILE *file = fopen(path, "rb");
    size_t size = 1 << 16, used = 0, got;
    char *text = malloc(size + 1);
    if (!file)
        die("cannot open", path);
    while (text && (got = fread(text + used, 1, size - used, file)) > 0)
        if ((used += got) == size)
            text = realloc(text, (size *= 2) + 1);
    if (!text)
        die("out of memory", NULL);
    fclose(file);
    text[used] = '\0';
    *length = used;
    return text;
}

/* Read one message (a NUL-terminated line) into the recording. */
static void read_message(recording *rec, const json_document *doc)
{
    protocol_type type;
    protocol_error error;
    if (protocol_type_of(doc, 0, &type, &error))
        die(error.text, NULL);
    if (type == PROTOCOL_RESET) {
        rec->episodes = grow(rec->episodes, rec->n_episodes, sizeof *rec->episodes);
        episode_record *e = &rec->episodes[rec->n_episodes++];
        if (protocol_read_reset(doc, 0, &e->episode, &e->tuning, &error))
            die(error.text, NULL);
        e->first = rec->n_steps;
        e->count = 0;
    } else if (type == PROTOCOL_OBSERVE) {
        if (!rec->n_episodes)
            die("an observe line before the first reset", NULL);
        rec->steps = grow(rec->steps, rec->n_steps, sizeof *rec->steps);
        step_record *s = &rec->steps[rec->n_steps++];
        if (protocol_read_observe(doc, 0, &s->observation, &error))
            die(error.text, NULL);
        s->has_reference = 0;
        rec->episodes[rec->n_episodes - 1].count++;
    } else if (type == PROTOCOL_COMMAND) {
        protocol_command command;
        step_record *s = rec->n_steps ? &rec->steps[rec->n_steps - 1] : NULL;
        if (!s || s->has_reference)
            die("a command line not after an observe line", NULL);
        if (protocol_read_command(doc, 0, &command, &error))
            die(error.text, NULL);
        s->has_reference = 1;
        s->heading = command.heading;
        s->speed = command.speed;
        s->branch[0] = '\0';
        if (command.branch >= 0)
            json_string_copy(doc, command.branch, s->branch, sizeof s->branch);
    }
}

static recording load(const char *path)
{
    recording rec = {NULL, NULL, 0, 0};
    size_t length, capacity = 0;
    char *text = read_file(path, &length), *line = text, *end;
    json_token *tokens = NULL;
    json_document doc;
    json_error error;
    for (; line < text + length; line = end + 1) {
        end = strchr(line, '\n');
        end = end ? end : text + length;
        *end = '\0';
        if (end == line)
            continue;
        if ((size_t)(end - line) / 2 + 1 > capacity) {
            capacity = (size_t)(end - line) / 2 + 1;
            tokens = realloc(tokens, capacity * sizeof *tokens);
            if (!tokens)
                die("out of memory", NULL);
        }
        if (json_parse(&doc, line, (size_t)(end - line), tokens, (int)capacity, &error))
            die(error.message, NULL);
        read_message(&rec, &doc);
    }
    free(tokens);
    free(text);
    if (!rec.n_steps)
        die("no observe line in", path);
    return rec;
}

static int64_t now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec;
}

static int by_value(const void *a, const void *b)
{
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

/* The q-quantile of values[0 .. n) (sorted in place), interpolated between neighbours. */
static double quantile(int64_t *values, int n, double q)
{
    qsort(values, (size_t)n, sizeof *values, by_value);
    double position = q * (n - 1);
    int below = (int)position;
    if (below + 1 >= n)
        return (double)values[n - 1];
    return (double)values[below] + (position - below) * (double)(values[below + 1] - values[below]);
}

static int64_t timer_cost(void)
{
    static int64_t samples[TIMER_SAMPLES];
    for (int i = 0; i < TIMER_SAMPLES; i++) {
        int64_t start = now_ns();
        samples[i] = now_ns() - start;
    }
    return (int64_t)quantile(samples, TIMER_SAMPLES, 0.5);
}

static int same_command(const ifgm_command *a, const ifgm_command *b)
{
    return memcmp(&a->heading, &b->heading, sizeof a->heading) == 0 &&
           memcmp(&a->speed, &b->speed, sizeof a->speed) == 0 && a->behaviour == b->behaviour &&
           a->branch == b->branch && a->stop == b->stop;
}

/* One pass: every episode from a fresh init; ns[k] the net time of step k. The first pass
 * keeps the commands, the others must repeat them. */
static void run_pass(const ifgm_planner_kind *kind, void *planner, const recording *rec,
                     int64_t cost, int64_t *ns, ifgm_command *commands, int first_pass)
{
    for (int e = 0; e < rec->n_episodes; e++) {
        const episode_record *episode = &rec->episodes[e];
        int status = kind->init(planner, &episode->episode, &episode->tuning);
        if (status != IFGM_OK)
            die("init failed", ifgm_status_text(status));
        for (int k = episode->first; k < episode->first + episode->count; k++) {
            int64_t start = now_ns();
            ifgm_command command = kind->step(planner, &rec->steps[k].observation);
            ns[k] = now_ns() - start - cost;
            if (first_pass)
                commands[k] = command;
            else if (!same_command(&command, &commands[k]))
                die("a pass answered another command than the first", kind->name);
        }
    }
}

static int by_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of values[0 .. n) (sorted in place) and, in *best, the least. */
static double median_and_best(double *values, int n, double *best)
{
    qsort(values, (size_t)n, sizeof *values, by_double);
    *best = values[0];
    return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

static const char *branch_of(const ifgm_command *command)
{
    return command->branch ? command->branch : "null";
}

/* The q-quantile of each pass over the steps `pick` selects (all if NULL), then the median
 * and the best of those over the passes. */
static double over_passes(const int64_t *ns, int passes, int n, const ifgm_command *commands,
                          const char *pick, double q, double *best)
{
    int64_t *picked = malloc((size_t)n * sizeof *picked);
    double *per_pass = malloc((size_t)passes * sizeof *per_pass);
    int m = 0;
    if (!picked || !per_pass)
        die("out of memory", NULL);
    for (int r = 0; r < passes; r++) {
        m = 0;
        for (int k = 0; k < n; k++)
            if (!pick || strcmp(branch_of(&commands[k]), pick) == 0)
                picked[m++] = ns[(size_t)r * n + k];
        per_pass[r] = quantile(picked, m, q);
    }
    double median = median_and_best(per_pass, passes, best);
    free(picked);
    free(per_pass);
    return median;
}

/* "reference": how the commands compare with the reference's, where the file has them. */
static void print_reference(const recording *rec, const ifgm_command *commands)
{
    int compared = 0, branch_equal = 0;
    double heading = 0, speed = 0;
    for (int k = 0; k < rec->n_steps; k++) {
        const step_record *s = &rec->steps[k];
        if (!s->has_reference)
            continue;
        compared++;
        branch_equal += strcmp(commands[k].branch ? commands[k].branch : "", s->branch) == 0;
        double dh = fabs(remainder((double)commands[k].heading - s->heading, 2 * PI));
        double ds = fabs((double)commands[k].speed - s->speed);
        heading = dh > heading ? dh : heading;
        speed = ds > speed ? ds : speed;
    }
    printf("\"reference\": {\"compared\": %d, \"branch_equal\": %d, \"max_heading_diff\": %.3g, "
           "\"max_speed_diff\": %.3g}",
           compared, branch_equal, heading, speed);
}

static void print_branches(const recording *rec, const int64_t *ns, int passes,
                           const ifgm_command *commands)
{
    const char *names[MAX_BRANCHES];
    int counts[MAX_BRANCHES], n_names = 0;
    for (int k = 0; k < rec->n_steps; k++) {
        int b = 0;
        while (b < n_names && strcmp(names[b], branch_of(&commands[k])) != 0)
            b++;
        if (b == n_names) {
            if (n_names == MAX_BRANCHES)
                die("too many branch names", NULL);
            names[n_names] = branch_of(&commands[k]);
            counts[n_names++] = 0;
        }
        counts[b]++;
    }
    printf("\"branches\": {");
    for (int b = 0; b < n_names; b++) {
        double best, median = over_passes(ns, passes, rec->n_steps, commands, names[b], 0.5, &best);
        printf("%s\"%s\": {\"decisions\": %d, \"median_ns\": %.1f}", b ? ", " : "", names[b],
               counts[b], median);
    }
    printf("}");
}

/* The report: planner, episodes, decisions, passes, timer_cost_ns, median_ns,
 * median_best_ns, p90_ns, p90_best_ns, allocations (null where they cannot be counted),
 * reference, branches. */
static void print_report(const ifgm_planner_kind *kind, const recording *rec, const int64_t *ns,
                         int passes, const ifgm_command *commands, int64_t cost, long allocations)
{
    double median_best, p90_best;
    double median = over_passes(ns, passes, rec->n_steps, commands, NULL, 0.5, &median_best);
    double p90 = over_passes(ns, passes, rec->n_steps, commands, NULL, 0.9, &p90_best);
    printf("{\"planner\": \"%s\", \"episodes\": %d, \"decisions\": %d, \"passes\": %d, "
           "\"timer_cost_ns\": %lld, \"median_ns\": %.1f, \"median_best_ns\": %.1f, "
           "\"p90_ns\": %.1f, \"p90_best_ns\": %.1f, ",
           kind->name, rec->n_episodes, rec->n_steps, passes, (long long)cost, median,
           median_best, p90, p90_best);
    if (alloc_count_works())
        printf("\"allocations\": %ld, ", allocations);
    else
        printf("\"allocations\": null, ");
    print_reference(rec, commands);
    printf(", ");
    print_branches(rec, ns, passes, commands);
    printf("}\n");
}

static void bench(const char *name, int passes, const recording *rec)
{
    const ifgm_planner_kind *kind = ifgm_planner_kind_named(name);
    if (!kind)
        die("no such planner", name);
    void *planner = malloc(ifgm_planner_max_size()); /* aligned for any type */
    int64_t *ns = malloc((size_t)passes * (size_t)rec->n_steps * sizeof *ns);
    ifgm_command *commands = malloc((size_t)rec->n_steps * sizeof *commands);
    if (!planner || !ns || !commands)
        die("out of memory", NULL);
    int64_t cost = timer_cost();
    alloc_count_start();
    for (int r = 0; r < passes; r++)
        run_pass(kind, planner, rec, cost, ns + (size_t)r * rec->n_steps, commands, r == 0);
    long allocations = alloc_count_stop();
    print_report(kind, rec, ns, passes, commands, cost, allocations);
    free(commands);
    free(ns);
    free(planner);
}

static void write_int(FILE *out, int value)
{
    int32_t v = value;
    fwrite(&v, sizeof v, 1, out);
}

static void dump(const char *path, const recording *rec)
{
    FILE *out = fopen(path, "wb");
    if (!out)
        die("cannot write", path);
    fwrite("IFGMDUMP", 1, 8, out);
    write_int(out, (int)sizeof(ifgm_episode));
    write_int(out, (int)sizeof(ifgm_tuning));
    write_int(out, (int)sizeof(ifgm_observation));
    write_int(out, rec->n_episodes);
    for (int e = 0; e < rec->n_episodes; e++) {
        const episode_record *episode = &rec->episodes[e];
        fwrite(&episode->episode, sizeof episode->episode, 1, out);
        fwrite(&episode->tuning, sizeof episode->tuning, 1, out);
        write_int(out, episode->count);
        for (int k = episode->first; k < episode->first + episode->count; k++)
            fwrite(&rec->steps[k].observation, sizeof(ifgm_observation), 1, out);
    }
    if (fclose(out) != 0)
        die("cannot write", path);
}

static const char USAGE[] =
    "usage: ifgm_bench --planner NAME [--repeats N] EPISODES.jsonl\n"
    "       ifgm_bench --dump OUT.bin EPISODES.jsonl\n"
    "Time one decision of the planner NAME (ifgm, iba, distbug, fgm) on the recorded\n"
    "episodes (protocol lines: reset, observe, optionally the reference's command), N\n"
    "passes (default 5); print a JSON report. --dump writes the parsed structs instead.\n";

int main(int argc, char **argv)
{
    const char *planner = NULL, *dump_to = NULL, *path = NULL;
    int passes = 5;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--planner") == 0 && i + 1 < argc)
            planner = argv[++i];
        else if (strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
            passes = atoi(argv[++i]);
        else if (strcmp(argv[i], "--dump") == 0 && i + 1 < argc)
            dump_to = argv[++i];
        else if (strcmp(argv[i], "--help") == 0) {
            fputs(USAGE, stdout);
            return 0;
        } else if (!path && argv[i][0] != '-')
            path = argv[i];
        else
            die("bad argument", argv[i]);
    }
    if (!path || !planner == !dump_to || passes < 1) {
        fputs(USAGE, stderr);
        return 2;
    }
    recording rec = load(path);
    if (dump_to)
        dump(dump_to, &rec);
    else
        bench(planner, passes, &rec);
    free(rec.steps);
    free(rec.episodes);
    return 0;
}
