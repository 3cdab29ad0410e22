"""Cost of one planner decision (scan in, command out): wall-clock time and operation counts.

Run from the project root: ``python benchmarks/bench_decision.py`` (``--help`` for options).

The decisions
-------------
Each planner (IFGM, FGM, DistBug; IBA for information) runs one real episode in each world
(by default ``scenario1``, the paper's simple obstacles, and ``u_trap``, a U across the
line), with the default robot, sensor (135 degrees, 76 rays, 15 ft) and time step, up to
``--max-time`` seconds; :class:`~ifgm_ref.core.recording.RecordingPlanner` keeps every
observation and the command answered. So each planner is timed on its own decisions: moving
to the goal, meeting and avoiding obstacles, and (FGM in the U) trapped with every ray
blocked, where FGM's arrays are largest (every return against every ray). The default limit
lets every planner finish ``scenario1``; FGM spends the rest of it trapped in the U (the
simulator's stall rules are off here, so that those decisions are recorded).

The wall-clock measurement
--------------------------
A pass replays every recorded episode into a fresh planner (``make_planner(name)``, reset
with the recorded start, goal and parameters) and times each ``step(observation)`` alone
with ``time.perf_counter_ns``; the planners are deterministic, so the replayed commands must
equal the recorded ones (asserted: the benchmark times the episode's real decisions). A pass
reports the median and the 90th percentile over its decisions, and the median per decision
branch (``Command.branch``: IFGM's Figure 3 branch). The report gives the median over
``--repeats`` passes and, in brackets, the best pass. The planners take turns within each
pass, so that a noisy stretch of the machine does not fall on one planner only. The cyclic
garbage collector is off while timing (as ``timeit`` does). Timings are wall-clock on one
core: OpenBLAS is held to one thread.

The operation counts
--------------------
Two extra replays count what each decision executes; the counts are deterministic:

* *bytecodes*: Python bytecode instructions, by ``sys.settrace`` with
  ``frame.f_trace_opcodes``, split into the planner's own code (``ifgm_ref``) and the rest
  (numpy's Python layer, the standard library, generated dataclass code), with the calls of
  the ``math`` module (scalar ``atan2``, ``hypot``, ``cos`` ...) counted by ``sys.setprofile``;
* *array elements*: numpy hides loops inside vectorised calls (over the 76 rays, the returns,
  the remembered points), so the replay hands the planner scans whose arrays are a counting
  ``ndarray`` subclass (:class:`CountedArray`). Every array derived from them is one too,
  and every numpy operation on one adds its size -- the largest input or the output,
  whichever is larger -- to the decision's element count (transcendental ufuncs, such as
  ``cos``, ``arcsin``, ``hypot``, separately).

The microcontroller estimate
----------------------------
A C port does the same work without the interpreter: the planner's own bytecodes become
scalar code, the array elements become loops. :class:`McuModel` states the assumptions --
instructions per bytecode, per element and per transcendental function, a Cortex-M4F-class
clock, one instruction per cycle, float32 -- and the report gives the resulting range of
cycles and microseconds per decision against the control period (``SimParams().dt``). It is
an estimate from counts, not a measurement on a microcontroller.
"""

from __future__ import annotations

import argparse
import gc
import importlib.util
import os
import statistics
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from types import FrameType
from typing import Any, NamedTuple

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # before numpy loads BLAS: one core
if importlib.util.find_spec("ifgm_ref") is None:  # run from a checkout without installing
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np
from numpy.typing import NDArray

import ifgm_ref
from ifgm_ref.apps.bench.report import machine
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.protocol import Command, Observation, Planner
from ifgm_ref.core.recording import Recording, RecordingPlanner
from ifgm_ref.core.recording import replay as replay_recording
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.simulator import simulate

#: The planners compared (IBA, IFGM's avoidance half, for information).
PLANNERS = ("ifgm", "fgm", "distbug", "iba")
#: Worlds where every planner meets obstacles: simple ones, and a U.
WORLDS = ("scenario1", "u_trap")
#: Where the planners' own code lives: its bytecodes are the decision's scalar work.
OWN_CODE = str(Path(ifgm_ref.__file__).resolve().parent)
#: Scalar ``math`` functions costed as transcendental (the rest -- ``isfinite``, ``isclose``,
#: ``floor`` ... -- are a few instructions, counted with the bytecodes around them).
MATH_TRANSCENDENTAL = frozenset(
    {"sin", "cos", "tan", "asin", "acos", "atan", "atan2", "hypot", "dist", "sqrt", "exp", "log"}
)
#: numpy ufuncs costed as transcendental per element.
UFUNC_TRANSCENDENTAL = frozenset(
    {"sin", "cos", "tan", "arcsin", "arccos", "arctan", "arctan2", "hypot", "sqrt", "exp", "log"}
)


@dataclass(frozen=True)
class McuModel:
    """The assumptions that turn operation counts into microcontroller time (low, high).

    Parameters
    ----------
    clock_hz : (float, float), default 100 to 200 MHz
        A Cortex-M4F-class microcontroller (STM32F4: 84-180 MHz; NXP K66: 180 MHz).
    per_bytecode : (float, float), default 2 to 8 instructions
        One bytecode of the planner's own code, compiled: a load, an arithmetic operation, a
        compare-and-branch, a field access; a call costs more, a constant load less.
    per_element : (float, float), default 2 to 6 instructions
        One element of a vectorised operation as a C loop: load(s), the operation, a store,
        the loop counter and branch.
    per_transcendental : (float, float), default 30 to 150 instructions
        ``sinf``, ``cosf``, ``atan2f``, ``asinf`` on a single-precision FPU: a table-based
        routine (CMSIS-DSP) near the low end, a full-accuracy libm near the high end;
        ``sqrtf`` is one 14-cycle instruction, ``hypotf`` a few more.

    One instruction per cycle (what the M4's pipeline nears running from zero-wait-state
    memory or behind a flash accelerator) and float32 throughout: the reference computes in
    float64, which an M4F emulates in software, many times slower per operation (a Cortex-M7
    with a double-precision FPU does not).
    """

    clock_hz: tuple[float, float] = (100e6, 200e6)
    per_bytecode: tuple[float, float] = (2.0, 8.0)
    per_element: tuple[float, float] = (2.0, 6.0)
    per_transcendental: tuple[float, float] = (30.0, 150.0)

    def cycles(self, ops: OpCount) -> tuple[float, float]:
        """Instructions (= cycles) of one decision, low and high."""
        transcendental = ops.math_transcendental + ops.transcendental_elements
        plain_elements = ops.elements - ops.transcendental_elements
        low, high = (
            ops.own_bytecodes * bytecode + plain_elements * element + transcendental * function
            for bytecode, element, function in zip(
                self.per_bytecode, self.per_element, self.per_transcendental, strict=True
            )
        )
        return low, high

    def microseconds(self, ops: OpCount) -> tuple[float, float]:
        """Time of one decision, us: fewest cycles at the fastest clock, most at the slowest."""
        low, high = self.cycles(ops)
        return 1e6 * low / self.clock_hz[1], 1e6 * high / self.clock_hz[0]


@dataclass(frozen=True)
class Episode:
    """One recorded episode: its world, and the reset and every (observation, command)."""

    world: str
    recording: Recording

    @property
    def steps(self) -> tuple[tuple[Observation, Command], ...]:
        """Every (observation, command) exchanged, in order."""
        return self.recording.steps


class OpCount(NamedTuple):
    """What one decision executed (see the module docstring)."""

    own_bytecodes: int
    other_bytecodes: int
    math_calls: int
    math_transcendental: int
    array_ops: int
    elements: int
    transcendental_elements: int
    returns: int
    remembered: int

    @property
    def ops(self) -> int:
        """Operations of a C port: own bytecodes, array elements and ``math`` calls."""
        return self.own_bytecodes + self.elements + self.math_calls


class Timing(NamedTuple):
    """One planner's wall-clock figures, microseconds per decision: median over passes and
    best pass of the per-pass median and 90th percentile, and the median per branch."""

    median: float
    median_best: float
    p90: float
    p90_best: float
    branches: dict[str, tuple[float, int]]


def record(planner: str, world: str, max_time: float) -> Episode:
    """Run ``planner`` in the built-in ``world`` for at most ``max_time`` s, stalled or not,
    and keep it all."""
    recorder = RecordingPlanner(make_planner(planner))
    sim = SimParams(max_time=max_time, stall_time=None, stall_laps=None)
    simulate(resolve_world(world), recorder, sim)
    return Episode(world, recorder.recording())


def replay(
    planner: str,
    episodes: Sequence[Episode],
    step: Callable[[Planner, Observation], Command],
    swap: Callable[[Observation], Observation] | None = None,
) -> None:
    """Replay ``episodes`` into fresh planners (:func:`ifgm_ref.core.recording.replay`),
    deciding each step by ``step(planner, observation)``; check that every command equals the
    recorded one. ``swap`` may replace the observations handed over (prepared before the
    episode starts)."""
    for episode in episodes:
        observations = None if swap is None else [swap(obs) for obs, _ in episode.steps]
        replayed = replay_recording(
            episode.recording, make_planner(planner), step=step, observations=observations
        )
        for k, (_, recorded, command) in enumerate(replayed):
            assert command == recorded, (
                f"{planner} in {episode.world}, step {k}: command={command}, but should be "
                f"{recorded} (the recorded one)"
            )


def time_decisions(
    planners: Sequence[str], episodes: dict[str, list[Episode]], repeats: int
) -> dict[str, Timing]:
    """Time every decision of every planner ``repeats`` times; planners take turns."""
    passes: dict[str, list[list[int]]] = {name: [] for name in planners}
    for _ in range(repeats):
        for name in planners:
            times: list[int] = []

            def timed(planner: Planner, obs: Observation, times: list[int] = times) -> Command:
                start = time.perf_counter_ns()
                command = planner.step(obs)
                times.append(time.perf_counter_ns() - start)
                return command

            gc.disable()
            try:
                replay(name, episodes[name], timed)
            finally:
                gc.enable()
            passes[name].append(times)
    return {name: _timing(passes[name], episodes[name]) for name in planners}


def _timing(passes: list[list[int]], episodes: list[Episode]) -> Timing:
    """Summarise the passes of one planner (times in ns, one list per pass)."""
    branches = [str(cmd.branch) for ep in episodes for _, cmd in ep.steps]
    medians = [statistics.median(p) / 1e3 for p in passes]
    p90s = [float(np.percentile(p, 90)) / 1e3 for p in passes]
    by_branch: dict[str, tuple[float, int]] = {}
    for branch in dict.fromkeys(branches):
        picked = [i for i, b in enumerate(branches) if b == branch]
        per_pass = [statistics.median(p[i] for i in picked) / 1e3 for p in passes]
        by_branch[branch] = (statistics.median(per_pass), len(picked))
    return Timing(
        statistics.median(medians), min(medians), statistics.median(p90s), min(p90s), by_branch
    )


class CountedArray(np.ndarray):
    """An ndarray that counts the element operations numpy does on it.

    Every ufunc (operators, methods such as ``min`` and ``any``), every numpy function
    (``where``, ``concatenate`` ...) and every index by an array, applied to a
    ``CountedArray``, adds one to :attr:`ops` and its size -- the largest input or the
    output -- to :attr:`elements` (and to :attr:`transcendental` for the ufuncs of
    ``UFUNC_TRANSCENDENTAL``); array results are ``CountedArray`` again, so the count follows
    everything derived from the scan. The tallies are class-wide: :meth:`clear` them per
    decision.
    """

    ops = 0
    elements = 0
    transcendental = 0

    @classmethod
    def clear(cls) -> None:
        """Start counting from zero."""
        cls.ops = cls.elements = cls.transcendental = 0

    @classmethod
    def _tally(cls, inputs: Any, result: Any, transcendental: bool = False) -> None:
        size = max(_largest(inputs), _total(result), 1)
        cls.ops += 1
        cls.elements += size
        cls.transcendental += size if transcendental else 0

    def __array_ufunc__(self, ufunc: np.ufunc, method: str, *inputs: Any, **kwargs: Any) -> Any:
        plain = _plain(inputs)
        if "out" in kwargs:
            kwargs["out"] = _plain(kwargs["out"])
        result = getattr(ufunc, method)(*plain, **kwargs)
        CountedArray._tally(plain, result, ufunc.__name__ in UFUNC_TRANSCENDENTAL)
        return _counted(result)

    def __array_function__(
        self, func: Callable[..., Any], types: Any, args: Any, kwargs: dict[str, Any]
    ) -> Any:
        plain_args, plain_kwargs = _plain(args), _plain(kwargs)
        result = func(*plain_args, **plain_kwargs)
        CountedArray._tally((plain_args, plain_kwargs), result)
        return _counted(result)

    def __getitem__(self, key: Any) -> Any:
        plain = _plain(key)
        result = super().__getitem__(plain)
        if _largest(plain) > 0:  # an index array: a pass over it (basic slices are views)
            CountedArray._tally(plain, result)
        return result


def _plain(value: Any) -> Any:
    """``value`` with every :class:`CountedArray` in it (nested in tuples, lists and dicts)
    viewed as a plain ndarray."""
    if isinstance(value, CountedArray):
        return value.view(np.ndarray)
    if isinstance(value, tuple | list):
        return type(value)(_plain(v) for v in value)
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


def _counted(value: Any) -> Any:
    """``value`` with every ndarray in it (or in a tuple) viewed as a :class:`CountedArray`."""
    if isinstance(value, np.ndarray):
        return value.view(CountedArray)
    if isinstance(value, tuple):
        return tuple(_counted(v) for v in value)
    return value


def _largest(value: Any) -> int:
    """Size of the largest ndarray in ``value`` (nested in tuples, lists and dicts), or 0."""
    if isinstance(value, np.ndarray):
        return value.size
    if isinstance(value, tuple | list):
        return max((_largest(v) for v in value), default=0)
    if isinstance(value, dict):
        return max((_largest(v) for v in value.values()), default=0)
    return 0


def _total(value: Any) -> int:
    """Total size of the ndarrays of a result (an array or a tuple of them), or 0."""
    if isinstance(value, np.ndarray):
        return value.size
    if isinstance(value, tuple):
        return sum(_total(v) for v in value)
    return 0


class CountingScan(LaserScan):
    """A scan whose ranges and angles are :class:`CountedArray` views (values unchanged)."""

    def __post_init__(self) -> None:
        super().__post_init__()
        object.__setattr__(self, "ranges", self.ranges.view(CountedArray))

    @property
    def angles(self) -> NDArray[np.float64]:
        """The ray angles, as a counting array."""
        return super().angles.view(CountedArray)


def counting_observation(observation: Observation) -> Observation:
    """``observation`` with its scan as a :class:`CountingScan`."""
    scan = observation.scan
    counting = CountingScan(
        scan.angle_min,
        scan.angle_max,
        scan.angle_increment,
        scan.range_min,
        scan.range_max,
        scan.ranges,
    )
    return replace(observation, scan=counting)


def count_operations(name: str, episodes: Sequence[Episode], every: int) -> list[OpCount]:
    """Count what every ``every``-th decision of planner ``name`` executes (see the docstring):
    one replay traces bytecodes and ``math`` calls on plain scans, a second counts array
    elements on counting scans. An untraced replay runs first, and the garbage collector is
    off while counting, so that the counts are a decision's own work, not what library code
    runs once on a first call or what collecting earlier garbage runs: in one full test run
    two counts of one episode differed by 38 bytecodes of library code at the second step
    (not reproduced alone; the cause is not pinned down)."""
    replay(name, episodes, lambda planner, observation: planner.step(observation))
    gc.collect()
    gc.disable()
    try:
        traced = _trace_bytecodes(name, episodes, every)
        counted = _count_elements(name, episodes, every)
    finally:
        gc.enable()
    return [OpCount(*a, *b) for a, b in zip(traced, counted, strict=True)]


def _trace_bytecodes(
    name: str, episodes: Sequence[Episode], every: int
) -> list[tuple[int, int, int, int]]:
    """Own and other bytecodes, all and transcendental ``math`` calls, of every ``every``-th
    decision."""
    bytecodes = [0, 0]  # own, other
    maths = [0, 0]  # all math calls, transcendental ones

    def opcodes(index: int) -> Callable[[FrameType, str, Any], Any]:
        def local(frame: FrameType, event: str, arg: Any) -> Any:
            if event == "opcode":
                bytecodes[index] += 1
            return local

        return local

    own, other = opcodes(0), opcodes(1)

    def on_call(frame: FrameType, event: str, arg: Any) -> Any:
        frame.f_trace_opcodes = True
        return own if frame.f_code.co_filename.startswith(OWN_CODE) else other

    def on_c_call(frame: FrameType, event: str, arg: Any) -> None:
        if event == "c_call" and getattr(arg, "__module__", None) == "math":
            maths[0] += 1
            maths[1] += arg.__name__ in MATH_TRANSCENDENTAL

    traced: list[tuple[int, int, int, int]] = []
    decisions = 0

    def trace(planner: Planner, observation: Observation) -> Command:
        nonlocal decisions
        decisions += 1
        if decisions % every:
            return planner.step(observation)
        bytecodes[:] = maths[:] = [0, 0]
        sys.settrace(on_call)
        sys.setprofile(on_c_call)
        try:
            command = planner.step(observation)
        finally:
            sys.setprofile(None)
            sys.settrace(None)
        traced.append((bytecodes[0], bytecodes[1], maths[0], maths[1]))
        return command

    replay(name, episodes, trace)
    return traced


def _count_elements(
    name: str, episodes: Sequence[Episode], every: int
) -> list[tuple[int, int, int, int, int]]:
    """Array operations, elements and transcendental elements, returns and remembered points
    of every ``every``-th decision."""
    counted: list[tuple[int, int, int, int, int]] = []
    decisions = 0

    def count(planner: Planner, observation: Observation) -> Command:
        nonlocal decisions
        decisions += 1
        CountedArray.clear()
        command = planner.step(observation)
        if decisions % every == 0:
            memory = getattr(planner, "memory", None)
            returns = int(np.isfinite(observation.scan.ranges.view(np.ndarray)).sum())
            counted.append(
                (
                    CountedArray.ops,
                    CountedArray.elements,
                    CountedArray.transcendental,
                    returns,
                    0 if memory is None else len(memory.points),
                )
            )
        return command

    replay(name, episodes, count, counting_observation)
    return counted


def _median_max(values: Iterable[int]) -> str:
    """``median/max`` of counts (the median an actual value: the lower middle one)."""
    values = list(values)
    return f"{_short(statistics.median_low(values))}/{_short(max(values))}"


def _short(value: float) -> str:
    """A count to two significant figures, with k for thousands and M for millions."""
    if value >= 1e6:
        return f"{value / 1e6:.2g}M"
    if value >= 1e3:
        return f"{value / 1e3:.2g}k" if value < 1e4 else f"{value / 1e3:.0f}k"
    return f"{value:.2g}" if value < 100 else f"{value:.0f}"


def _arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--planners", nargs="+", default=PLANNERS, help="planners (%(default)s)")
    parser.add_argument("--worlds", nargs="+", default=WORLDS, help="built-in worlds (%(default)s)")
    parser.add_argument("--max-time", type=float, default=180.0, help="episode limit, s (180)")
    parser.add_argument("--repeats", type=int, default=5, help="timed passes (5)")
    parser.add_argument(
        "--count-every", type=int, default=5, help="count the ops of every N-th decision (5)"
    )
    return parser.parse_args(argv)


def main(argv: Sequence[str] | None = None) -> int:
    """Record, time and count the decisions of the planners; print the report."""
    args = _arguments(argv)
    dt = SimParams().dt
    print(f"machine: {machine()}")
    episodes = {
        name: [record(name, world, args.max_time) for world in args.worlds]
        for name in args.planners
    }
    rays = len(episodes[args.planners[0]][0].steps[0][0].scan.ranges)
    print(
        f"episodes: {', '.join(args.worlds)}, up to {args.max_time:g} s each (dt {dt:g} s, "
        f"{rays} rays a scan); median (best) of {args.repeats} passes, gc off while timing"
    )
    ops = {name: count_operations(name, episodes[name], args.count_every) for name in args.planners}
    timings = time_decisions(args.planners, episodes, args.repeats)
    _print_timings(timings, episodes)
    _print_counts(ops, args.count_every)
    _print_estimate(ops, McuModel(), dt)
    return 0


def _print_timings(timings: dict[str, Timing], episodes: dict[str, list[Episode]]) -> None:
    print("\nwall-clock per decision, us")
    print(f"{'planner':8s} {'decisions':>9s} {'median':>15s} {'90th percentile':>17s}")
    for name, t in timings.items():
        n = sum(len(ep.steps) for ep in episodes[name])
        print(
            f"{name:8s} {n:9d} {t.median:8.0f} ({t.median_best:4.0f}) "
            f"{t.p90:10.0f} ({t.p90_best:4.0f})"
        )
    for name, t in timings.items():
        parts = [f"{b} {us:.0f} ({n})" for b, (us, n) in t.branches.items()]
        print(f"  {name} by branch, median us (decisions): {', '.join(parts)}")


#: The columns of the operation counts: label, value of one decision.
COLUMNS: tuple[tuple[str, Callable[[OpCount], int]], ...] = (
    ("own bc", lambda o: o.own_bytecodes),
    ("other bc", lambda o: o.other_bytecodes),
    ("math", lambda o: o.math_calls),
    ("np ops", lambda o: o.array_ops),
    ("elements", lambda o: o.elements),
    ("transc.", lambda o: o.transcendental_elements),
    ("returns", lambda o: o.returns),
    ("memory", lambda o: o.remembered),
    ("ops", lambda o: o.ops),
)


def _print_counts(ops: dict[str, list[OpCount]], every: int) -> None:
    print(f"\noperations per decision, median/max over every {every}-th decision (deterministic)")
    print(f"{'planner':8s} " + " ".join(f"{label:>11s}" for label, _ in COLUMNS))
    for name, counts in ops.items():
        cells = [_median_max(get(o) for o in counts) for _, get in COLUMNS]
        print(f"{name:8s} " + " ".join(f"{cell:>11s}" for cell in cells))
    print(
        "  own bc: bytecodes of ifgm_ref code; other bc: of numpy's Python layer, stdlib, "
        "generated code;\n  math: scalar math calls; np ops, elements, transc.: numpy "
        "operations, the elements they process,\n  the transcendental ones among them; "
        "returns: rays with a return; memory: remembered points;\n  ops = own bc + elements "
        "+ math"
    )


def _print_estimate(ops: dict[str, list[OpCount]], mcu: McuModel, dt: float) -> None:
    print(
        f"\nmicrocontroller estimate (an estimate, not a measurement): "
        f"{mcu.per_bytecode[0]:g}-{mcu.per_bytecode[1]:g} instructions per own bytecode, "
        f"{mcu.per_element[0]:g}-{mcu.per_element[1]:g} per array element,\n"
        f"  {mcu.per_transcendental[0]:g}-{mcu.per_transcendental[1]:g} per transcendental "
        f"(float32 libm), 1 instruction/cycle, Cortex-M4F-class at "
        f"{mcu.clock_hz[0] / 1e6:g}-{mcu.clock_hz[1] / 1e6:g} MHz, float32; "
        f"control period dt = {dt * 1e6:,.0f} us"
    )
    print(f"{'planner':8s} {'decision':>9s} {'ops':>7s} {'cycles':>15s} {'us':>13s} {'of dt':>12s}")
    for name, counts in ops.items():
        median_k = sorted(range(len(counts)), key=lambda i: counts[i].ops)[len(counts) // 2]
        for label, op in (
            ("median", counts[median_k]),
            ("max", max(counts, key=lambda o: o.ops)),
        ):
            low, high = mcu.cycles(op)
            us_low, us_high = mcu.microseconds(op)
            print(
                f"{name:8s} {label:>9s} {_short(op.ops):>7s} "
                f"{_short(low):>7s}-{_short(high):<7s} {us_low:6.0f}-{us_high:<6.0f} "
                f"{100 * us_low / (dt * 1e6):5.1f}-{100 * us_high / (dt * 1e6):.1f} %"
            )


if __name__ == "__main__":
    sys.exit(main())
