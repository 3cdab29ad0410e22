"""What one step of a ``--cmd`` program costs the oracle: polled pipes against threaded ones.

Run from the project root: ``python benchmarks/bench_cmd_step.py [--repeats N] [--cmd CMD]``.

The reference IFGM's episode in ``u_trap`` is recorded in process; its observations are then
handed, open loop, to the program (default: the C port, ``examples/c/build/ifgm_json``, built
with ``make`` if missing) through :class:`~ifgm_ref.io.transport.external.ExternalPlanner`, once
with each kind of :mod:`~ifgm_ref.io.transport.pipes` (alternating, ``--repeats`` passes each,
one program per pass). The report gives the median pass in microseconds per step and, apart,
what the oracle's side spends encoding the ``observe`` message and reading the ``command``
reply, which both kinds share.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import time
from pathlib import Path

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.core.recording import RecordingPlanner
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.io.transport import pipes
from ifgm_ref.io.transport.external import ExternalPlanner
from ifgm_ref.io.transport.wire import (
    command_message,
    decode,
    encode,
    observe_message,
    parse_command,
)
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.simulator import simulate

ROOT = Path(__file__).resolve().parent.parent
C_PORT = ROOT / "examples" / "c" / "build" / "ifgm_json"


def main() -> None:
    """Time the steps both ways and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=7, help="passes per kind (default 7)")
    parser.add_argument("--cmd", help="the program (default: the C port)")
    args = parser.parse_args()
    if args.cmd is None and not C_PORT.exists():
        subprocess.run(["make", "-s", "-C", str(ROOT / "examples" / "c")], check=True)
    command = args.cmd or str(C_PORT)
    recorder = RecordingPlanner(make_planner("ifgm"))
    simulate(resolve_world("u_trap"), recorder)
    recording = recorder.recording()
    observations = [obs for obs, _ in recording.steps]
    print(f"machine: {machine()}")
    print(f"program: {command}; {len(observations)} steps a pass, {args.repeats} passes a kind")
    passes: dict[str, list[float]] = {"threaded": [], "polled": []}
    for _ in range(args.repeats):
        for kind in passes:
            pipes.POLLED = kind == "polled"
            with ExternalPlanner(command) as planner:
                planner.reset(recording.start, recording.goal, recording.params)
                began = time.perf_counter()
                for observation in observations:
                    planner.step(observation)
                passes[kind].append((time.perf_counter() - began) / len(observations) * 1e6)
    for kind, times in passes.items():
        median = statistics.median(times)
        print(f"{kind:>9}: median {median:6.1f} us a step (best {min(times):.1f})")
    ratio = statistics.median(passes["threaded"]) / statistics.median(passes["polled"])
    print(f"threaded / polled: {ratio:.2f}x")
    began = time.perf_counter()
    for observation, command_sent in recording.steps:
        encode(observe_message(observation))
        parse_command(decode(encode(command_message(command_sent))), at=None)
    codec = (time.perf_counter() - began) / len(observations) * 1e6
    print(f"of which the codec (encode observe, decode command): {codec:.1f} us a step")


if __name__ == "__main__":
    main()
