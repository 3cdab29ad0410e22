"""A program that writes to the terminal (``/dev/tty``) at its start and at every message,
saying on stderr whether it could, and otherwise drives straight at the goal."""

import json
import math
import sys

NOTE = b"HOSTILE PROGRAM WAS HERE\n"


def scribble() -> None:
    """Write :data:`NOTE` to the controlling terminal, if there is one."""
    try:
        with open("/dev/tty", "wb", buffering=0) as tty:
            tty.write(NOTE)
        print("wrote to the terminal", file=sys.stderr)
    except OSError as err:
        print(f"no terminal: {err}", file=sys.stderr)


def main() -> None:
    """Scribble on the terminal, then answer every message."""
    scribble()
    for line in sys.stdin:
        scribble()
        message = json.loads(line)
        if message["type"] == "bye":
            return
        if message["type"] == "reset":
            speed, reply = message["robot"]["speed"], {"type": "ready"}
        else:
            (x, y, _), (gx, gy) = message["pose"], message["goal"]
            heading = math.atan2(gy - y, gx - x)
            reply = {"type": "command", "heading": heading, "speed": speed}
        sys.stdout.write(json.dumps(reply) + "\n")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
