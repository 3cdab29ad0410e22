"""A program that answers ``reset``, then answers ``observe`` with a command whose
``behaviour`` holds a byte that is not UTF-8 (Latin-1 ``café``): valid JSON but for that."""

import sys


def main() -> None:
    """Answer every message; each command carries the byte 0xe9."""
    for line in sys.stdin.buffer:
        if b'"bye"' in line:
            break
        if b'"reset"' in line:
            reply = b'{"type": "ready"}\n'
        else:
            reply = b'{"type": "command", "heading": 0.0, "speed": 1.0, "behaviour": "caf\xe9"}\n'
        sys.stdout.buffer.write(reply)
        sys.stdout.buffer.flush()


if __name__ == "__main__":
    main()
