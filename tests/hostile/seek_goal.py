"""The well-behaved part the hostile programs share: answer each protocol message by driving
straight at the goal, until ``bye``; ``before`` (if given) sees each message first."""

import json
import math
import sys
from collections.abc import Callable
from typing import Any


def answer_until_bye(before: Callable[[dict[str, Any]], None] | None = None) -> None:
    """Answer ``reset`` with ``ready`` and ``observe`` with a command at the goal, at the
    robot's speed; return at ``bye``."""
    speed = 0.0
    for line in sys.stdin:
        message = json.loads(line)
        if before is not None:
            before(message)
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
