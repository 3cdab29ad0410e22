"""``ifgm-ref oracle``: check a planner, Python or a program, against the oracle's properties."""

from __future__ import annotations

import argparse
import os
import sys
from dataclasses import replace
from typing import TYPE_CHECKING, TextIO

from ifgm_ref.apps.cli.common import (
    add_engine_options,
    add_robot_options,
    add_timeout_options,
    output_folder,
    robot_of,
    with_engine,
)
from ifgm_ref.apps.cli.ros import add_ros_options, exactly_one
from ifgm_ref.apps.cli.suite import add_suite_options, refuse_drawing_options, run_suite
from ifgm_ref.core.cache import user_cache
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import SimParams
from ifgm_ref.sim.noise import KINDS

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands
    from ifgm_ref.oracle.implementation import Implementation
    from ifgm_ref.oracle.specification import Specification


#: What ``ifgm-ref oracle --help`` says the command does.
DESCRIPTION = (
    "Run the oracle's property checks against a built-in or Python planner "
    "(--planner) or a program speaking the JSON-lines protocol (--cmd), noise-free or under "
    "noise (--profile robust, --noise), on the kinematic robot or one with mass (--engine "
    "mujoco). Prints each check's line on stderr as it finishes, then the report on stdout: "
    "every check's line and a summary (only the summary when stdout goes where stderr goes, "
    "a terminal, a pipe or a file, which has the lines already). Exit status 0 when every "
    "check passed (or failed as expected), 1 "
    "otherwise. Counterexamples go to --artifacts. With --suite VERSION, the frozen cases "
    "of that suite version run instead of drawn examples, one JSON line per case on stdout "
    "(or --results), each verdict's line on stderr; exit status 0 when every case that "
    "applies passed."
)


def add_oracle(sub: Subcommands) -> None:
    """Add ``oracle`` to the subcommands."""
    oracle = sub.add_parser(
        "oracle",
        help="check a planner against the oracle's properties (docs/oracle.md)",
        description=DESCRIPTION,
    )
    oracle.add_argument("--planner", metavar="NAME", help="built-in name or module:attribute")
    oracle.add_argument("--cmd", metavar="PROGRAM", help="a JSON-lines protocol program")
    add_ros_options(oracle)
    oracle.add_argument(
        "--profile",
        default="quick",
        choices=("quick", "standard", "thorough", "robust", "brief", "default"),
        help="examples per check: quick 50 (the default), standard 200, thorough 1000, brief "
        "10; robust: 50 under the noise levels the planner promises ('default' is the old name of "
        "standard)",
    )
    oracle.add_argument(
        "--noise",
        metavar="KIND=LEVEL,...",
        help=f"check under these noise levels, in any profile ({', '.join(KINDS)}; e.g. "
        "range=0.02,dropout=0.05,odometry=0.01): collisions fail at once, convergence is "
        "counted (docs/oracle.md, 'Robustness')",
    )
    _add_level_options(oracle)
    add_engine_options(oracle)
    add_robot_options(oracle)
    oracle.add_argument(
        "--equations",
        metavar="MODULE",
        help="check the eqs. (1)-(4) of this module (or module:attribute), which exposes "
        "eq1_gap_midpoint ... as ifgm_ref.paper.equations does (default: "
        "ifgm_ref.paper.equations for a built-in --planner, none for any other; a --cmd "
        "program's own equations are checked with the vectors of `ifgm-ref vectors` instead)",
    )
    oracle.add_argument(
        "--promises",
        metavar="PLANNER",
        help="check what this built-in planner promises (default: what the planner declares: "
        "a built-in's own, a factory's promises attribute; a --cmd program: ifgm's; any other "
        "must be told)",
    )
    oracle.add_argument(
        "--spec",
        metavar="FILE.toml",
        help="the implementation's declared specification: what it promises, its level and "
        "readings, goal tolerance, dt, sensor and robot, in its own length unit (docs/oracle.md, "
        "'Declaring your implementation's specification'); not with --promises, --level, "
        "--reading, --robot or --speed",
    )
    _add_run_options(oracle)
    add_suite_options(oracle)
    oracle.set_defaults(func=run_oracle)


def _add_level_options(oracle: argparse.ArgumentParser) -> None:
    """The level of conformance, and the readings the implementation declares for it."""
    oracle.add_argument(
        "--level",
        choices=("paper", "reference"),
        help="paper (the default): the paper's properties, which any valid reading passes; "
        "reference: those and agreement with the reference IFGM step by step "
        "(agrees_with_reference; docs/oracle.md, 'Two levels of conformance')",
    )
    oracle.add_argument(
        "--reading",
        action="append",
        metavar="NAME=VALUE",
        help="the implementation's reading of one of the paper's open choices, where it is not "
        "ours (repeatable; dead_end_side, gap_points, gap_choice, leaving_rule: docs/oracle.md, "
        "'Readings as options'): agrees_with_reference compares it with the reference running "
        "the same reading",
    )


def _add_run_options(oracle: argparse.ArgumentParser) -> None:
    """Which checks run, how, and where their counterexamples go."""
    oracle.add_argument(
        "--check", action="append", metavar="NAME", help="run only this check (repeatable)"
    )
    oracle.add_argument(
        "--expect-failure",
        action="append",
        metavar="CHECK=REASON",
        help="a check known to fail, reported as an expected failure (repeatable)",
    )
    oracle.add_argument(
        "--artifacts",
        default="oracle-failures",
        metavar="DIR",
        help="where counterexamples are written (default oracle-failures)",
    )
    add_timeout_options(oracle)
    oracle.add_argument(
        "--stop-on-failure", action="store_true", help="stop at the first failing check"
    )
    oracle.add_argument(
        "--no-shrink",
        action="store_true",
        help="report a failing example as found, without shrinking it to the simplest world "
        "that still fails (faster where only the verdict matters: benchmarks/bench_mutation.py)",
    )
    oracle.add_argument(
        "--jobs",
        type=int,
        default=os.cpu_count() or 1,
        metavar="N",
        help="run the simulation checks in N processes (default: the number of CPUs; a "
        "--cmd program is started anew for each check a process runs, once in all with "
        "--jobs 1; a --suite run takes its cases in order, in one process)",
    )


def run_oracle(args: argparse.Namespace) -> int:
    """Run the checks; print the report; return 0 when every check passed (or as expected)."""
    from ifgm_ref.oracle.profiles import PROFILE_ALIASES, profile_named
    from ifgm_ref.oracle.runner import check_planner

    keep_hypothesis_out_of_the_working_folder()

    exactly_one(args)
    if args.jobs < 1:
        raise ParameterError(f"--jobs {args.jobs}: must be at least 1")
    if args.profile in PROFILE_ALIASES:
        new = PROFILE_ALIASES[args.profile]
        print(f"ifgm-ref: note: profile {args.profile!r} is now called {new!r}", file=sys.stderr)
    expected = {}
    for item in args.expect_failure or []:
        name, _, reason = item.partition("=")
        expected[name] = reason or "expected"
    if args.suite is not None:
        refuse_drawing_options(args)
        if args.results is not None:  # its folder made before the run, as every output's
            output_folder("--results", args.results)
    elif args.results is not None or args.tier != "full":
        raise ParameterError("--tier and --results apply only with --suite")
    spec = declared_by(args)  # before any program starts: a bad file is one line
    impl = _implementation(args)
    if args.suite is not None:
        try:
            return run_suite(args, impl)
        finally:
            impl.close()
    try:
        sim = with_engine(SimParams(), args)  # MuJoCo installed, a body only on it
        robot = tuple(robot_of(args).items())
        profile = replace(
            profile_named(args.profile), engine=sim.engine, body=sim.body, robot=robot
        )
        report = check_planner(
            impl,
            profile=replace(profile, shrink=False) if args.no_shrink else profile,
            checks=args.check,
            expected_failed_checks=expected,
            artifacts=args.artifacts,
            progress=True,
            stop_on_failure=args.stop_on_failure,
            jobs=args.jobs,
            noise=args.noise,
            level=args.level,
            spec=spec,
        )
    finally:
        impl.close()
    # Each check's line went to stderr as it finished; where stdout goes too (a terminal, or
    # `2>&1` into a pipe or a file) has them already and gets the summary only. Stdout that
    # goes elsewhere gets the whole report.
    print(report.summary() if same_destination(sys.stdout, sys.stderr) else report.text())
    return 0 if report.ok else 1


def _implementation(args: argparse.Namespace) -> Implementation:
    """The implementation of ``--planner``, ``--cmd`` or ``--ros-node``, with its equations
    (``--equations``; for a built-in ``--planner``, the reference's by default:
    :func:`~ifgm_ref.oracle.implementation.default_equations`) and readings (``--reading``); a
    program is started and reset once."""
    from ifgm_ref.oracle.equation_checks import load_equations
    from ifgm_ref.oracle.implementation import Implementation, Promises, default_equations
    from ifgm_ref.planners.ifgm.readings import parse_readings

    given = args.equations
    if given is None and args.planner is not None:
        given = default_equations(args.planner)
    equations = None if given is None else load_equations(given)
    if args.ros_node is not None:
        impl = _ros_implementation(args, equations)  # started and reset once, or it raises
    elif args.cmd is not None:
        impl = Implementation.from_command(
            args.cmd,
            timeout=args.timeout,
            startup_timeout=args.startup_timeout,
            promises=args.promises,
            equations=equations,
        )
        impl.answers_reset()  # a program that cannot start is bad input, not 11 errors
    else:
        told = args.promises if args.spec is None else Promises()  # the file's replace them
        impl = Implementation.from_spec(args.planner, promises=told, equations=equations)
    if args.reading:
        impl.declare_readings(parse_readings(args.reading))
    return impl


def _ros_implementation(args: argparse.Namespace, equations: object | None) -> Implementation:
    """The nodes of ``--ros-node`` as the implementation
    (:mod:`ifgm_ref.apps.cli.ros_oracle`)."""
    from ifgm_ref.apps.cli.ros_oracle import ros_implementation

    return ros_implementation(args, equations)


def declared_by(args: argparse.Namespace) -> Specification | None:
    """The specification of ``--spec``, if given (said on stderr: what the run holds the
    implementation to); an option that declares what the file declares is refused."""
    from ifgm_ref.oracle.specification import load_specification, refuse_options

    if args.spec is None:
        return None
    spec = load_specification(args.spec)
    given = {"--promises": args.promises, "--level": args.level, "--reading": args.reading}
    refuse_options(spec.source, {**given, "--robot": args.robot, "--speed": args.speed})
    print(spec.held_to(), file=sys.stderr)
    return spec


def keep_hypothesis_out_of_the_working_folder() -> None:
    """Point Hypothesis (a cache of the constants it found in the code; the oracle keeps no
    example database) at ``hypothesis`` in :func:`~ifgm_ref.core.cache.user_cache` instead of
    ``./.hypothesis``, unless ``$HYPOTHESIS_STORAGE_DIRECTORY`` chooses a folder; through that
    variable, so the worker processes of ``--jobs`` inherit it however they start."""
    if not os.environ.get("HYPOTHESIS_STORAGE_DIRECTORY"):
        os.environ["HYPOTHESIS_STORAGE_DIRECTORY"] = str(user_cache() / "hypothesis")


def same_destination(out: TextIO, err: TextIO) -> bool:
    """Whether ``out`` and ``err`` write to the same place: one stream, or one terminal, pipe or
    file (``2>&1``), so that what one showed, the other would show again.

    >>> import io
    >>> same_destination(io.StringIO(), io.StringIO())
    False
    >>> one = io.StringIO()
    >>> same_destination(one, one)
    True
    """
    if out is err:
        return True
    try:
        return os.path.samestat(os.fstat(out.fileno()), os.fstat(err.fileno()))
    except (AttributeError, OSError, ValueError):  # a stream without a file: not the other one
        return False
