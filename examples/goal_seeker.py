#!/usr/bin/env python3
"""A small reactive planner speaking the oracle's JSON-lines protocol (stdlib only).

It shows what a program under test has to do (docs/oracle-protocol.md): read one JSON object
per line on stdin, answer one per line on stdout, flush after every answer, write anything
else to stderr, and exit with status 0 after "bye".

The planner: head straight for the goal; when a return lies in the robot's path (within the
robot's radius plus a margin of the line ahead, and closer than a look-ahead distance), turn
45 degrees towards the side whose free ranges are longer. It is deliberately simple: it gets
round single obstacles, but it is trapped in a U (it never remembers where it has been), so
it does not pass every property of the oracle.

Run it under the oracle with:  ifgm-ref oracle --cmd "python3 examples/goal_seeker.py"
Units: feet, seconds, radians (angles counter-clockwise, positive scan angles look left).
"""

import json
import math
import sys

#: Extra clearance wanted beside the robot, ft.
MARGIN = 0.5
#: Returns nearer than this along the path ahead make the robot turn away, ft.
LOOKAHEAD = 4.0
#: How far to turn away from a blocked path, radians (the paper's 45-degree step).
TURN = math.pi / 4


def send(message):
    """Write one message as one line of JSON, and flush so that the oracle sees it now."""
    sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()


def blocked(scan, radius):
    """True if a return lies in the corridor the robot would sweep going straight ahead."""
    for i, r in enumerate(scan["ranges"]):
        if r is None:  # null: no return within range_max
            continue
        angle = scan["angle_min"] + i * scan["angle_increment"]  # robot frame, left positive
        ahead, beside = r * math.cos(angle), r * math.sin(angle)
        if 0.0 <= ahead <= LOOKAHEAD and abs(beside) <= radius + MARGIN:
            return True
    return False


def freer_side(scan):
    """+1 if the left half of the scan (positive angles) is freer than the right, else -1."""
    left = right = 0.0
    for i, r in enumerate(scan["ranges"]):
        free = scan["range_max"] if r is None else r
        angle = scan["angle_min"] + i * scan["angle_increment"]
        if angle > 0:
            left += free
        elif angle < 0:
            right += free
    return 1 if left >= right else -1


def main():
    radius = speed = None
    for line in sys.stdin:
        message = json.loads(line)
        kind = message["type"]
        if kind == "reset":
            # A new episode: keep what the planner needs from the robot description.
            radius = message["robot"]["radius"]
            speed = message["robot"]["speed"]
            send({"type": "ready"})
        elif kind == "observe":
            x, y, theta = message["pose"]
            gx, gy = message["goal"]
            scan = message["scan"]
            if blocked(scan, radius):
                heading = theta + freer_side(scan) * TURN
                behaviour = "obstacle_avoidance"
            else:
                heading = math.atan2(gy - y, gx - x)
                behaviour = "move_to_goal"
            send({"type": "command", "heading": heading, "speed": speed, "behaviour": behaviour})
        elif kind == "bye":
            return 0
        else:
            print(f"goal_seeker: unexpected message type {kind!r}", file=sys.stderr)
            return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
