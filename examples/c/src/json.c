/* A small JSON reader: see json.h. A recursive-descent parser, its depth bounded by
 * JSON_MAX_DEPTH, writing tokens in text order. */
#include "json.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *text;
    size_t length, pos;
    json_token *tokens;
    int capacity, count;
    json_error *error;
} parser;

static int parse_value(parser *p, int parent, int depth);

static int fail(parser *p, size_t offset, const char *message)
{
    p->error->offset = offset;
    snprintf(p->error->message, sizeof p->error->message, "%s", message);
    return -1;
}

/* The byte at the parser's position, or 0 at the end of the text. */
static char peek(const parser *p)
{
    return p->pos < p->length ? p->text[p->pos] : '\0';
}

static void skip_space(parser *p)
{
    for (char c = peek(p); c == ' ' || c == '\t' || c == '\n' || c == '\r'; c = peek(p))
        p->pos++;
}

/* A new token of type, starting at byte start; its index, or -1 when the array is full. */
static int new_token(parser *p, json_type type, size_t start, int parent)
{
    if (p->count == p->capacity) {
        p->error->offset = start;
        snprintf(p->error->message, sizeof p->error->message,
                 "more tokens than the %d the reader was given room for", p->capacity);
        return -1;
    }
    json_token *token = &p->tokens[p->count];
    token->type = type;
    token->start = token->end = start;
    token->size = 0;
    token->parent = parent;
    token->after = p->count + 1;
    return p->count++;
}

static int is_hex(char c)
{
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

/* A string, the parser at its opening quote: checked, not decoded (json_string_copy does). */
static int parse_string(parser *p, int parent)
{
    int index = new_token(p, JSON_STRING, p->pos + 1, parent);
    if (index < 0)
        return -1;
    for (p->pos++; p->pos < p->length; p->pos++) {
        unsigned char c = (unsigned char)p->text[p->pos];
        if (c == '"') {
            p->tokens[index].end = p->pos++;
            return index;
        }
        if (c < 0x20)
            return fail(p, p->pos, "control character in a string (escape it)");
        if (c != '\\')
            continue;
        c = p->pos + 1 < p->length ? (unsigned char)p->text[p->pos + 1] : '\0';
        if (c == 'u') {
            for (int i = 2; i < 6; i++)
                if (p->pos + i >= p->length || !is_hex(p->text[p->pos + i]))
                    return fail(p, p->pos, "\\u must be followed by 4 hexadecimal digits");
            p->pos += 5;
        } else if (c != '\0' && strchr("\"\\/bfnrt", c)) {
            p->pos++;
        } else {
            return fail(p, p->pos, "invalid escape in a string");
        }
    }
    return fail(p, p->tokens[index].start - 1, "unterminated string");
}

static size_t skip_digits(const parser *p, size_t pos)
{
    while (pos < p->length && p->text[pos] >= '0' && p->text[pos] <= '9')
        pos++;
    return pos;
}

/* A number: -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)? (RFC 8259, section 6). */
static int parse_number(parser *p, int parent)
{
    size_t pos = p->pos;
    if (pos < p->length && p->text[pos] == '-')
        pos++;
    size_t digits = skip_digits(p, pos);
    if (digits == pos || (p->text[pos] == '0' && digits > pos + 1))
        return fail(p, p->pos, "invalid number");
    pos = digits;
    if (pos < p->length && p->text[pos] == '.') {
        digits = skip_digits(p, pos + 1);
        if (digits == pos + 1)
            return fail(p, p->pos, "invalid number: no digit after '.'");
        pos = digits;
    }
    if (pos < p->length && (p->text[pos] == 'e' || p->text[pos] == 'E')) {
        pos++;
        if (pos < p->length && (p->text[pos] == '+' || p->text[pos] == '-'))
            pos++;
        digits = skip_digits(p, pos);
        if (digits == pos)
            return fail(p, p->pos, "invalid number: no digit in the exponent");
        pos = digits;
    }
    int index = new_token(p, JSON_NUMBER, p->pos, parent);
    if (index < 0)
        return -1;
    p->tokens[index].end = p->pos = pos;
    return index;
}

static int starts_with(const parser *p, const char *word)
{
    size_t n = strlen(word);
    return p->length - p->pos >= n && memcmp(p->text + p->pos, word, n) == 0;
}

/* true, false or null; NaN and Infinity named as what they are. */
static int parse_word(parser *p, int parent)
{
    static const struct {
        const char *word;
        json_type type;
    } words[] = {{"true", JSON_TRUE}, {"false", JSON_FALSE}, {"null", JSON_NULL}};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
        if (!starts_with(p, words[i].word))
            continue;
        int index = new_token(p, words[i].type, p->pos, parent);
        if (index < 0)
            return -1;
        p->pos += strlen(words[i].word);
        p->tokens[index].end = p->pos;
        return index;
    }
    if (starts_with(p, "NaN") || starts_with(p, "Infinity") || starts_with(p, "-Infinity"))
        return fail(p, p->pos, "NaN and Infinity are not JSON (RFC 8259)");
    if (p->pos == p->length)
        return fail(p, p->pos, "expected a value, found the end of the text");
    return fail(p, p->pos, "expected a value");
}

/* The members or elements of an object or array, the parser just past its opening bracket. */
static int parse_children(parser *p, int index, int depth)
{
    json_token *tokens = p->tokens;
    char close = tokens[index].type == JSON_OBJECT ? '}' : ']';
    skip_space(p);
    if (peek(p) == close) {
        p->pos++;
        return 0;
    }
    for (;;) {
        skip_space(p);
        int child;
        if (close == '}') {
            if (peek(p) != '"')
                return fail(p, p->pos, "expected a string key");
            child = parse_string(p, index);
            skip_space(p);
            if (child < 0 || peek(p) != ':')
                return child < 0 ? -1 : fail(p, p->pos, "expected ':' after a key");
            p->pos++;
            if (parse_value(p, child, depth + 1) < 0)
                return -1;
            tokens[child].size = 1;
            tokens[child].after = p->count;
        } else if ((child = parse_value(p, index, depth + 1)) < 0) {
            return -1;
        }
        tokens[index].size++;
        skip_space(p);
        char c = peek(p);
        p->pos++;
        if (c == close)
            return 0;
        if (c != ',')
            return fail(p, p->pos - 1,
                        close == '}' ? "expected ',' or '}' in an object"
                                     : "expected ',' or ']' in an array");
    }
}

static int parse_value(parser *p, int parent, int depth)
{
    skip_space(p);
    char c = peek(p);
    if (c == '"')
        return parse_string(p, parent);
    if (c == '-' ? !starts_with(p, "-Infinity") : (c >= '0' && c <= '9'))
        return parse_number(p, parent);
    if (c != '{' && c != '[')
        return parse_word(p, parent);
    if (depth >= JSON_MAX_DEPTH)
        return fail(p, p->pos, "nested deeper than the reader's limit");
    int index = new_token(p, c == '{' ? JSON_OBJECT : JSON_ARRAY, p->pos, parent);
    if (index < 0)
        return -1;
    p->pos++;
    if (parse_children(p, index, depth) < 0)
        return -1;
    p->tokens[index].end = p->pos;
    p->tokens[index].after = p->count;
    return index;
}

int json_parse(json_document *doc, const char *text, size_t length, json_token *tokens,
               int capacity, json_error *error)
{
    parser p = {text, length, 0, tokens, capacity, 0, error};
    if (text[length] != '\0')
        return fail(&p, length, "the text does not end with a NUL byte (json.h)");
    if (parse_value(&p, -1, 0) < 0)
        return -1;
    skip_space(&p);
    if (p.pos != length)
        return fail(&p, p.pos, "unexpected text after the value");
    doc->text = text;
    doc->tokens = tokens;
    doc->count = p.count;
    return 0;
}

/* ---- lookups --------------------------------------------------------------------------- */

int json_is(const json_document *doc, int token, json_type type)
{
    return token >= 0 && token < doc->count && doc->tokens[token].type == type;
}

const char *json_type_name(const json_document *doc, int token)
{
    static const char *const names[] = {"nothing", "object", "array", "string",
                                        "number",  "true",   "false", "null"};
    return token >= 0 && token < doc->count ? names[doc->tokens[token].type] : names[0];
}

int json_size(const json_document *doc, int token)
{
    return json_is(doc, token, JSON_OBJECT) || json_is(doc, token, JSON_ARRAY)
               ? doc->tokens[token].size
               : 0;
}

int json_first(const json_document *doc, int container)
{
    return json_size(doc, container) > 0 ? container + 1 : -1;
}

int json_next(const json_document *doc, int child)
{
    if (child < 0 || child >= doc->count || doc->tokens[child].parent < 0)
        return -1;
    int next = doc->tokens[child].after;
    return next < doc->tokens[doc->tokens[child].parent].after ? next : -1;
}

int json_member(const json_document *doc, int object, const char *key)
{
    int found = -1;
    if (!json_is(doc, object, JSON_OBJECT))
        return -1;
    for (int k = json_first(doc, object); k >= 0; k = json_next(doc, k))
        if (json_string_equals(doc, k, key))
            found = k + 1;
    return found;
}

int json_element(const json_document *doc, int array, int i)
{
    if (!json_is(doc, array, JSON_ARRAY) || i < 0)
        return -1;
    int e = json_first(doc, array);
    while (e >= 0 && i-- > 0)
        e = json_next(doc, e);
    return e;
}

int json_number(const json_document *doc, int token, double *out)
{
    if (!json_is(doc, token, JSON_NUMBER))
        return -1;
    *out = strtod(doc->text + doc->tokens[token].start, NULL);
    return 0;
}

/* ---- strings --------------------------------------------------------------------------- */

static unsigned hex4(const char *s)
{
    unsigned value = 0;
    for (int i = 0; i < 4; i++) {
        char c = s[i];
        value = value * 16 +
                (unsigned)(c <= '9' ? c - '0' : (c | 0x20) - 'a' + 10); /* checked: is_hex */
    }
    return value;
}

/* Decode the character at s[*i] (a byte or an escape) into out, 1 to 4 bytes; return their
 * number and advance *i past it. The string was checked by parse_string. */
static int decode_one(const char *s, size_t end, size_t *i, unsigned char out[4])
{
    if (s[*i] != '\\') {
        out[0] = (unsigned char)s[(*i)++];
        return 1;
    }
    char c = s[*i + 1];
    if (c != 'u') {
        static const char from[] = "\"\\/bfnrt", to[] = "\"\\/\b\f\n\r\t";
        out[0] = (unsigned char)to[strchr(from, c) - from];
        *i += 2;
        return 1;
    }
    unsigned code = hex4(s + *i + 2);
    *i += 6;
    if (code >= 0xD800 && code < 0xDC00 && *i + 6 <= end && s[*i] == '\\' && s[*i + 1] == 'u') {
        unsigned low = hex4(s + *i + 2);
        if (low >= 0xDC00 && low < 0xE000) {
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
            *i += 6;
        }
    }
    if (code < 0x80) {
        out[0] = (unsigned char)code;
        return 1;
    }
    if (code < 0x800) {
        out[0] = (unsigned char)(0xC0 | code >> 6);
        out[1] = (unsigned char)(0x80 | (code & 0x3F));
        return 2;
    }
    if (code < 0x10000) {
        out[0] = (unsigned char)(0xE0 | code >> 12);
        out[1] = (unsigned char)(0x80 | (code >> 6 & 0x3F));
        out[2] = (unsigned char)(0x80 | (code & 0x3F));
        return 3;
    }
    out[0] = (unsigned char)(0xF0 | code >> 18);
    out[1] = (unsigned char)(0x80 | (code >> 12 & 0x3F));
    out[2] = (unsigned char)(0x80 | (code >> 6 & 0x3F));
    out[3] = (unsigned char)(0x80 | (code & 0x3F));
    return 4;
}

int json_string_equals(const json_document *doc, int token, const char *s)
{
    if (!json_is(doc, token, JSON_STRING))
        return 0;
    const json_token *t = &doc->tokens[token];
    size_t i = t->start, matched = 0;
    while (i < t->end) {
        unsigned char bytes[4];
        int n = decode_one(doc->text, t->end, &i, bytes);
        for (int k = 0; k < n; k++, matched++)
            if (s[matched] == '\0' || (unsigned char)s[matched] != bytes[k])
                return 0;
    }
    return s[matched] == '\0';
}

size_t json_string_copy(const json_document *doc, int token, char *out, size_t size)
{
    size_t length = 0;
    if (json_is(doc, token, JSON_STRING)) {
        const json_token *t = &doc->tokens[token];
        for (size_t i = t->start; i < t->end;) {
            unsigned char bytes[4];
            int n = decode_one(doc->text, t->end, &i, bytes);
            for (int k = 0; k < n; k++, length++)
                if (length + 1 < size)
                    out[length] = (char)bytes[k];
        }
    }
    if (size > 0)
        out[length < size ? length : size - 1] = '\0';
    return length;
}
