"""A program that sleeps for an hour, ignoring SIGTERM, SIGINT and SIGHUP, where the first
argument says: at ``reset`` (before its first reply), at the first ``observe``, or at ``bye``
(it never exits); until then it drives straight at the goal. It writes its pid to the file
given as the second argument."""

import json
import math
import os
import signal
import sys
import time


def main() -> None:
    """Answer every message until the one named, then sleep."""
    for each in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(each, signal.SIG_IGN)
    with open(sys.argv[2], "w") as file:
        file.write(str(os.getpid()))
    for line in sys.stdin:
        message = json.loads(line)
        if message["type"] == sys.argv[1]:
            time.sleep(3600)
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
