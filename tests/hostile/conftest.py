"""The hostile programs here run as the oracle's child processes, not under pytest: never import them."""

collect_ignore_glob = ["*.py"]
