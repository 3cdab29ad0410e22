"""A program that answers out of turn, as the argument says: ``command_first`` answers
``reset`` with a ``command``; ``twice`` answers every message twice; ``ready_again`` answers
``observe`` with ``ready``. Otherwise it drives straight at the goal."""

import json
import math
import sys

READY = {"type": "ready"}


def main() -> None:
    """Answer each message, out of turn."""
    mode = sys.argv[1]
    for line in sys.stdin:
        message = json.loads(line)
        if message["type"] == "bye":
            break
        if message["type"] == "reset":
            speed = message["robot"]["speed"]
            replies = [READY]
            if mode == "command_first":
                replies = [{"type": "command", "heading": 0.0, "speed": speed}]
        else:
            (x, y, _), (gx, gy) = message["pose"], message["goal"]
            command = {"type": "command", "heading": math.atan2(gy - y, gx - x), "speed": speed}
            replies = [READY if mode == "ready_again" else command]
        if mode == "twice":
            replies *= 2
        sys.stdout.write("".join(json.dumps(reply) + "\n" for reply in replies))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
