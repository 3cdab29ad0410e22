"""A program whose output never ends, as the argument says: ``line`` answers ``reset`` with
``ready``, then at the first ``observe`` writes ``x`` without a newline for ever; ``lines``
answers ``reset`` with ``ready`` lines for ever. A ``bye`` that comes first ends it."""

import sys

CHUNK = 1 << 16


def main() -> None:
    """Answer ``reset``, then write without end."""
    endless = sys.argv[1]
    for line in sys.stdin:
        if '"bye"' in line:
            return
        if endless == "lines":
            while True:
                sys.stdout.write('{"type": "ready"}\n' * 1000)
                sys.stdout.flush()
        if '"reset"' in line:
            sys.stdout.write('{"type": "ready"}\n')
            sys.stdout.flush()
            continue
        sys.stdout.write('{"type": "command", "heading": 0.0, "speed": 1.0, "behaviour": "')
        while True:
            sys.stdout.write("x" * CHUNK)


if __name__ == "__main__":
    main()
