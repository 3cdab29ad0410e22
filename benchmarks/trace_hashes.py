"""Trace hashes of 7 planners in 28 worlds: a refactoring that keeps behaviour keeps them.

Each planner (IFGM, IBA, Bug1, Bug2, DistBug, FGM, APF) runs in each world (the 15 built-in
ones, the first 10 of ``tests/worlds`` and BARN's worlds 5, 115 and 151) through
``ifgm-ref simulate ... --max-time 120 --trace FILE``, in this process; each line gives the
planner, the world, the first 16 hex digits of the trace file's SHA-256 and the start of the
result line. Compare two commits' outputs with ``diff``::

    python benchmarks/trace_hashes.py > before.txt    # at one commit
    python benchmarks/trace_hashes.py > after.txt     # at the other
    diff before.txt after.txt

About 40 s on one core.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ifgm_ref.apps.cli import main as cli  # noqa: E402

BUILTIN = [
    "free", "scenario1", "fig7a", "fig7b", "fig7c", "fig7d", "scenario2", "box", "post",
    "offset_box", "posts_wide", "posts_narrow", "wall_posts", "u_trap", "h_block",
]  # fmt: skip
PLANNERS = ["ifgm", "iba", "bug1", "bug2", "distbug", "fgm", "apf"]


def worlds() -> list[str]:
    """The 28 worlds: built-in, the first 10 world files of the tests, 3 of BARN's."""
    files = sorted(str(p) for p in (ROOT / "tests" / "worlds").glob("*.json"))[:10]
    return [*BUILTIN, *files, "barn:5", "barn:115", "barn:151"]


def trace_hash(planner: str, world: str, folder: Path) -> tuple[str, str]:
    """The trace's hash and the result line of one run."""
    trace = folder / "trace.csv"
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(io.StringIO()):
        cli(["simulate", world, "--planner", planner, "--max-time", "120", "--trace", str(trace)])
    return hashlib.sha256(trace.read_bytes()).hexdigest()[:16], printed.getvalue().strip()


def main() -> None:
    """Print each run's line."""
    with tempfile.TemporaryDirectory() as tmp:
        for planner in PLANNERS:
            for world in worlds():
                digest, result = trace_hash(planner, world, Path(tmp))
                print(f"{planner} {Path(world).name} {digest} {result[:80]}", flush=True)


if __name__ == "__main__":
    main()
