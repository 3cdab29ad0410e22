"""A program that answers ``reset`` with ``ready``, then closes its stdout at the first
``observe`` and goes on running: it reads its stdin until it ends (and exits at ``bye``)."""

import os
import sys


def main() -> None:
    """Answer ``ready``; close stdout at ``observe``; keep reading."""
    for line in sys.stdin:
        if '"bye"' in line:
            return
        if '"reset"' in line:
            sys.stdout.write('{"type": "ready"}\n')
            sys.stdout.flush()
        elif not sys.stdout.closed:
            sys.stdout.close()
            os.close(1)


if __name__ == "__main__":
    main()
