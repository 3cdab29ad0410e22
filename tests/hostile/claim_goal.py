"""A program that never moves and claims, at every step, to have reached the goal."""

import json
import sys


def main() -> None:
    """Answer every message of the protocol; every command claims the goal."""
    for line in sys.stdin:
        kind = json.loads(line)["type"]
        if kind == "bye":
            break
        reply = (
            {"type": "ready"}
            if kind == "reset"
            else {"type": "command", "linear": 0, "angular": 0, "stop": "goal_reached"}
        )
        sys.stdout.write(json.dumps(reply) + "\n")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
