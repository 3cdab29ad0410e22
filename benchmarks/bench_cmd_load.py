"""Is a healthy ``--cmd`` program blamed for the machine's load? N oracles at once.

Run from the project root: ``python benchmarks/bench_cmd_load.py [--oracles N] [--jobs J]``.

Runs ``--oracles`` (default 4) ``ifgm-ref oracle --cmd ... --profile quick`` at once, each
against ``ifgm-ref serve --planner ifgm`` behind ``benchmarks/cmd_relay.py``, a relay that
logs how long the oracle waited for each reply (``cmd_relay.py`` says how). The reference
behind ``serve`` passes every check in process, so an ERROR here is the load blamed on the
program (issue 24, item 5). First it times ``--alone`` sessions of the relayed program one
at a time, before the oracles (start-up and exit at the machine's load of the moment). Then
it prints per oracle: its exit status, wall time and verdict counts; the start-up latency of
its programs (one per program start: the oracle starts one per check in each worker
process), the per-reply latency (median, 99th percentile, max) and the exit latency after
``bye``; then every ERROR's message, and the load average sampled every ``--sample`` seconds
during the run.
``--timeout`` and ``--startup-timeout``, if given, are passed to every oracle.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shlex
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path

from ifgm_ref.apps.bench.report import machine
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.io.transport.external import ExternalPlanner
from ifgm_ref.oracle.runner import Status

RELAY = Path(__file__).resolve().parent / "cmd_relay.py"
#: The start-up timeout of the starts timed alone, s: long enough never to cut one short.
LONG_WAIT = 600.0
#: What the relay times: the first reply of a start, every other reply, the exit after bye.
KINDS = ("startup", "reply", "exit")
#: The verdicts of the report's lines, in the order they are printed.
VERDICTS = [status.upper() for status in Status]


@dataclass(frozen=True)
class OracleRun:
    """One oracle's outcome: its report's verdicts, and the latencies its relays logged, s,
    by kind (:data:`KINDS`)."""

    status: int
    seconds: float
    verdicts: dict[str, int]
    errors: list[str]
    latencies: dict[str, list[float]]


def program_command(args: argparse.Namespace, logs: Path) -> list[str]:
    """``ifgm-ref serve`` behind the relay, the relay logging to ``logs``."""
    serve = [sys.executable, "-m", "ifgm_ref", "serve", "--planner", args.planner]
    return [sys.executable, str(RELAY), str(logs), "--", *serve]


def oracle_command(args: argparse.Namespace, logs: Path, artifacts: Path) -> list[str]:
    """The ``ifgm-ref oracle`` command line of one oracle, its relays logging to ``logs``."""
    program = shlex.join(program_command(args, logs))
    command = [sys.executable, "-m", "ifgm_ref", "oracle", "--cmd", program]
    command += ["--profile", args.profile, "--artifacts", str(artifacts)]
    if args.jobs is not None:
        command += ["--jobs", str(args.jobs)]
    for option in ("timeout", "startup_timeout"):
        value = getattr(args, option)
        if value is not None:
            command += [f"--{option.replace('_', '-')}", str(value)]
    for check in args.check or []:
        command += ["--check", check]
    return command


def sessions_alone(args: argparse.Namespace, logs: Path) -> tuple[list[float], list[float]]:
    """Seconds from starting the relayed program to its first ``ready``, and from ``bye`` to
    its exit, as the oracle waits (:class:`ExternalPlanner`), ``--alone`` times, one program
    at a time."""
    starts, exits = [], []
    for _ in range(args.alone):
        planner = ExternalPlanner(program_command(args, logs), startup_timeout=LONG_WAIT)
        began = time.monotonic()
        planner.reset(Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), EpisodeParams())
        starts.append(time.monotonic() - began)
        began = time.monotonic()
        planner.close()
        exits.append(time.monotonic() - began)
    return starts, exits


def read_report(stdout: str) -> tuple[dict[str, int], list[str]]:
    """The verdict counts of an oracle's report, and each ERROR's check and message."""
    counts = dict.fromkeys(VERDICTS, 0)
    errors: list[str] = []
    lines = stdout.splitlines()
    for k, line in enumerate(lines):
        verdict = next((v for v in VERDICTS if line.startswith(v + " ")), None)
        if verdict is None:
            continue
        counts[verdict] += 1
        if verdict == Status.ERROR.upper():
            message = lines[k + 1].strip() if k + 1 < len(lines) else ""
            errors.append(f"{line.split()[1]}: {message}")
    return {v: n for v, n in counts.items() if n}, errors


def read_logs(folder: Path) -> dict[str, list[float]]:
    """The latencies, s, every relay in ``folder`` logged, by kind (:data:`KINDS`)."""
    latencies: dict[str, list[float]] = {kind: [] for kind in KINDS}
    for path in sorted(folder.glob("relay-*.jsonl")):
        for line in path.read_text().splitlines():
            ((kind, seconds),) = json.loads(line).items()
            latencies[kind].append(seconds)
    return latencies


def median(values: list[float]) -> float:
    """The median of ``values``, or nan for none."""
    return statistics.median(values) if values else math.nan


def maximum(values: list[float]) -> float:
    """The largest of ``values``, or nan for none."""
    return max(values, default=math.nan)


def percentile(values: list[float], q: float) -> float:
    """The ``q``-quantile of ``values`` (nearest rank), or nan for none."""
    if not values:
        return math.nan
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, max(0, round(q * len(ordered)) - 1))]


def sample_load(every: float, samples: list[float], stop: threading.Event) -> None:
    """Append the 1-minute load average to ``samples`` every ``every`` s until ``stop``."""
    while not stop.is_set():
        samples.append(os.getloadavg()[0])
        stop.wait(every)


def run_oracles(args: argparse.Namespace, work: Path) -> tuple[list[OracleRun], list[float]]:
    """Start every oracle at once, wait for all; return their outcomes and the load samples."""
    load: list[float] = []
    stop = threading.Event()
    sampler = threading.Thread(target=sample_load, args=(args.sample, load, stop), daemon=True)
    sampler.start()
    began = time.monotonic()
    processes = []
    for k in range(args.oracles):
        command = oracle_command(args, work / f"logs-{k}", work / f"artifacts-{k}")
        out = (work / f"oracle-{k}.out").open("w")
        err = (work / f"oracle-{k}.err").open("w")
        processes.append((subprocess.Popen(command, stdout=out, stderr=err, text=True), out, err))
    runs = []
    for k, (process, out, err) in enumerate(processes):
        status = process.wait()
        seconds = time.monotonic() - began
        out.close()
        err.close()
        print(f"oracle {k} done after {seconds:.0f} s (exit {status})", file=sys.stderr)
        verdicts, errors = read_report((work / f"oracle-{k}.out").read_text())
        runs.append(OracleRun(status, seconds, verdicts, errors, read_logs(work / f"logs-{k}")))
    stop.set()
    sampler.join()
    return runs, load


def main() -> None:
    """Run the oracles and print what each got and how long its program kept it waiting."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--oracles", type=int, default=4, help="oracles at once (default 4)")
    parser.add_argument("--jobs", type=int, help="each oracle's --jobs (default: its own)")
    parser.add_argument("--profile", default="quick", help="each oracle's --profile (quick)")
    parser.add_argument("--planner", default="ifgm", help="the planner behind serve (ifgm)")
    parser.add_argument("--check", action="append", help="run only this check (repeatable)")
    parser.add_argument("--timeout", type=float, help="each oracle's --timeout, s")
    parser.add_argument("--startup-timeout", type=float, help="each oracle's --startup-timeout")
    parser.add_argument(
        "--alone", type=int, default=5, help="starts timed alone, before the oracles (5)"
    )
    parser.add_argument("--sample", type=float, default=5.0, help="load sampling period, s (5)")
    parser.add_argument("--keep", metavar="DIR", help="keep reports and logs here (default: a "
                        "temporary folder, removed)")  # fmt: skip
    args = parser.parse_args()
    print(f"machine: {machine()}")
    example = shlex.join(oracle_command(args, Path("LOGS"), Path("DIR")))
    print(f"{args.oracles} oracles at once, each: {example}")
    with tempfile.TemporaryDirectory() as temporary:
        work = Path(args.keep or temporary)
        work.mkdir(parents=True, exist_ok=True)
        starts, exits = sessions_alone(args, work / "logs-alone")
        print(
            f"alone: start-up median {median(starts):.2f} s, max {maximum(starts):.2f} s; exit "
            f"median {median(exits):.2f} s, max {maximum(exits):.2f} s; over {len(starts)} "
            f"sessions, at load average {os.getloadavg()[0]:.2f}",
            flush=True,
        )
        runs, load = run_oracles(args, work)
    print_runs(runs)
    every = {kind: [x for run in runs for x in run.latencies[kind]] for kind in KINDS}
    print(
        f"all: {sum(run.verdicts.get('ERROR', 0) for run in runs)} errors; start-up median "
        f"{median(every['startup']):.2f} s, max {maximum(every['startup']):.2f} s over "
        f"{len(every['startup'])} starts; reply median {1e3 * median(every['reply']):.2f} ms, "
        f"p99 {1e3 * percentile(every['reply'], 0.99):.1f} ms, max "
        f"{1e3 * maximum(every['reply']):.1f} ms over {len(every['reply'])} replies; exit "
        f"median {median(every['exit']):.2f} s, max {maximum(every['exit']):.2f} s over "
        f"{len(every['exit'])} exits"
    )
    print(
        f"load average (1 min) during the run: min {min(load):.2f}, median "
        f"{median(load):.2f}, max {max(load):.2f} ({len(load)} samples); "
        f"at the end {' '.join(f'{v:.2f}' for v in os.getloadavg())}"
    )


def print_runs(runs: list[OracleRun]) -> None:
    """One line per oracle (start-ups and exits in s, replies in ms), then every ERROR."""
    print(
        f"{'oracle':>6} {'status':>6} {'wall s':>6}  {'verdicts':<34} {'starts':>6} "
        f"{'median':>6} {'max':>6} {'replies':>8} {'med ms':>6} {'p99 ms':>6} {'max ms':>7} "
        f"{'exits':>5} {'median':>6} {'max':>6}"
    )
    for k, run in enumerate(runs):
        verdicts = ", ".join(f"{n} {v.lower()}" for v, n in run.verdicts.items())
        starts, replies, exits = (run.latencies[kind] for kind in KINDS)
        print(
            f"{k:>6} {run.status:>6} {run.seconds:>6.0f}  {verdicts:<34} {len(starts):>6} "
            f"{median(starts):>6.2f} {maximum(starts):>6.2f} {len(replies):>8} "
            f"{1e3 * median(replies):>6.2f} {1e3 * percentile(replies, 0.99):>6.1f} "
            f"{1e3 * maximum(replies):>7.1f} {len(exits):>5} {median(exits):>6.2f} "
            f"{maximum(exits):>6.2f}"
        )
    for k, run in enumerate(runs):
        for error in run.errors:
            print(f"oracle {k} ERROR {error}")


if __name__ == "__main__":
    main()
