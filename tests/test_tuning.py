"""The scale-free parameter model (``ifgm_ref.planners.tuning``): formulas, units, names."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.formulas import Scale, Unit, formula_expr
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.planners import PLANNERS, make_planner, parameters_markdown
from ifgm_ref.planners.ifgm import IFGMParams
from ifgm_ref.planners.tuning import derived, episode_values

#: The defaults every planner had as absolute numbers for the paper's 1 ft robot before the
#: model: the formulas give them back, d_th too (``2 r + 1 ft`` then, ``3 r`` now: 3 ft).
#: One moved on purpose: ``standoff_margin``, 1 ft then, ``2 r / 3`` now (errata row 29). One is
#: new: ``turn_done``, 1e-6 rad then (a constant), ``w dt / 2`` now (pi/40 for the paper's robot).
PAPER_VALUES = {
    "standoff_margin": 2.0 / 3.0, "corridor_margin": 0.25, "hit_margin": 0.5, "memory_horizon": 8.0,
    "return_radius": 1.0, "min_loop": 12.0, "step_length": 2.0, "m_line_tolerance": 0.1322147651,
    "alpha": 8.0, "beta": 1.0, "inflation_margin": 0.5, "d_th": 3.0, "d_obs": 1.6610738255,
    "d_look": 8.0, "w_g": 9.0, "w_d": 1.0, "jump": 2.0, "preempt_margin": 0.5, "view_range": 15.0,
    "k_att": 1.0, "eta": 50.0, "d0": 5.0, "stop_margin": 0.5, "turn_done": math.pi / 40,
    # dwa came with the model: its formulas give BARN's values for BARN's robot
    # (tests/test_dwa.py); these are what they give the paper's 1 ft robot.
    "resolution": 1 / 4.4, "obstacle_range": 50 / 4.4, "raytrace_range": 60 / 4.4,
    "inflation_radius": 6 / 4.4, "cost_decay": 2 / 4.4, "local_size": 200 / 4.4,
    "max_vel_x": 197 / 298, "min_vel_x": 197 / 1490, "max_vel_theta": math.pi / 4,
    "min_in_place_vel_theta": math.pi / 20, "acc_lim_x": 1970 / 298, "acc_lim_theta": 5.0,
    "sim_time": 4.0, "sim_granularity": 0.4 / 4.4, "angular_sim_granularity": 0.02,
    "vx_samples": 6.0, "vtheta_samples": 20.0, "pdist_scale": 0.75, "gdist_scale": 1.0,
    "occdist_scale": 0.1, "heading_lookahead": 6.5 / 4.4, "planner_period": 0.1,
}  # fmt: skip


@pytest.mark.parametrize("name", [n for n in PLANNERS if PLANNERS[n].tunings])
def test_formulas_give_the_paper_robot_its_former_values(name: str) -> None:
    values = episode_values(PLANNERS[name].tunings, EpisodeParams())
    assert values == pytest.approx({k: PAPER_VALUES[k] for k in values}, rel=1e-9)


def _scaled_episode(k: float) -> EpisodeParams:
    base = EpisodeParams()
    robot = dataclasses.replace(
        base.robot, radius=k * base.robot.radius, speed=k * base.robot.speed
    )
    sensor = dataclasses.replace(base.sensor, range_max=k * base.sensor.range_max)
    return EpisodeParams(robot, sensor, base.dt, {}, k * base.goal_tolerance)


@given(k=st.sampled_from([0.25, 0.3048, 0.22, 2.0, 3.7, 1000.0]))
def test_every_default_scales_with_its_unit(k: float) -> None:
    """Scale every length of robot and sensor by k: each default scales by k ** power."""
    for info in PLANNERS.values():
        before = episode_values(info.tunings, EpisodeParams())
        after = episode_values(info.tunings, _scaled_episode(k))
        for param in info.infos:
            expected = before[param.name] * k**param.unit.length_power
            assert after[param.name] == pytest.approx(expected, rel=1e-12), param.name


def test_a_value_given_by_name_replaces_the_formula_and_keeps_the_others() -> None:
    episode = EpisodeParams(params={"d_th": 4.5})
    p = IFGMParams.for_episode(episode)
    assert (p.d_th, p.d_look) == (4.5, 8.0)


@pytest.mark.parametrize("name", sorted(PLANNERS))
def test_the_library_rejects_an_unknown_parameter_name(name: str) -> None:
    planner = make_planner(name)
    with pytest.raises(ParameterError, match=rf"^{name} has no parameter `no_such`; it has: "):
        planner.reset(Pose(0, 0, 0), Point(5, 0), EpisodeParams(params={"no_such": 1.0}))


def test_an_explicit_none_is_not_a_value() -> None:
    with pytest.raises(ParameterError, match=r"^`d_look` must be a finite number > 0, got None"):
        IFGMParams.for_episode(EpisodeParams(params={"d_look": None}))


def test_formulas_may_only_use_the_declared_symbols() -> None:
    assert {s.name for s in formula_expr("Max(r, v/w) + R*res/fov + dt").free_symbols} == {
        "r",
        "v",
        "w",
        "R",
        "res",
        "fov",
        "dt",
    }
    with pytest.raises(ParameterError, match=r"formula 'r \+ ft' uses ft"):
        derived("r + ft", Unit.LENGTH)


def test_scale_of_an_episode_reads_robot_time_step_and_sensor() -> None:
    robot = RobotParams(radius=0.22, speed=1.0, max_turn_rate=math.pi)
    sensor = SensorParams(fov=1.5 * math.pi, rays=720, range_max=30.0)
    scale = Scale.of(EpisodeParams(robot, sensor, 0.05))
    assert scale == Scale(0.22, 1.0, math.pi, 0.05, 30.0, 1.5 * math.pi / 719, 1.5 * math.pi)


def test_the_committed_parameter_table_is_current() -> None:
    committed = (Path(__file__).resolve().parents[1] / "docs" / "parameters.md").read_text()
    assert committed == parameters_markdown(), (
        "run: ifgm-ref planners --markdown > docs/parameters.md"
    )
