"""The oracle on the physical robot: the profile's engine reaches every check's simulations
(``ifgm_ref.oracle.profiles.on_engine``, ``ifgm-ref oracle --engine``, ``--ifgm-engine``),
kinematic by default, and how the checks read on the ``mujoco`` engine
(``docs/oracle.md``, "On the physical robot")."""

from __future__ import annotations

from typing import ClassVar

import pytest

from ifgm_ref.apps.cli import main
from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.oracle.check_types import Recorder
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.mutants import MUTANTS
from ifgm_ref.oracle.profiles import Profile, engine_tag, on_engine
from ifgm_ref.oracle.runner import Status, check_planner, run_check
from ifgm_ref.sim.convergence import time_bound

pytest.importorskip("mujoco")

#: One example, as drawn (the simplest world first), not shrunk.
ONE = Profile("one", 1, shrink=False)
#: Steps the probe drives before it gives up (a short episode on either engine).
PROBE_STEPS = 12


class Probe:
    """Drives at full speed, turning, for :data:`PROBE_STEPS` steps, then stops; keeps every
    pose it was told, so a test sees what the check's simulation handed it."""

    name = "probe"
    told: ClassVar[list[Pose]] = []

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.steps = 0

    def step(self, observation: Observation) -> Command:
        Probe.told.append(observation.pose)
        self.steps += 1
        stop = "goal_unreachable" if self.steps >= PROBE_STEPS else None
        return Command(observation.pose.theta + 0.3, 10.0, stop=stop)


def told_in_check(engine: str) -> list[Pose]:
    """The poses ``deterministic``'s first example told the probe in its episode on
    ``engine`` (the check then replays them into a second probe: the same again)."""
    Probe.told.clear()
    impl = Implementation(Probe, "probe", promises_of("ifgm"))
    result = run_check(CHECKS["deterministic"], impl, on_engine(ONE, engine), artifacts=None)
    assert result.status is Status.PASSED, result.line()
    assert Probe.told[PROBE_STEPS:] == Probe.told[:PROBE_STEPS]
    return Probe.told[:PROBE_STEPS]


def test_the_engine_reaches_the_checks_simulations() -> None:
    """The same check, the same drawn world and the same commands: on mujoco the robot
    accelerates and its wheel odometry tells other poses than the kinematic robot's."""
    kinematic, physical = told_in_check("kinematic"), told_in_check("mujoco")
    assert len(kinematic) == len(physical) == PROBE_STEPS
    assert kinematic[0] == physical[0]  # the start, before any motion
    moved_kinematic = abs(kinematic[1].x - kinematic[0].x) + abs(kinematic[1].y - kinematic[0].y)
    moved_physical = abs(physical[1].x - physical[0].x) + abs(physical[1].y - physical[0].y)
    assert moved_physical < moved_kinematic  # it cannot reach full speed at once


def test_kinematic_stays_the_default() -> None:
    """Every check's episode runs as before unless a profile names another engine."""
    world = resolve_world("u_trap")
    assert Recorder().sim_for(world) == SimParams(max_time=time_bound(world))
    assert not Recorder().physical and Profile("p", 1).sim() == SimParams()
    assert engine_tag(on_engine("quick", None)) == "kinematic"


def test_bad_engines_are_refused() -> None:
    with pytest.raises(ParameterError, match="`engine` must be one of"):
        check_planner("ifgm", profile=Profile("p", 1, engine="bullet"))  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match="`body` applies to the mujoco engine only"):
        Profile("p", 1, body="jackal")
    argv = ["oracle", "--planner", "ifgm", "--body", "jackal", "--check", "deterministic"]
    assert main(argv) == 2  # a body needs --engine mujoco: bad input, before any run


def test_scale_invariance_says_what_it_leaves_out_on_mujoco() -> None:
    """A power of two (the first scale drawn) is compared bit for bit, open loop; the check's
    line says the scaled run itself is not compared, and why."""
    result = run_check(
        CHECKS["scale_invariant"], Implementation.from_spec("ifgm"), on_engine(ONE, "mujoco"),
        artifacts=None,
    )  # fmt: skip
    assert result.status is Status.PASSED, result.line()
    assert "1 power-of-two scale(s) replayed open loop" in result.message
    assert "not scale-free" in result.message


def test_a_broken_variant_is_rejected_on_mujoco(tmp_path) -> None:
    """A fixed stand-off of 1.0 (not a length of the robot's) fails scale invariance on the
    physical robot too, and the counterexample replays on the same engine."""
    hunt = on_engine(Profile("hunt", 50, shrink=False), "mujoco")
    report = check_planner(
        MUTANTS["absolute_standoff"], profile=hunt, checks=["scale_invariant"], artifacts=tmp_path
    )
    result = report["scale_invariant"]
    assert result.status is Status.FAILED, report.text()
    assert "a power of two: exact" in result.message
    assert "engine mujoco" in report.summary()
    assert result.artifacts is not None
    assert "--engine mujoco" in (result.artifacts / "report.md").read_text()
