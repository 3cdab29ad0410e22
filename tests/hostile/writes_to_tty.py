"""A program that writes to the terminal (``/dev/tty``) at its start and at every message,
saying on stderr whether it could, and otherwise drives straight at the goal."""

import sys

from seek_goal import answer_until_bye

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
    answer_until_bye(lambda message: scribble())


if __name__ == "__main__":
    main()
