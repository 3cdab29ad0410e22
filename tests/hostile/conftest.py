"""The hostile programs here run as the oracle's child processes, never under pytest."""

collect_ignore_glob = ["*.py"]
