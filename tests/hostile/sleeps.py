"""A program that sleeps for an hour, ignoring SIGTERM, SIGINT and SIGHUP, where the first
argument says: at ``reset`` (before its first reply), at the first ``observe``, or at ``bye``
(it never exits); until then it drives straight at the goal. It writes its pid to the file
given as the second argument."""

import os
import signal
import sys
import time
from typing import Any

from seek_goal import answer_until_bye


def _sleep_at(message: dict[str, Any]) -> None:
    """Sleep for an hour at the message the first argument names."""
    if message["type"] == sys.argv[1]:
        time.sleep(3600)


def main() -> None:
    """Answer every message until the one named, then sleep."""
    for each in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(each, signal.SIG_IGN)
    with open(sys.argv[2], "w") as file:
        file.write(str(os.getpid()))
    answer_until_bye(_sleep_at)


if __name__ == "__main__":
    main()
