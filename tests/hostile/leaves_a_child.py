"""A program that forks a grandchild of the oracle, which keeps the program's pipes open and
runs for a minute, and adds its pid to the file given as the first argument. Then, as the
second argument says: ``bye`` drives straight at the goal and exits with status 0 at ``bye``;
``exit`` exits with status 0 at once, before answering anything."""

import os
import signal
import sys
import time

from seek_goal import answer_until_bye


def main() -> None:
    """Fork the lingering grandchild, then play or leave."""
    pid = os.fork()
    if pid == 0:  # the grandchild: holds stdin, stdout and stderr, ignores all but SIGKILL
        for each in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
            signal.signal(each, signal.SIG_IGN)
        time.sleep(60)
        os._exit(0)
    with open(sys.argv[1], "a") as file:  # one line for each start of the program
        file.write(f"{pid}\n")
    if sys.argv[2] == "exit":
        return
    answer_until_bye()


if __name__ == "__main__":
    main()
