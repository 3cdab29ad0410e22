/* The JSON-lines protocol's messages (docs/oracle-protocol.md) and the port's structs
 * (types.h): the oracle's `reset` and `observe` read into ifgm_episode, ifgm_tuning and
 * ifgm_observation, and a planner's ifgm_command written as a `command` line. ifgm_json
 * speaks the protocol with them; ifgm_vectors reads the vectors' recorded messages with them.
 *
 * The readers check what the port relies on, as ifgm_ref/io/transport/wire.py does, and name
 * the offending field in their error ("reset.robot.radius: missing"): every field present
 * but the optional ones (the robot's dynamics `braking`, `acceleration`, `response` and its
 * `latency`: absent, the paper's robot), every number finite (but `braking` and
 * `acceleration`, which Python reads as an infinity when written 1e400), `sensor.rays` an
 * integer >= 2, `robot.latency` an integer >= 0, the scan's angles consistent with the
 * sensor's and with the scan's length. Unknown fields are ignored. Domains (a radius > 0, a d_th > 2 r, ...) are left to
 * the planners' init, which answers a status (types.h). */
#ifndef IFGM_PROTOCOL_H
#define IFGM_PROTOCOL_H

#include <stdio.h>

#include "json.h"
#include "types.h"

/* What is wrong with a message, as one line of text. */
typedef struct {
    char text[256];
} protocol_error;

typedef enum {
    PROTOCOL_RESET,
    PROTOCOL_READY,
    PROTOCOL_OBSERVE,
    PROTOCOL_COMMAND,
    PROTOCOL_BYE
} protocol_type;

/* The `type` of the message at token message: 0 and *type, or -1 and error (the message is
 * no object, has no type, or one the protocol does not know). */
int protocol_type_of(const json_document *doc, int message, protocol_type *type,
                     protocol_error *error);

/* Read a `reset` message into *episode and *tuning (every parameter unset, then each that
 * `params` names set: ifgm_tuning_unset). Returns 0, or -1 and error. */
int protocol_read_reset(const json_document *doc, int message, ifgm_episode *episode,
                        ifgm_tuning *tuning, protocol_error *error);

/* The names in a `reset` message's `params` that no ifgm_tuning field has (protocol_read_reset
 * ignores them), written to names quoted and comma-separated ("'foo', 'bar'"; cut short to
 * size bytes); returns how many there are. */
int protocol_unknown_params(const json_document *doc, int message, char *names, size_t size);

/* Read an `observe` message into *observation: a null range is +INFINITY. More ranges than
 * IFGM_MAX_RAYS is an error. Returns 0, or -1 and error. */
int protocol_read_observe(const json_document *doc, int message, ifgm_observation *observation,
                          protocol_error *error);

/* A `command` message as recorded in the vectors: its numbers, and the token of its branch
 * (-1 when absent or null). */
typedef struct {
    double heading, speed;
    int branch;
} protocol_command;

/* Read a `command` message into *command. Returns 0, or -1 and error. */
int protocol_read_command(const json_document *doc, int message, protocol_command *command,
                          protocol_error *error);

/* Room for a number written by protocol_format_number, bytes. */
#define PROTOCOL_NUMBER_SIZE 32

/* x as the protocol writes numbers: the fewest significant digits (17 at most) that read back
 * as the same double, as Python's repr, and ".0" after an integer, so that Python reads a
 * float (json.loads reads "-0" as the integer 0, losing the sign of -0.0). A NaN or an
 * infinity is written "nan", "inf": not JSON. */
void protocol_format_number(char out[PROTOCOL_NUMBER_SIZE], double x);

/* Write the `ready` reply, one line. Returns 0, or -1 if out failed. */
int protocol_write_ready(FILE *out);

/* Write the `command` reply for command, one line: numbers by protocol_format_number (a float
 * build's are the doubles equal to its floats), absent strings left out. Writes nothing and returns -1 with error if the heading or the
 * speed is not finite (JSON cannot carry it); returns -1 if out failed; else 0. */
int protocol_write_command(FILE *out, const ifgm_command *command, protocol_error *error);

#endif
