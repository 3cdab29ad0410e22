"""Cost of one decision of the C port (``examples/c``): time, code size, stack, and a Cortex-M4F.

Run from the project root: ``python benchmarks/bench_c.py`` (``--help`` for options). Needs a C
compiler and GNU make; the Cortex-M4F part needs more (``benchmarks/cortex_m4.py``) and is
skipped, saying what is missing, without it.

The decisions
-------------
The episodes of ``benchmarks/bench_decision.py``, recorded by its ``record``: each planner
(IFGM, FGM, DistBug; IBA for information) in each of its ``WORLDS`` with the default robot
and sensor, up to ``--max-time`` seconds, the stall rules off. They are written as protocol
lines (``ifgm_ref.io.transport.wire``): per episode a ``reset``, then each ``observe`` and the
``command`` the Python planner answered.

The time (host)
---------------
``make -C examples/c`` builds ``build/ifgm_bench`` (double precision, ``-O2``), which reads
every line first, then times each step alone, ``--repeats`` passes, every episode from a
fresh init (its docstring states the method: ``clock_gettime`` around each step, less the
timer's own cost). The report gives the median over passes of the per-pass median and 90th
percentile, ns per decision (the best pass in brackets), the median per branch, the heap
calls made (0: the planners allocate nothing) and how many decisions took the Python
planner's branch (the port is checked against the reference, so the decisions timed are
the episode's own).

Code, data and stack (host)
---------------------------
The planners' objects are compiled again with ``-fstack-usage -fcallgraph-info=su`` (GCC;
the same code). A planner's objects are those defining a function reachable from its
``NAME_init`` or ``NAME_step`` in the call graph; their ``size`` (text, data, bss) is
summed. The stack of a decision is the largest sum of frames along a call chain from
``NAME_step`` (GCC's frame sizes; a recursion or a frame of unbounded size is an error);
the C library's functions it calls (libm) have no frame there and are named apart.

The Cortex-M4F (estimate)
-------------------------
``benchmarks/cortex_m4.py``: the planners built for the M4F in single precision with newlib,
their linked flash size, and every ``--m4-every``-th decision run in an emulated Cortex-M4
with each executed instruction costed by the M4's published timings (zero wait states):
cycles and microseconds at ``--m4-clock`` (80 MHz), and the stack the decision writes. It
is an estimate: an emulator and an instruction timing table, not a board.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NamedTuple

BENCHMARKS = Path(__file__).resolve().parent
ROOT = BENCHMARKS.parent
sys.path[:0] = [str(BENCHMARKS), str(ROOT)]  # bench_decision and cortex_m4; ifgm_ref unpacked

import bench_decision  # noqa: E402
import cortex_m4  # noqa: E402

from ifgm_ref.apps.bench.report import machine  # noqa: E402
from ifgm_ref.io.transport import wire  # noqa: E402

#: The C port.
PORT = ROOT / "examples" / "c"
#: The planners timed (the same as bench_decision's).
PLANNERS = bench_decision.PLANNERS
#: The compiler flags that add the frame sizes and call graph (GCC 10 or later).
STACK_FLAGS = "-fstack-usage -fcallgraph-info=su"


def write_episodes(path: Path, episodes: Sequence[bench_decision.Episode]) -> Path:
    """Write ``episodes`` as protocol lines: a reset, then each observe and its command."""
    with path.open("w") as out:
        for episode in episodes:
            r = episode.recording
            out.write(wire.encode(wire.reset_message(r.start, r.goal, r.params)) + "\n")
            for observation, command in r.steps:
                out.write(wire.encode(wire.observe_message(observation)) + "\n")
                out.write(wire.encode(wire.command_message(command)) + "\n")
    return path


def make(*targets: str, **variables: str) -> None:
    """``make -C examples/c`` with ``variables`` (``BUILD``, ``VARIANT``, ``CC`` ...)."""
    settings = [f"{name}={value}" for name, value in variables.items()]
    subprocess.run(["make", "-s", "-C", str(PORT), *settings, *targets], check=True)


def run_bench(binary: Path, planner: str, episodes: Path, repeats: int) -> dict[str, Any]:
    """``ifgm_bench``'s report for ``planner`` on the episodes file."""
    args = [str(binary), "--planner", planner, "--repeats", str(repeats), str(episodes)]
    report: dict[str, Any] = json.loads(
        subprocess.run(args, check=True, stdout=subprocess.PIPE, text=True).stdout
    )
    return report


class Sizes(NamedTuple):
    """Bytes of an object file's sections, as ``size`` counts them."""

    text: int
    data: int
    bss: int


def total_size(sizes: Sequence[Sizes]) -> Sizes:
    """The sizes of several objects together."""
    return Sizes(*(sum(column) for column in zip(Sizes(0, 0, 0), *sizes, strict=True)))


def object_sizes(objects: Sequence[Path], tool: str = "size") -> dict[str, Sizes]:
    """``size`` (Berkeley format) of each object, by file name without its suffix."""
    out = subprocess.run([tool, *map(str, objects)], check=True, capture_output=True, text=True)
    sizes = {}
    for line in out.stdout.splitlines()[1:]:
        text, data, bss, _, _, name = line.split(None, 5)
        sizes[Path(name).stem] = Sizes(int(text), int(data), int(bss))
    return sizes


class CallGraph(NamedTuple):
    """GCC's call graph (``.ci`` files): each defined function's frame, bytes, and file; the
    calls; the functions whose frame is unbounded (``dynamic`` without ``bounded``)."""

    frames: dict[str, int]
    files: dict[str, str]
    calls: dict[str, set[str]]
    unbounded: set[str]


_NODE = re.compile(r'node: \{ title: "([^"]+)" label: "[^"]*?(?:\\n(\d+) bytes \(([^)]*)\))?"')
_EDGE = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')


def read_call_graph(ci_files: Sequence[Path]) -> CallGraph:
    """Merge the ``.ci`` files of ``-fcallgraph-info=su``. A static function's name is
    ``FILE:name``, an external one's its name: the files join on those."""
    graph = CallGraph({}, {}, {}, set())
    for path in ci_files:
        text = path.read_text()
        for name, frame, kind in _NODE.findall(text):
            if frame:
                graph.frames[name] = int(frame)
                graph.files[name] = path.stem
                if "dynamic" in kind and "bounded" not in kind:
                    graph.unbounded.add(name)
        for caller, callee in _EDGE.findall(text):
            graph.calls.setdefault(caller, set()).add(callee)
    return graph


def reachable(graph: CallGraph, roots: Sequence[str]) -> set[str]:
    """Every function reachable from ``roots``, the roots included."""
    seen: set[str] = set()
    todo = list(roots)
    while todo:
        name = todo.pop()
        if name not in seen:
            seen.add(name)
            todo.extend(graph.calls.get(name, ()))
    return seen


def deepest_chain(graph: CallGraph, root: str) -> tuple[int, list[str]]:
    """The largest sum of frames along a call chain from ``root``, and the chain.

    Functions without a frame in the graph (the C library's) count 0. A recursion or an
    unbounded frame has no such bound: :class:`ValueError`.
    """
    best: dict[str, tuple[int, list[str]]] = {}
    on_path: set[str] = set()

    def visit(name: str) -> tuple[int, list[str]]:
        if name in graph.unbounded:
            raise ValueError(f"{name}: a frame of unbounded size")
        if name in on_path:
            raise ValueError(f"{name}: recursive, the stack has no static bound")
        if name not in best:
            on_path.add(name)
            below = max((visit(c) for c in graph.calls.get(name, ())), default=(0, []))
            on_path.discard(name)
            best[name] = (graph.frames.get(name, 0) + below[0], [name, *below[1]])
        return best[name]

    return visit(root)


class HostCode(NamedTuple):
    """One planner on the host: its objects' sizes and its decision's deepest stack."""

    objects: tuple[str, ...]
    sizes: Sizes
    stack: int
    chain: tuple[str, ...]
    library: tuple[str, ...]


def host_code(planner: str, graph: CallGraph, sizes: dict[str, Sizes]) -> HostCode:
    """Sizes and stack of ``planner`` from the call graph and the objects' sizes."""
    functions = reachable(graph, [f"{planner}_init", f"{planner}_step"])
    objects = tuple(sorted({graph.files[f] for f in functions if f in graph.files}))
    total = total_size([sizes[o] for o in objects])
    stack, chain = deepest_chain(graph, f"{planner}_step")
    step_functions = reachable(graph, [f"{planner}_step"])
    library = tuple(sorted(f for f in step_functions if f not in graph.frames))
    return HostCode(objects, total, stack, tuple(chain), library)


def build_host(build: Path) -> tuple[Path, dict[str, HostCode], str]:
    """Build the port (``make``), and again with the call graph into ``build``; return the
    benchmark program, each planner's code, and the compiler's version line."""
    make()
    make(f"{build}/libifgm.a", BUILD=str(build), VARIANT=STACK_FLAGS)
    objects = sorted((build / "obj").glob("*.o"))
    graph = read_call_graph(sorted((build / "obj").glob("*.ci")))
    sizes = object_sizes(objects)
    code = {name: host_code(name, graph, sizes) for name in PLANNERS}
    cc = os.environ.get("CC", "cc")
    version = subprocess.run([cc, "--version"], capture_output=True, text=True).stdout
    return PORT / "build" / "ifgm_bench", code, version.splitlines()[0]


class M4Code(NamedTuple):
    """One planner on the Cortex-M4F: its linked image's and its objects' sizes, the cycles
    of each counted decision, the deepest stack written, and how many of all its decisions
    took the reference's branch."""

    image: Sizes
    objects: Sizes
    cycles: tuple[cortex_m4.Cost, ...]
    stack: int
    same_branch: int
    decisions: int


def build_m4(build: Path, cc: str) -> Path:
    """The port's library for the Cortex-M4F (module docstring of ``cortex_m4``), in
    ``build``."""
    shim = PORT / "cortex-m4" / "newlib_tgmath.h"
    variant = f"-DIFGM_FLOAT {' '.join(cortex_m4.ARM_FLAGS)} -include {shim} {STACK_FLAGS}"
    make(
        f"{build}/libifgm.a",
        BUILD=str(build),
        CC=cc,
        AR=cc.replace("gcc", "ar"),
        CFLAGS="-O2 -ffunction-sections -fdata-sections",
        VARIANT=variant,
    )
    return build / "libifgm.a"


def m4_code(
    planner: str,
    episodes: Path,
    references: Sequence[str | None],
    objects: Sequence[str],
    build: Path,
    every: int,
) -> M4Code:
    """Link, size and emulate ``planner`` on the episodes (every ``every``-th decision
    counted); ``references`` are the reference's branches, ``objects`` the planner's."""
    cc = "arm-none-eabi-gcc"
    image_path = cortex_m4.link_planner(planner, build / "libifgm.a", build / f"{planner}.elf", cc)
    image = object_sizes([image_path], cc.replace("gcc", "size"))[planner]
    sizes = object_sizes([build / "obj" / f"{o}.o" for o in objects], cc.replace("gcc", "size"))
    dump = build / f"{planner}.dump"
    subprocess.run(
        [str(PORT / "build" / "float" / "ifgm_bench"), "--dump", str(dump), str(episodes)],
        check=True,
    )
    emulator = cortex_m4.Emulator(cortex_m4.read_elf(image_path), planner)
    decisions: list[cortex_m4.Decision] = []
    for episode in cortex_m4.read_dump(dump):
        status = emulator.start(episode)
        if status != 0:
            raise RuntimeError(f"{planner}_init on the Cortex-M4: status {status}")
        for observation in episode.observations:
            decisions.append(emulator.decide(observation, len(decisions) % every == 0))
    return M4Code(
        image,
        total_size(list(sizes.values())),
        tuple(d.cycles for d in decisions if d.cycles is not None),
        max(d.stack for d in decisions if d.stack is not None),
        sum(d.branch == ref for d, ref in zip(decisions, references, strict=True)),
        len(decisions),
    )


def _print_times(reports: dict[str, dict[str, Any]]) -> None:
    print("\none decision on this machine, ns (double precision)")
    print(
        f"{'planner':8s} {'decisions':>9s} {'median':>15s} {'90th percentile':>17s} "
        f"{'heap calls':>10s}  reference's branch"
    )
    for name, r in reports.items():
        ref = r["reference"]
        print(
            f"{name:8s} {r['decisions']:9d} {r['median_ns']:8.0f} ({r['median_best_ns']:4.0f}) "
            f"{r['p90_ns']:10.0f} ({r['p90_best_ns']:4.0f}) {r['allocations']!s:>10s}  "
            f"{ref['branch_equal']} of {ref['compared']}, heading within "
            f"{ref['max_heading_diff']:.3g} rad"
        )
    for name, r in reports.items():
        parts = [f"{b} {v['median_ns']:.0f} ({v['decisions']})" for b, v in r["branches"].items()]
        print(f"  {name} by branch, median ns (decisions): {', '.join(parts)}")
    cost = {r["timer_cost_ns"] for r in reports.values()}
    print(f"  timer cost subtracted from each reading: {', '.join(map(str, sorted(cost)))} ns")


def _print_code(code: dict[str, HostCode], compiler: str) -> None:
    print(f"\ncode and stack on this machine ({compiler}, -O2; size of the planner's objects)")
    print(f"{'planner':8s} {'text':>6s} {'data':>5s} {'bss':>4s} {'stack':>6s}  objects")
    for name, c in code.items():
        print(
            f"{name:8s} {c.sizes.text:6d} {c.sizes.data:5d} {c.sizes.bss:4d} {c.stack:6d}  "
            f"{' '.join(o + '.o' for o in c.objects)}"
        )
    for name, c in code.items():
        chain = " > ".join(f.rsplit(":", 1)[-1] for f in c.chain)
        print(f"  {name} deepest chain: {chain}; libm not counted: {', '.join(c.library)}")


def _print_m4(m4: dict[str, M4Code], clock_hz: float, every: int) -> None:
    mhz = clock_hz / 1e6
    print(
        f"\nCortex-M4F estimate (emulated, instructions costed by the M4's timings, zero wait "
        f"states; float;\n  every {every}-th decision counted; cycles nominal [least-most], "
        f"us at {mhz:g} MHz)"
    )
    print(
        f"{'planner':8s} {'flash':>6s} {'objects':>7s} {'median cycles':>22s} {'p90':>7s} "
        f"{'max':>8s} {'median us':>10s} {'max us':>7s} {'stack':>5s}  reference's branch"
    )
    for name, c in m4.items():
        nominal = [x.nominal for x in c.cycles]
        median = statistics.median_low(nominal)
        at = nominal.index(median)
        p90 = sorted(nominal)[int(0.9 * (len(nominal) - 1))]
        worst = max(c.cycles, key=lambda x: x.nominal)
        print(
            f"{name:8s} {c.image.text + c.image.data:6d} {c.objects.text:7d} "
            f"{median:7d} [{c.cycles[at].low}-{c.cycles[at].high}] {p90:7d} {worst.high:8d} "
            f"{median / mhz:10.1f} {worst.high / mhz:7.0f} {c.stack:5d}  "
            f"{c.same_branch} of {c.decisions}"
        )
    print(
        "  flash: the linked image's .text + .data (libm's functions included); objects: "
        "the planner's own .text;\n  max: the most cycles of the slowest counted decision; "
        "stack: the deepest any counted decision wrote"
    )


def _arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--planners", nargs="+", default=PLANNERS, help="planners (%(default)s)")
    parser.add_argument(
        "--worlds", nargs="+", default=bench_decision.WORLDS, help="built-in worlds (%(default)s)"
    )
    parser.add_argument("--max-time", type=float, default=180.0, help="episode limit, s (180)")
    parser.add_argument("--repeats", type=int, default=5, help="timed passes (5)")
    parser.add_argument(
        "--m4-every", type=int, default=5, help="emulate the cycles of every N-th decision (5)"
    )
    parser.add_argument(
        "--m4-clock", type=float, default=80e6, help="the Cortex-M4F's clock, Hz (80e6)"
    )
    parser.add_argument("--no-m4", action="store_true", help="skip the Cortex-M4F estimate")
    return parser.parse_args(argv)


def main(argv: Sequence[str] | None = None) -> int:
    """Record the episodes, build the port, time, size and emulate; print the report."""
    args = _arguments(argv)
    print(f"machine: {machine()}")
    with tempfile.TemporaryDirectory(prefix="bench_c-") as tmp:
        work = Path(tmp)
        episodes = {
            name: [bench_decision.record(name, world, args.max_time) for world in args.worlds]
            for name in args.planners
        }
        files = {
            name: write_episodes(work / f"{name}.jsonl", eps) for name, eps in episodes.items()
        }
        print(
            f"episodes: {', '.join(args.worlds)}, up to {args.max_time:g} s each, as "
            f"bench_decision.py records them; {args.repeats} passes"
        )
        binary, code, compiler = build_host(work / "host")
        reports = {name: run_bench(binary, name, files[name], args.repeats) for name in files}
        _print_times(reports)
        _print_code({name: code[name] for name in files}, compiler)
        absent = cortex_m4.missing()
        if args.no_m4 or absent:
            print(
                f"\nCortex-M4F estimate skipped: {'--no-m4' if args.no_m4 else ', '.join(absent)}"
            )
            return 0
        build = work / "m4"
        build_m4(build, "arm-none-eabi-gcc")
        make("float")  # its ifgm_bench --dump writes the emulator's input
        m4 = {
            name: m4_code(
                name,
                files[name],
                [cmd.branch for ep in episodes[name] for _, cmd in ep.steps],
                code[name].objects,
                build,
                args.m4_every,
            )
            for name in files
        }
        _print_m4(m4, args.m4_clock, args.m4_every)
    return 0


if __name__ == "__main__":
    sys.exit(main())
