"""``ifgm-ref simulate``: run one planner (built-in, a factory or a program) in one world."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from ifgm_ref.apps.cli.common import (
    add_engine_options,
    add_robot_options,
    add_timeout_options,
    non_negative_int,
    numbers,
    output_folder,
    positive_float,
    robot_of,
    with_engine,
)
from ifgm_ref.apps.cli.ros import add_ros_options, exactly_one, ros_planner
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.outputs import LEDGER, written
from ifgm_ref.core.params import SENSOR_PRESETS, SimParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Planner
from ifgm_ref.core.recording import Recording, RecordingPlanner
from ifgm_ref.io.barn import DEFAULT_SENSOR, GazeboTask, barn_score, gazebo_task
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import PLANNERS
from ifgm_ref.sim.noise import KINDS, NoiseLevels
from ifgm_ref.sim.simulator import Run, simulate
from ifgm_ref.sim.world import World

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands

#: The file types ``--plot`` and ``--animate`` can write.
PLOT_SUFFIXES = (".png", ".svg", ".pdf", ".jpg", ".jpeg")
ANIMATION_SUFFIXES = (".gif",)


def add_simulate(sub: Subcommands) -> None:
    """Add ``simulate`` to the subcommands."""
    sim = sub.add_parser("simulate", help="run one planner in one world")
    sim.add_argument(
        "world",
        metavar="WORLD",
        help="a world file (JSON), a built-in world name, a Gazebo world (.world, .sdf) or "
        "barn:N (BARN's world N; docs/benchmark.md)",
    )
    sim.add_argument(
        "--planner",
        metavar="NAME",
        help=f"planner to run: {', '.join(sorted(PLANNERS))}, or module:attribute (a factory)",
    )
    sim.add_argument(
        "--cmd",
        metavar="PROGRAM",
        help="run a program speaking the JSON-lines protocol instead (docs/oracle-protocol.md)",
    )
    add_timeout_options(sim)
    add_ros_options(sim)
    sim.add_argument(
        "--param",
        action="append",
        metavar="NAME=VALUE",
        help="set a planner parameter (repeatable; see `ifgm-ref planners`)",
    )
    sim.add_argument("--json", action="store_true", help="print the result as one JSON object")
    sim.add_argument(
        "--require-goal",
        action="store_true",
        help="exit with status 1 unless the goal is reached (a collision, a time-out or a "
        "planner's stop fails): for CI scripts",
    )
    _add_output_options(sim)
    add_engine_options(sim)
    add_robot_options(sim)
    _add_gazebo_options(sim)
    sim.set_defaults(func=run_simulate)


def _add_gazebo_options(sim: argparse.ArgumentParser) -> None:
    """Where BARN's worlds are, and the task in a Gazebo world (which holds none)."""
    sim.add_argument(
        "--barn-dir",
        metavar="DIR",
        help="with barn:N: BARN's worlds in DIR (a folder of world_N.world and path_N.npy, or a "
        "clone of BARN's repository; default: the 200 that ship with ifgm-ref)",
    )
    sim.add_argument(
        "--sensor",
        choices=sorted(SENSOR_PRESETS),
        help=f"with a Gazebo world or barn:N: the sensor preset (default {DEFAULT_SENSOR})",
    )
    sim.add_argument(
        "--start",
        type=numbers(3),
        metavar="X,Y,THETA",
        help="with a Gazebo world or barn:N: the start pose, m and rad (default BARN's, "
        "-2,3,pi/2; write --start=-2,3,1.57 when it begins with a minus)",
    )
    sim.add_argument(
        "--goal",
        type=numbers(2),
        metavar="X,Y",
        help="with a Gazebo world or barn:N: the goal, m (default BARN's, --goal=-2,13)",
    )


def _add_output_options(sim: argparse.ArgumentParser) -> None:
    """The trace, plot and animation files, then the simulation parameters."""
    sim.add_argument("--trace", metavar="FILE", help="write the trace (.json for JSON, else CSV)")
    sim.add_argument("--plot", metavar="FILE", help="write a plot of the run (e.g. run.png)")
    sim.add_argument(
        "--colour-by",
        choices=("behaviour", "branch"),
        default="behaviour",
        help="colour the plotted path by behaviour (default) or flowchart branch",
    )
    sim.add_argument("--animate", metavar="FILE.gif", help="write an animation of the run")
    sim.add_argument(
        "--record",
        metavar="FILE",
        help="write the run as a ROS bag, in metres: FILE.mcap (ROS 2, MCAP: Foxglove, "
        "ros2 bag play), FILE.bag (ROS 1) or a new FOLDER without suffix (ROS 2, sqlite3); "
        "docs/bags.md",
    )
    sim.add_argument("--dt", type=positive_float, help=f"time step in s (default {SimParams.dt})")
    sim.add_argument(
        "--max-time", type=positive_float, help=f"time limit in s (default {SimParams.max_time})"
    )
    sim.add_argument(
        "--goal-tolerance",
        type=positive_float,
        help=f"goal radius, in the world's length unit (default {SimParams.goal_tolerance})",
    )
    sim.add_argument(
        "--noise",
        metavar="KIND=LEVEL,...",
        help=f"noise levels ({', '.join(KINDS)}; docs/noise.md), e.g. "
        "range=0.02,dropout=0.05,odometry=0.01: they replace the world file's",
    )
    sim.add_argument(
        "--noise-seed",
        type=non_negative_int,
        help="seed of every noise generator (default: the world file's seeds)",
    )


def run_simulate(args: argparse.Namespace) -> int:
    """Run ``ifgm-ref simulate``; return the exit status."""
    task = _gazebo_task(args)
    world = resolve_world(args.world) if task is None else task.world
    if args.noise is not None or args.noise_seed is not None:
        world = NoiseLevels.parse(args.noise or "").apply(world, args.noise_seed)
    world = world.with_robot(robot_of(args))
    defaults = SimParams() if task is None else task.sim
    sim = dataclasses.replace(
        defaults,
        dt=defaults.dt if args.dt is None else args.dt,
        max_time=defaults.max_time if args.max_time is None else args.max_time,
        goal_tolerance=defaults.goal_tolerance
        if args.goal_tolerance is None
        else args.goal_tolerance,
    )
    sim = with_engine(sim, args)
    exactly_one(args)
    check_outputs(args)  # before the run, not after it
    LEDGER.plan(*(p for p in (args.record, args.trace, args.plot, args.animate) if p))
    LEDGER.doing(f"simulating {args.world}")
    if args.ros_node is not None:
        from ifgm_ref.io.bags.messages import metres_per_unit

        params = planner_params(None, args.param or [])
        with ros_planner(args, metres_per_unit("ft" if task is None else "m")) as nodes:
            run, recording = _run(args, world, nodes, sim, params)
    elif args.cmd is not None:
        from ifgm_ref.io.transport.external import ExternalPlanner

        params = planner_params(None, args.param or [])
        with ExternalPlanner(
            args.cmd, timeout=args.timeout, startup_timeout=args.startup_timeout
        ) as external:
            run, recording = _run(args, world, external, sim, params)
    else:
        from ifgm_ref.io.transport.loading import load_planner

        params = planner_params(args.planner, args.param or [])
        run, recording = _run(args, world, load_planner(args.planner), sim, params)
    unit = "ft" if task is None else "m"  # Gazebo worlds are in metres
    _print_result(args, run, task, unit)  # before the outputs: the GIF takes half a minute
    sys.stdout.flush()
    _write_outputs(args, world, run, unit, recording)
    return 1 if args.require_goal and not run.result.reached else 0


def _gazebo_task(args: argparse.Namespace) -> GazeboTask | None:
    """The Gazebo or BARN task of ``args.world`` (None for a JSON world or a built-in one,
    which take none of the Gazebo options)."""
    task = gazebo_task(
        args.world,
        folder=args.barn_dir,
        sensor=args.sensor or DEFAULT_SENSOR,
        start=None if args.start is None else Pose(*args.start),
        goal=None if args.goal is None else Point(*args.goal),
    )
    given = [o for o in ("barn_dir", "sensor", "start", "goal") if getattr(args, o) is not None]
    if task is None and given:
        flag = "--" + given[0].replace("_", "-")
        raise ParameterError(f"{flag} applies to Gazebo worlds (.world, .sdf) and barn:N only")
    if args.barn_dir is not None and not args.world.startswith("barn:"):
        raise ParameterError("--barn-dir applies to barn:N only")
    return task


def _run(
    args: argparse.Namespace,
    world: World,
    planner: Planner,
    sim: SimParams,
    params: dict[str, float],
) -> tuple[Run, Recording | None]:
    """Simulate ``planner`` in ``world``; keep what it was handed and answered when
    ``--record`` asks for a bag."""
    if not args.record:
        return simulate(world, planner, sim, params=params, progress=None), None
    recorder = RecordingPlanner(planner)
    run = simulate(world, recorder, sim, params=params, progress=None)
    return run, recorder.recording()


def _write_outputs(
    args: argparse.Namespace, world: World, run: Run, unit: str, recording: Recording | None
) -> None:
    """Write the bag (from ``recording``), the trace, the plot and the animation that were
    asked for, in that order (the slowest last), each whole or not at all
    (:func:`~ifgm_ref.core.outputs.written`) and said as it lands (lengths in ``unit``; the bag's
    in metres)."""
    result = run.result
    if recording is not None:
        from ifgm_ref.io.bags.write import write_bag

        LEDGER.doing(f"writing {args.record}")
        with written(args.record) as partial:
            write_bag(partial, world, run, recording, unit)
    if args.trace:
        LEDGER.doing(f"writing {args.trace}")
        with written(args.trace) as partial:
            partial.write_text(run.trace_json() if partial.suffix == ".json" else run.trace_csv())
    if args.plot or args.animate:
        from ifgm_ref.sim.plotting import animate_run, plot_run, save_figure

        if args.plot:
            LEDGER.doing(f"writing {args.plot}")
            figure = plot_run(
                world, run.trace, result, colour_by=args.colour_by, unit=unit, engine=args.engine
            )
            with written(args.plot) as partial:
                save_figure(figure, partial)
        if args.animate:
            LEDGER.doing(f"writing {args.animate}")
            with written(args.animate) as partial:
                animate_run(world, run.trace, result, partial, unit=unit, engine=args.engine)


def _print_result(args: argparse.Namespace, run: Run, task: GazeboTask | None, unit: str) -> None:
    """Print the result: one JSON object (``--json``) or a sentence, lengths in ``unit``; for
    a BARN world, with its BARN score (``barn_score``, from its reference path length)."""
    result = run.result
    reference = None if task is None else task.reference_length
    score = None if reference is None else barn_score(result.reached, result.time_s, reference)
    if args.json:
        extra = {} if score is None else {"barn_score": score, "reference_length": reference}
        print(json.dumps({**result.to_json_dict(), **extra}))
        return
    clearance = (
        "n/a" if result.min_clearance == float("inf") else f"{result.min_clearance:.3f} {unit}"
    )
    print(
        f"{result.planner} in {result.world or args.world}: {result.stop_reason} "
        f"(reached={result.reached}, collided={result.collided}) after {result.time_s:.1f} s, "
        f"{result.steps} step{'' if result.steps == 1 else 's'}, "
        f"path {result.path_length:.2f} {unit}, min clearance {clearance}"
    )
    if result.detail:
        print(f"detail: {result.detail}")
    if score is not None:
        print(f"BARN score {score:.3f} (reference path {reference:.2f} m; best 0.5)")


def check_outputs(args: argparse.Namespace) -> None:
    """Refuse an output file type the run could not write, and make the outputs' folders,
    before the run."""
    for option, name, allowed in (
        ("--plot", args.plot, PLOT_SUFFIXES),
        ("--animate", args.animate, ANIMATION_SUFFIXES),
    ):
        if name and Path(name).suffix.lower() not in allowed:
            raise ParameterError(
                f"{option} {name}: cannot write {Path(name).suffix or 'a file without suffix'}; "
                f"use one of {', '.join(allowed)}"
            )
    if args.record:
        from ifgm_ref.io.bags.write import bag_format

        bag_format(args.record, "--record")
    for option, name in (
        ("--trace", args.trace),
        ("--plot", args.plot),
        ("--animate", args.animate),
        ("--record", args.record),
    ):
        if name:
            output_folder(option, name)


def planner_params(planner: str | None, pairs: list[str]) -> dict[str, float]:
    """Parse ``NAME=VALUE`` planner parameters, checking names against a built-in planner's
    list (any name goes for other implementations).

    >>> planner_params("ifgm", ["d_th=3.5"])
    {'d_th': 3.5}
    >>> planner_params("ifgm", ["d_th"])
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: --param 'd_th': expected NAME=VALUE
    >>> planner_params("ifgm", ["d_th=-1"])
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: --param d_th=-1: must be a finite number > 0, got -1.0
    """
    allowed = PLANNERS[planner].parameters if planner in PLANNERS else None
    params: dict[str, float] = {}
    for pair in pairs:
        name, sep, text = pair.partition("=")
        if not sep:
            raise ParameterError(f"--param {pair!r}: expected NAME=VALUE")
        if allowed is not None and name not in allowed:
            known = ", ".join(allowed) or "none"
            raise ParameterError(
                f"--param {name!r}: {planner} has no such parameter; it has: {known}"
            )
        try:
            params[name] = float(text)
        except ValueError:
            raise ParameterError(f"--param {name}: must be a number, got {text!r}") from None
        tunings = PLANNERS[planner].tunings if planner in PLANNERS else ()
        for tuning in (t for t in tunings if name in t.names()):
            if why := tuning.violation(name, params[name]):
                raise ParameterError(f"--param {pair}: {why}")
    return params
