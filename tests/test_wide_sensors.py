"""Sensors beyond the paper's 135-degree IR sensor keep the paper's rules (errata row 30)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.laserscan import Beam, LaserScan
from ifgm_ref.core.params import SensorParams, jackal_lidar, paper_ir
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import EpisodeParams, Observation
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.planners import make_planner
from ifgm_ref.sim.simulator import simulate


def _scan(sensor: SensorParams) -> LaserScan:
    half = sensor.fov / 2
    ranges = np.linspace(1.0, 2.0, sensor.rays)
    return LaserScan(-half, half, sensor.angle_increment, 0.0, sensor.range_max, ranges)


@pytest.mark.paper("sensor.fov")
def test_beams_keep_the_paper_angles_on_a_wide_scan() -> None:
    scan = _scan(jackal_lidar())  # 270 degrees, 720 rays
    degrees = np.degrees(scan.angles)
    left, right, front = (scan.beam_mask(b) for b in (Beam.LEFT, Beam.RIGHT, Beam.FRONT))
    assert degrees[left].min() > 22.5 and degrees[left].max() <= 67.5
    assert degrees[right].max() < -22.5 and degrees[right].min() >= -67.5
    assert np.abs(degrees[front]).max() <= 22.5
    outside = ~(left | right | front)
    assert np.all(np.abs(degrees[outside]) > 67.5) and outside.sum() == 360
    view = scan.window()
    assert np.array_equal(view.ranges, scan.ranges[~outside])
    assert view.window() is view


def test_the_paper_sensor_is_its_own_view() -> None:
    scan = _scan(paper_ir())
    assert scan.window() is scan
    assert all(beam is not None for beam in scan.beams)


def test_a_sensor_with_too_few_rays_in_the_paper_view_is_rejected() -> None:
    sensor = SensorParams(fov=1.5 * math.pi, rays=3)  # rays at -135, 0 and 135 degrees
    params = EpisodeParams(sensor=sensor)
    with pytest.raises(ParameterError, match="IFGM reads the paper's 135-degree view: 1 ray"):
        make_planner("ifgm").reset(Pose(0, 0, 0), Point(10, 0), params)


@pytest.mark.paper("sensor.fov", "s5.ifgm_u_h")
@pytest.mark.parametrize("world", ["u_trap", "h_block"])
@pytest.mark.parametrize("planner", ["ifgm", "iba"])
@pytest.mark.parametrize(("fov_degrees", "rays"), [(90, 51), (270, 720), (356, 400)])
def test_ifgm_and_iba_cross_u_and_h_with_any_field_of_view(
    world: str, planner: str, fov_degrees: int, rays: int
) -> None:
    base = resolve_world(world)
    sensor = SensorParams(fov=math.radians(fov_degrees), rays=rays, range_max=15.0)
    run = simulate(dataclasses.replace(base, sensor=sensor), make_planner(planner))
    assert run.result.stop_reason == "goal_reached", run.result
    if planner == "ifgm":  # the dead-end rule still fires inside the U and the H
        assert "dead_end_turn" in {step.branch for step in run.trace}


def test_a_long_range_scan_is_seen_as_far_as_the_paper_sensor() -> None:
    """A 100 ft sensor on the paper's 1 ft robot: returns beyond view_range = 15 r are neither
    remembered nor obstacles of Figure 3, so a far wall all round closes no view."""
    sensor = SensorParams(range_max=100.0)
    params = EpisodeParams(sensor=sensor)
    half = sensor.fov / 2
    far = LaserScan(-half, half, sensor.angle_increment, 0.0, 100.0, [30.0] * sensor.rays)
    near = LaserScan(-half, half, sensor.angle_increment, 0.0, 100.0, [5.0] * sensor.rays)
    for scan, remembered in ((far, 0), (near, sensor.rays)):
        planner = make_planner("ifgm")
        planner.reset(Pose(0, 0, 0), Point(50, 0), params)
        planner.step(Observation(0.0, Pose(0, 0, 0), Point(50, 0), scan))
        assert len(planner.memory.points) == remembered
        atoms = planner.last_atoms
        assert atoms is not None and atoms.blocked == (scan is near)
