"""The ``scale_invariant`` check and the scaling it rests on (:mod:`ifgm_ref.oracle.metamorphic`).

The scaled problem scales every length and nothing else; the reference planners pass the
check; a planner with one absolute margin is caught on a world where the reference is exact
to the bit, and with a rounded scale on the open-loop replay (``tests/test_invariance.py``
tests the replay itself).
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.formulas import Unit
from ifgm_ref.core.params import RobotParams, SensorParams, SimParams
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation, promises_of
from ifgm_ref.oracle.metamorphic import (
    is_power_of_two,
    scale_params,
    scale_sim,
    scale_world,
)
from ifgm_ref.oracle.mutants import AbsoluteStandoff
from ifgm_ref.oracle.profiles import Profile
from ifgm_ref.oracle.runner import Status, check_planner, run_check
from ifgm_ref.planners import PLANNERS
from ifgm_ref.sim.world import Circle, Polygon, World
from ifgm_ref.sim.worldgen.classes import random_world

#: A few examples per planner keep CI cheap (the CLI's quick profile runs 50).
FEW = Profile("few", 20)
ONE = Profile("one", 1, shrink=False)


def _one(impl: Implementation, world: World, k: float, **kwargs: object):
    """``scale_invariant`` on exactly one example, through the real runner."""
    check = CHECKS["scale_invariant"]
    if kwargs:
        test = check.test
        check = replace(check, test=lambda i, ex, rec: test(i, ex, rec, **kwargs))
    check = replace(check, strategy=lambda i: st.just((world, k)))
    return run_check(check, impl, ONE, artifacts=None)


# -- scaling a problem -----------------------------------------------------------------------


def test_scale_world_scales_every_length_and_keeps_every_angle() -> None:
    world = World(
        start=(1.0, -2.0, 0.7),
        goal=(30.0, 4.0),
        obstacles=(Circle((10.0, 0.0), 2.0), Polygon([(15, 3), (18, 3), (18, 9)])),
        bounds=(-10.0, -20.0, 40.0, 20.0),
        robot=RobotParams(radius=0.5, speed=1.5, max_turn_rate=1.2),
        sensor=SensorParams(fov=2.0, rays=31, range_max=12.0, range_min=0.2, noise_std=0.05),
        name="mixed",
    )
    k = 0.3048
    s = scale_world(world, k)
    assert s.start == (k * 1.0, k * -2.0, 0.7)
    assert s.goal == (k * 30.0, k * 4.0)
    assert s.obstacles[0] == Circle((k * 10.0, 0.0), k * 2.0)
    assert s.obstacles[1] == Polygon([(k * 15, k * 3), (k * 18, k * 3), (k * 18, k * 9)])
    assert tuple(s.bounds) == (k * -10.0, k * -20.0, k * 40.0, k * 20.0)
    assert s.robot == RobotParams(radius=k * 0.5, speed=k * 1.5, max_turn_rate=1.2)
    assert s.sensor == SensorParams(
        fov=2.0, rays=31, range_max=k * 12.0, range_min=k * 0.2, noise_std=k * 0.05
    )
    assert s.name == "mixed"
    assert scale_world(world, 1.0) == world


def test_scale_sim_scales_the_goal_tolerance_only() -> None:
    assert scale_sim(SimParams(dt=0.05, max_time=90.0, goal_tolerance=0.5), 4.0) == SimParams(
        dt=0.05, max_time=90.0, goal_tolerance=2.0
    )


def test_scale_params_follows_the_declared_units() -> None:
    infos = PLANNERS["apf"].infos
    assert scale_params({"d0": 5.0, "eta": 50.0, "k_att": 1.0}, infos, 2.0) == {
        "d0": 10.0,
        "eta": 800.0,
        "k_att": 1.0,
    }
    with pytest.raises(ParameterError, match=r"cannot scale parameter\(s\) d_th: no declared unit"):
        scale_params({"d_th": 3.0}, infos, 2.0)
    with pytest.raises(ParameterError, match="finite number > 0"):
        scale_world(World(start=(0, 0, 0), goal=(5, 0)), -1.0)


def test_powers_of_two() -> None:
    assert [is_power_of_two(k) for k in (0.25, 0.5, 1.0, 2.0, 8.0)] == [True] * 5
    assert [is_power_of_two(k) for k in (0.3048, 0.22, 3.0, 3.7, 0.0, -2.0)] == [False] * 6


# -- the check -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "planner",
    [
        "iba",
        "bug1",
        "bug2",
        "distbug",
        "fgm",
        "apf",
        "straight",
        "ifgm",
    ],
)
def test_reference_planners_are_scale_invariant(planner: str) -> None:
    result = run_check(CHECKS["scale_invariant"], Implementation.from_spec(planner), FEW)
    assert result.status is Status.PASSED, result.line()
    assert result.examples == 2 * FEW.max_examples


def test_an_absolute_margin_is_caught_where_the_reference_is_exact() -> None:
    world = random_world("open", 1)  # IFGM follows the edge here (Case-2), never Case-1
    reference = _one(Implementation.from_spec("ifgm"), world, 2.0)
    assert reference.status is Status.PASSED, reference.line()
    for k in (2.0, 0.3048):
        broken = _one(Implementation(AbsoluteStandoff, "absolute-standoff"), world, k)
        assert broken.status is Status.FAILED, broken.line()
    assert broken.message.startswith("scaled by k=0.3048, the original run's step")
    assert "replayed open loop) was answered with heading" in broken.message
    exact = _one(Implementation(AbsoluteStandoff, "absolute-standoff"), world, 2.0)
    assert "(a power of two: exact), the run differs from the original times k at step" in (
        exact.message
    )
    assert "branch='move_to_goal' (should be 'case2_" in exact.message


def test_explicit_length_parameters_are_scaled_with_the_world() -> None:
    """Explicit parameters scale by their units; left unscaled, they break the relation."""
    world = random_world("open", 1)
    impl = Implementation.from_spec("iba")
    infos = PLANNERS["iba"].infos
    scaled = _one(impl, world, 4.0, params={"standoff_margin": 1.5}, infos=infos)
    assert scaled.status is Status.PASSED, scaled.line()
    unitless = [replace(i, unit=Unit.NUMBER) for i in infos]
    unscaled = _one(impl, world, 4.0, params={"standoff_margin": 1.5}, infos=unitless)
    assert unscaled.status is Status.FAILED, unscaled.line()


def test_a_crashing_planner_gets_a_verdict() -> None:
    class Crashes:
        name = "crashes"

        def reset(self, start, goal, params) -> None:
            if params.robot.radius != 1.0:
                raise RuntimeError("only feet")

        def step(self, observation):
            from ifgm_ref.core.protocol import Command

            return Command(math.atan2(observation.goal.y - observation.pose.y, 1.0), 1.0)

    result = _one(
        Implementation(Crashes, "crashes", promises_of("straight")),
        World(start=(0, 0, 0), goal=(10, 0)),
        2.0,
    )
    assert result.status is Status.FAILED
    assert "the planner raised RuntimeError: only feet" in result.message


def test_the_check_applies_to_what_promises_it() -> None:
    impl = Implementation.from_spec(
        "iba", promises=replace(promises_of("iba"), scale_invariant=False)
    )
    report = check_planner(impl, checks=["scale_invariant"], artifacts=None)
    assert report["scale_invariant"].status is Status.NOT_APPLICABLE
