"""``ifgm-ref replay BAG``: a robot's log fed to the reference, step by step, open loop."""

from __future__ import annotations

import argparse
import json
from pathlib import Path
from typing import TYPE_CHECKING

from ifgm_ref.apps.cli.common import numbers, output_folder, positive_float
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.outputs import LEDGER, written
from ifgm_ref.core.validate import POSITIVE, violation

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands
    from ifgm_ref.core.params import RobotParams

#: Exit status when a logged command differs from the reference's, in motion or branch.
EXIT_DIVERGED = 1


def add_replay(sub: Subcommands) -> None:
    """Add ``replay`` to the subcommands."""
    from ifgm_ref.apps.replay import BRANCH_RULE

    replay = sub.add_parser(
        "replay",
        help="feed a robot's log (ROS bag) to the reference and compare its commands",
        description="Read a robot's log (a ROS 1 .bag, a ROS 2 .mcap or rosbag2 folder: "
        "LaserScan, Odometry and Twist), hand the reference planner each scan with the pose "
        "at its time, open loop, and compare its command with the logged one, step by step "
        "(docs/bags.md). A step agrees in motion when the headings the two commands lead to "
        "after a step are within --heading-tolerance and the speeds within --speed-tolerance, "
        f"and in branch by the branch rule: {BRANCH_RULE}. The summary counts the steps that "
        "differ in motion and in branch apart, and each tolerance's. Exit status 0 when every "
        "logged command agrees, 1 when one differs (in motion or in branch), 2 on a bad log "
        "or option.",
    )
    replay.add_argument("bag", metavar="BAG", help="the log: FILE.bag, FILE.mcap or a folder")
    replay.add_argument(
        "--planner", default="ifgm", metavar="NAME", help="the reference planner (default ifgm)"
    )
    replay.add_argument(
        "--param", action="append", metavar="NAME=VALUE", help="a planner parameter (repeat)"
    )
    replay.add_argument(
        "--goal",
        type=numbers(2),
        metavar="X,Y",
        help="the goal, m, in the odometry's frame (default: the log's episode or /goal_pose)",
    )
    _add_setting_options(replay)
    _add_comparison_options(replay)
    replay.set_defaults(func=run_replay)


def _add_setting_options(replay: argparse.ArgumentParser) -> None:
    """The topics, the robot and the time step of a log (defaults: REP's and the log's)."""
    from ifgm_ref.io.bags.read import Topics

    defaults = Topics()
    for field in ("scan", "odom", "cmd_vel"):
        replay.add_argument(
            f"--{field.replace('_', '-')}-topic",
            default=getattr(defaults, field),
            metavar="TOPIC",
            help=f"the {field} topic (default {getattr(defaults, field)})",
        )
    replay.add_argument(
        "--robot",
        type=numbers(3),
        metavar="R,V,W",
        help="the robot's radius, speed and turn rate, in the log's unit (m, or the recorded "
        "run's) and rad/s (default: the log's episode, else BARN's robot 0.22,1,pi)",
    )
    replay.add_argument(
        "--dt", type=positive_float, help="the time step, s (default: the log's, else its scans')"
    )


def _add_comparison_options(replay: argparse.ArgumentParser) -> None:
    """The tolerances of the comparison and the outputs."""
    from ifgm_ref.apps.replay import Tolerance

    replay.add_argument(
        "--heading-tolerance",
        type=positive_float,
        default=Tolerance.heading,
        metavar="RAD",
        help="largest difference between the headings the two commands lead to after one "
        f"step that still agrees (default {Tolerance.heading:g}, the oracle's)",
    )
    replay.add_argument(
        "--speed-tolerance",
        type=positive_float,
        default=Tolerance.speed,
        metavar="REL",
        help="largest difference of speed, as a share of the robot's, that still agrees "
        f"(default {Tolerance.speed:g}, the oracle's)",
    )
    replay.add_argument("--steps", metavar="FILE.csv", help="write every step, side by side")
    replay.add_argument("--plot", metavar="FILE", help="write a figure of the replay (e.g. x.png)")
    replay.add_argument("--json", action="store_true", help="print the verdict as one JSON object")


def run_replay(args: argparse.Namespace) -> int:
    """Run ``ifgm-ref replay``; return the exit status."""
    from ifgm_ref.apps.cli.simulate import PLOT_SUFFIXES, planner_params
    from ifgm_ref.apps.replay import Tolerance, replay_log, setting_of
    from ifgm_ref.core.pose import Point
    from ifgm_ref.io.bags.read import Topics, read_log
    from ifgm_ref.io.transport.loading import load_planner

    if args.plot and Path(args.plot).suffix.lower() not in PLOT_SUFFIXES:
        raise ParameterError(f"--plot {args.plot}: use one of {', '.join(PLOT_SUFFIXES)}")
    for option, name in (("--steps", args.steps), ("--plot", args.plot)):
        if name:
            output_folder(option, name)
    topics = Topics(scan=args.scan_topic, odom=args.odom_topic, cmd_vel=args.cmd_vel_topic)
    log = read_log(args.bag, topics)
    params = planner_params(args.planner, args.param) if args.param else None
    setting = setting_of(
        log,
        goal=None if args.goal is None else Point(*args.goal),
        robot=None if args.robot is None else _robot(args.robot),
        dt=args.dt,
        params=params,
    )
    tolerance = Tolerance(args.heading_tolerance, args.speed_tolerance)
    report = replay_log(
        log, load_planner(args.planner), setting, tolerance=tolerance, progress=None
    )
    LEDGER.plan(*(p for p in (args.steps, args.plot) if p))
    if args.steps:
        with written(args.steps) as partial:
            partial.write_text(report.steps_csv())
    if args.plot:
        from ifgm_ref.apps.replay_plot import plot_replay
        from ifgm_ref.sim.plotting import save_figure

        LEDGER.doing(f"writing {args.plot}")
        with written(args.plot) as partial:
            save_figure(plot_replay(report), partial)
    print(json.dumps(report.to_json_dict()) if args.json else report.text())
    return 0 if report.first_divergence is None else EXIT_DIVERGED


def _robot(values: tuple[float, ...]) -> RobotParams:
    """The robot of ``--robot R,V,W``; a :class:`ParameterError` naming the option and the
    number out of its domain, as the user wrote them.

    >>> _robot((0.22, 1.0, 3.0)).radius
    0.22
    >>> _robot((0.22, 0.0, 3.0))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: --robot 0.22,0,3: V (the speed) must be a finite ...
    """
    from ifgm_ref.core.params import RobotParams

    names = ("R (the radius)", "V (the speed)", "W (the turn rate)")
    for value, name in zip(values, names, strict=True):
        why = violation(value, POSITIVE)
        if why:
            raise ParameterError(f"--robot {','.join(f'{v:g}' for v in values)}: {name} {why}")
    radius, speed, turn_rate = values
    return RobotParams(radius=radius, speed=speed, max_turn_rate=turn_rate)
