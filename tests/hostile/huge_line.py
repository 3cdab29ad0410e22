"""A program that answers ``reset`` with ``ready`` and the first ``observe`` with one line of
100 MB (a ``command`` padded with a field of 100 million ``x``), written 64 kB at a time so
that it holds no more than that itself; it exits at ``bye``."""

import sys

SIZE = 100_000_000
CHUNK = 1 << 16


def main() -> None:
    """Answer ``reset``; answer ``observe`` with the huge line."""
    for line in sys.stdin:
        if '"bye"' in line:
            return
        if '"reset"' in line:
            sys.stdout.write('{"type": "ready"}\n')
        else:
            sys.stdout.write('{"type": "command", "heading": 0.0, "speed": 1.0, "pad": "')
            for _ in range(SIZE // CHUNK):
                sys.stdout.write("x" * CHUNK)
            sys.stdout.write('"}\n')
        sys.stdout.flush()


if __name__ == "__main__":
    main()
