/* A small JSON reader (RFC 8259) for the port's host programs: the JSON-lines protocol
 * (ifgm_json) and the test vectors (ifgm_vectors). The planners never include it.
 *
 * Like jsmn, json_parse splits one text into tokens, in an array the caller provides: nothing
 * is allocated, and an array too small for the text is an error. A value's tokens are
 * contiguous: its own token first, then those of everything inside it, in text order. The
 * children of an array are its elements; the children of an object are its keys (string
 * tokens), and the one child of a key is its value, the token right after it.
 *
 * Every lookup takes and returns token indices, -1 meaning "none"; each accepts -1 (and a
 * token of the wrong type) and answers "none" or "no", so lookups chain:
 *
 *     json_token tokens[64];
 *     json_document doc;
 *     json_error error;
 *     double t;
 *     if (json_parse(&doc, line, strlen(line), tokens, 64, &error) != 0)
 *         fprintf(stderr, "%s at byte %zu\n", error.message, error.offset);
 *     else if (json_number(&doc, json_member(&doc, 0, "t"), &t) != 0)
 *         fprintf(stderr, "no number t\n");
 *
 * Numbers are read with strtod (in the "C" locale, which a program has unless it calls
 * setlocale): correctly rounded, so Python's repr of a double reads back to the same double.
 * Strings are checked (no raw control character, valid escapes) but not decoded in place:
 * json_string_equals and json_string_copy decode them, \uXXXX escapes included (a surrogate
 * pair is one character; a lone surrogate is kept as its 3-byte encoding). Bytes of 0x80 and
 * above are taken as they are (no UTF-8 validation). */
#ifndef IFGM_JSON_H
#define IFGM_JSON_H

#include <stddef.h>

/* Nesting deeper than this (objects and arrays inside each other) is an error. */
#define JSON_MAX_DEPTH 64

typedef enum {
    JSON_OBJECT = 1,
    JSON_ARRAY,
    JSON_STRING,
    JSON_NUMBER,
    JSON_TRUE,
    JSON_FALSE,
    JSON_NULL
} json_type;

typedef struct {
    json_type type;
    size_t start, end; /* the value's bytes in the text; a string's without its quotes */
    int size;          /* children: an object's keys, an array's elements, a key's 1 value */
    int parent;        /* the token of the enclosing value (a key for an object's value), -1 */
    int after;         /* the first token after this value and everything inside it */
} json_token;

/* A parsed text: the text itself (not copied: it must outlive the document) and its
 * tokens; token 0 is the whole value. */
typedef struct {
    const char *text;
    const json_token *tokens;
    int count;
} json_document;

/* Why a text is not JSON: what is wrong, and at which byte (0 for the first). */
typedef struct {
    size_t offset;
    char message[96];
} json_error;

/* Parse text[0 .. length) as one JSON value with optional surrounding white space, into
 * tokens[0 .. capacity). text[length] must be a NUL byte (pass a C string; NUL bytes inside
 * the text are errors). Returns 0 and fills doc, or -1 and fills error: a syntax error, the
 * non-standard tokens NaN and Infinity, nesting deeper than JSON_MAX_DEPTH, or more tokens
 * than capacity (a text of n bytes needs at most n / 2 + 1). */
int json_parse(json_document *doc, const char *text, size_t length, json_token *tokens,
               int capacity, json_error *error);

/* The name of a type, for messages: "object", "array", "string", "number", "true", ...
 * (the type of token -1 is "nothing"). */
const char *json_type_name(const json_document *doc, int token);

/* Whether token is of type type (0 for token -1). */
int json_is(const json_document *doc, int token, json_type type);

/* The value of the member key of an object (the last one if key repeats, as Python reads
 * it), or -1. */
int json_member(const json_document *doc, int object, const char *key);

/* Element i of an array (0 for the first), or -1. */
int json_element(const json_document *doc, int array, int i);

/* The number of children: an object's members, an array's elements; 0 for other tokens. */
int json_size(const json_document *doc, int token);

/* The first child of an object (its first key) or an array (its first element), or -1. */
int json_first(const json_document *doc, int container);

/* The next sibling of a child of an object (the next key) or of an array (the next
 * element), or -1 after the last. The value of a key k is k + 1. */
int json_next(const json_document *doc, int child);

/* If token is a number, 0 and its value in *out; else -1 (*out untouched). A number too
 * large for a double reads as an infinity: check isfinite where that matters. */
int json_number(const json_document *doc, int token, double *out);

/* Whether token is a string equal to s once its escapes are decoded. */
int json_string_equals(const json_document *doc, int token, const char *s);

/* Decode string token into out (size bytes, NUL-terminated, cut short if too small); return
 * the length of the whole decoded string, as snprintf does, or 0 if token is no string. */
size_t json_string_copy(const json_document *doc, int token, char *out, size_t size);

#endif
