"""What every subcommand of ``ifgm-ref`` shares: the parser class, argument types, exit code."""

from __future__ import annotations

import argparse
import math
import os
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, NoReturn

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import ENGINES, ROBOT_OPTIONS, EngineName, SimParams, robot_changes
from ifgm_ref.core.validate import POSITIVE, violation
from ifgm_ref.io.transport.external import STARTUP_TIMEOUT, TIMEOUT
from ifgm_ref.sim.engine import require_physics
from ifgm_ref.sim.physics.bodies import BODIES

#: Exit status of a usage error or of bad input, reported as one line on stderr.
EXIT_USAGE = 2


class Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line, as the README promises, with the
    prefix of every other error, ``ifgm-ref: error:``, and the subcommand's help to see."""

    def error(self, message: str) -> NoReturn:
        program = self.prog.split()[0]
        self.exit(EXIT_USAGE, f"{program}: error: {message} (see {self.prog} --help)\n")


if TYPE_CHECKING:
    #: What ``add_subparsers`` returns: each subcommand module adds its parser to it.
    Subcommands = argparse._SubParsersAction[Parser]


def positive_float(text: str) -> float:
    """Argument type: a finite number > 0.

    >>> positive_float("0.5")
    0.5
    >>> positive_float("inf")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: must be a finite number > 0, got 'inf'
    """
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if why := violation(value, POSITIVE, shown=repr(text)):
        raise argparse.ArgumentTypeError(why)
    return value


def add_timeout_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--timeout`` and ``--startup-timeout``, the waits for a ``--cmd`` program's replies,
    start and exit (:class:`~ifgm_ref.io.transport.external.ExternalPlanner`); a bad value is a
    usage error."""
    parser.add_argument(
        "--timeout",
        type=positive_float,
        default=TIMEOUT,
        metavar="S",
        help=f"per-reply timeout for --cmd, s (default {TIMEOUT:g})",
    )
    parser.add_argument(
        "--startup-timeout",
        type=positive_float,
        metavar="S",
        help="timeout for a --cmd program's first reply (its start-up, imports and first "
        f"reset) and its exit after bye, s (default {STARTUP_TIMEOUT:g}, or --timeout if "
        "longer)",
    )


def non_negative_int(text: str) -> int:
    """Argument type: an integer >= 0 (a seed).

    >>> non_negative_int("7")
    7
    >>> non_negative_int("-1")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: must be an integer >= 0, got '-1'
    """
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer >= 0, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be an integer >= 0, got {text!r}")
    return value


def names(text: str) -> list[str]:
    """Argument type: comma-separated names, at least one.

    >>> names("ifgm, iba,")
    ['ifgm', 'iba']
    """
    found = [name.strip() for name in text.split(",") if name.strip()]
    if not found:
        raise argparse.ArgumentTypeError(f"expected comma-separated names, got {text!r}")
    return found


def output_folder(option: str, name: str, *, is_folder: bool = False) -> None:
    """Make the folder an output file ``name`` (given with ``option``) goes in, or the folder
    ``name`` itself (``is_folder``), as ``figures --out`` does, before any work: a folder that
    cannot be made, or a file ``name`` that is a folder, is a
    :class:`~ifgm_ref.core.errors.ParameterError` naming the option, not an errno after the run.
    """
    if not is_folder and (name.endswith(("/", os.sep)) or Path(name).is_dir()):
        raise ParameterError(f"{option} {name}: is a folder; give a file name in it")
    folder = Path(name) if is_folder else Path(name).parent
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise ParameterError(
            f"{option} {name}: cannot make its folder {str(folder)!r}: {err.strerror or err}"
        ) from None


def numbers(count: int) -> Callable[[str], tuple[float, ...]]:
    """Argument type: ``count`` comma-separated finite numbers (a pose, a point).

    >>> numbers(2)("-2, 13")
    (-2.0, 13.0)
    >>> numbers(3)("1,2")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: expected 3 comma-separated numbers, got '1,2'
    """

    def parse(text: str) -> tuple[float, ...]:
        try:
            values = tuple(float(part) for part in text.split(","))
        except ValueError:
            values = ()
        if len(values) != count or not all(math.isfinite(v) for v in values):
            raise argparse.ArgumentTypeError(
                f"expected {count} comma-separated numbers, got {text!r}"
            )
        return values

    return parse


def add_engine_options(parser: argparse.ArgumentParser) -> None:
    """``--engine`` and ``--body``: what senses and moves the robot (docs/physics.md)."""
    parser.add_argument(
        "--engine",
        choices=ENGINES,
        default=ENGINES[0],
        help="what moves the robot: kinematic (default: the paper's instant robot) or mujoco (a "
        "robot with mass on the MuJoCo physics engine; pip install 'ifgm-ref[physics]')",
    )
    parser.add_argument(
        "--body",
        choices=sorted(BODIES),
        help="with --engine mujoco: the robot's body (default: jackal for BARN's robot, paper "
        "otherwise)",
    )


def with_engine(sim: SimParams, args: argparse.Namespace) -> SimParams:
    """``sim`` with the engine and body of ``--engine`` and ``--body`` (checked now, before any
    run: a body only for the mujoco engine, as :class:`SimParams` checks it; MuJoCo
    installed)."""
    sim = replace(sim, engine=args.engine, body=args.body)
    if sim.engine is EngineName.MUJOCO:
        require_physics()
    return sim


def add_robot_options(parser: argparse.ArgumentParser) -> None:
    """``--robot`` and ``--speed``: the robot's size, speed and dynamics, over the world's."""
    parser.add_argument(
        "--robot",
        metavar="NAME=VALUE,...",
        help=f"set the robot's {', '.join(ROBOT_OPTIONS)} over the world's, in its length "
        "unit, seconds and radians (e.g. braking=3.72,acceleration=4.9: a robot that cannot "
        "stop at once, which the planners then brake for; docs/physics.md)",
    )
    parser.add_argument(
        "--speed",
        type=positive_float,
        help="the robot's top speed, in the world's length unit per second (--robot speed=V)",
    )


def robot_of(args: argparse.Namespace) -> dict[str, float]:
    """The robot's fields ``--robot`` and ``--speed`` set (``--speed`` over ``--robot``)."""
    changes = robot_changes(args.robot or "")
    if args.speed is not None:
        changes["speed"] = args.speed
    return changes
