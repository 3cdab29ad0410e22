/* The vectors' equation cases against the functions of equations.h: see vectors.h.
 *
 * Each form of a group names a function, its arguments (case inputs, in the function's order)
 * and the quantity whose tolerance applies. A case holds the inputs and, for each form, the
 * expected output -- a number, a point [x, y], or {"error": ...} where the form must fail:
 * return IFGM_EQ_UNDEFINED, or a NaN or an infinity. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "equations.h"
#include "protocol.h"
#include "vectors.h"

/* The most numbers one call takes (eq. (4): 6; a point counts 2). */
#define MAX_INPUTS 8

/* A function of equations.h behind one signature: its inputs flattened in its parameters'
 * order (a point as x, y), its output (a point as 2 numbers). */
typedef int (*equation)(const ifgm_real *in, ifgm_real out[2]);

static int eq1(const ifgm_real *in, ifgm_real out[2])
{
    return eq1_gap_midpoint(in, in + 2, out);
}
static int eq2_literal(const ifgm_real *in, ifgm_real out[2])
{
    return eq2_gap_angle_literal(in[0], in[1], out);
}
static int eq2(const ifgm_real *in, ifgm_real out[2])
{
    return eq2_gap_angle(in[0], in[1], out);
}
static int fgm_centre(const ifgm_real *in, ifgm_real out[2])
{
    return fgm_gap_centre_angle(in[0], in[1], in[2], in[3], out);
}
static int eq3_literal(const ifgm_real *in, ifgm_real out[2])
{
    return eq3_goal_angle_literal(in, in + 2, out);
}
static int eq3(const ifgm_real *in, ifgm_real out[2])
{
    return eq3_goal_angle(in, in + 2, out);
}
static int eq4_literal(const ifgm_real *in, ifgm_real out[2])
{
    return eq4_final_heading_literal(in[0], in[1], in[2], in[3], in[4], out);
}
static int eq4(const ifgm_real *in, ifgm_real out[2])
{
    return eq4_final_heading(in[0], in[1], in[2], in[3], in[4], in[5], out);
}
static int eq4_fgm(const ifgm_real *in, ifgm_real out[2])
{
    return eq4_final_heading_fgm(in[0], in[1], in[2], in[3], in[4], in[5], out);
}

/* The port's functions by their reference names: their parameters in order, and how many
 * numbers they answer (a point: 2). */
static const struct {
    const char *name, *args;
    int outputs;
    equation call;
} functions[] = {
    {"eq1_gap_midpoint", "p1 p2", 2, eq1},
    {"eq2_gap_angle_literal", "x_g y_g", 1, eq2_literal},
    {"eq2_gap_angle", "x_g y_g", 1, eq2},
    {"fgm_gap_centre_angle", "d1 phi1 d2 phi2", 1, fgm_centre},
    {"eq3_goal_angle_literal", "current destination", 1, eq3_literal},
    {"eq3_goal_angle", "current destination", 1, eq3},
    {"eq4_final_heading_literal", "theta_g theta_d w_g w_d d_th", 1, eq4_literal},
    {"eq4_final_heading", "theta_g theta_d w_g w_d d_th heading", 1, eq4},
    {"eq4_final_heading_fgm", "theta_g theta_d alpha beta d_min heading", 1, eq4_fgm},
};

/* One form of a group, ready to check cases with. */
typedef struct {
    char key[16];      /* the case key of its output: "literal", "interpreted" or "output" */
    char function[64]; /* its function's name */
    int args;          /* the token of its argument names */
    int outputs;
    equation call;
    vectors_tolerance tolerance;
} form;

/* The form whose key token is key: 0, or -1 when it is skipped (reported). */
static int form_at(vectors_check *check, int key, form *out)
{
    const json_document *doc = check->doc;
    char args[128] = "", quantity[32];
    int n = 0;
    json_string_copy(doc, key, out->key, sizeof out->key);
    json_string_copy(doc, json_member(doc, key + 1, "function"), out->function,
                     sizeof out->function);
    json_string_copy(doc, json_member(doc, key + 1, "quantity"), quantity, sizeof quantity);
    out->args = json_member(doc, key + 1, "args");
    for (int a = json_first(doc, out->args); a >= 0; a = json_next(doc, a)) {
        char name[32];
        json_string_copy(doc, a, name, sizeof name);
        n += snprintf(args + n, sizeof args - (size_t)n, "%s%s", n ? " " : "", name);
    }
    for (size_t i = 0; i < sizeof functions / sizeof functions[0]; i++) {
        if (strcmp(functions[i].name, out->function) != 0)
            continue;
        if (strcmp(functions[i].args, args) != 0) {
            vectors_mismatch(check, "%s: the file passes (%s), but the port's takes (%s)",
                             out->function, args, functions[i].args);
            return -1;
        }
        out->outputs = functions[i].outputs;
        out->call = functions[i].call;
        return vectors_tolerance_of(check, quantity, &out->tolerance);
    }
    vectors_skip(check, "the port has no %s: its cases are skipped", out->function);
    return -1;
}

/* The numbers of token: 1 for a number, 2 for a point [x, y], 0 for anything else. */
static int values_of(const json_document *doc, int token, double out[2])
{
    if (json_number(doc, token, &out[0]) == 0)
        return 1;
    if (json_size(doc, token) == 2 && json_number(doc, json_element(doc, token, 0), &out[0]) == 0 &&
        json_number(doc, json_element(doc, token, 1), &out[1]) == 0)
        return 2;
    return 0;
}

/* count values as check.py shows them: "0.5", or a point between brackets, "(1.0, 2.0)". */
static const char *shown(const double *values, int count, const char *brackets, char out[80])
{
    char x[PROTOCOL_NUMBER_SIZE], y[PROTOCOL_NUMBER_SIZE];
    protocol_format_number(x, values[0]);
    if (count == 1)
        return strcpy(out, x);
    protocol_format_number(y, values[1]);
    snprintf(out, 80, "%c%s, %s%c", brackets[0], x, y, brackets[1]);
    return out;
}

/* The inputs of case c in the form's order, flattened into in, and the call as check.py
 * shows it ("eq3_goal_angle(current=(0.0, 0.0), destination=(-1.0, 1.0))") into call.
 * Returns 0, or -1 if the case lacks an input (reported). */
static int inputs_of(vectors_check *check, const form *f, int c, const char *id,
                     ifgm_real in[MAX_INPUTS], char call[512])
{
    const json_document *doc = check->doc;
    int inputs = json_member(doc, c, "inputs"), n = 0;
    size_t used = (size_t)snprintf(call, 512, "%s(", f->function);
    for (int a = json_first(doc, f->args); a >= 0; a = json_next(doc, a)) {
        char name[32], text[80];
        double value[2];
        json_string_copy(doc, a, name, sizeof name);
        int count = values_of(doc, json_member(doc, inputs, name), value);
        if (count == 0 || n + count > MAX_INPUTS) {
            vectors_mismatch(check, "%s: no input %s in the file [case %s]", f->function, name,
                             id);
            return -1;
        }
        used += (size_t)snprintf(call + used, 512 - used, "%s%s=%s", n ? ", " : "", name,
                                 shown(value, count, "()", text));
        for (int i = 0; i < count; i++)
            in[n++] = (ifgm_real)value[i];
    }
    snprintf(call + used, 512 - used, ")");
    return 0;
}

/* Where the case expects a failure: report a finite answer. */
static void check_failure(vectors_check *check, const form *f, int c, const char *id,
                          const char *call, int failed, const double actual[2])
{
    const json_document *doc = check->doc;
    int error = json_member(doc, json_member(doc, c, f->key), "error");
    char message[256], got[80];
    if (!json_is(doc, error, JSON_STRING)) {
        vectors_mismatch(check, "%s: the file has no %s output [case %s]", f->function, f->key,
                         id);
        return;
    }
    if (failed || !isfinite(actual[0]) || !isfinite(actual[f->outputs - 1]))
        return; /* an error code, a NaN or an infinity: the failure asked for */
    json_string_copy(doc, error, message, sizeof message);
    vectors_mismatch(check, "%s = %s, but should fail: %s [case %s]", call,
                     shown(actual, f->outputs, "()", got), message, id);
}

/* Check the form f on case c. */
static void check_case(vectors_check *check, const form *f, int c)
{
    const json_document *doc = check->doc;
    char id[64], call[512], got[80], want[80], tolerance[64];
    ifgm_real in[MAX_INPUTS], out[2] = {0, 0};
    double expected[2];
    json_string_copy(doc, json_member(doc, c, "id"), id, sizeof id);
    if (inputs_of(check, f, c, id, in, call) != 0)
        return;
    int failed = f->call(in, out) != 0;
    double actual[2] = {out[0], out[1]};
    int count = values_of(doc, json_member(doc, c, f->key), expected);
    if (count == 0) {
        check_failure(check, f, c, id, call, failed, actual);
        return;
    }
    if (count != f->outputs) {
        vectors_mismatch(check, "%s: the file's %s output is not %s [case %s]", f->function,
                         f->key, f->outputs == 2 ? "a point" : "a number", id);
        return;
    }
    shown(expected, count, "[]", want);
    if (failed) {
        vectors_mismatch(check, "%s failed (IFGM_EQ_UNDEFINED), but should be %s [case %s]",
                         call, want, id);
        return;
    }
    for (int i = 0; i < count; i++) {
        if (!vectors_allows(&f->tolerance, expected[i], actual[i])) {
            vectors_mismatch(check, "%s = %s, but should be %s (%s) [case %s]", call,
                             shown(actual, count, "()", got), want,
                             vectors_describe(&f->tolerance, tolerance), id);
            return;
        }
    }
}

void vectors_check_equations(vectors_check *check)
{
    const json_document *doc = check->doc;
    int groups = json_member(doc, 0, "equations");
    for (int g = json_first(doc, groups); g >= 0; g = json_next(doc, g)) {
        int cases = json_member(doc, g + 1, "cases");
        int forms = json_member(doc, g + 1, "forms");
        check->cases += json_size(doc, cases);
        for (int key = json_first(doc, forms); key >= 0; key = json_next(doc, key)) {
            form f;
            if (form_at(check, key, &f) != 0)
                continue;
            for (int c = json_first(doc, cases); c >= 0; c = json_next(doc, c))
                check_case(check, &f, c);
        }
    }
}
