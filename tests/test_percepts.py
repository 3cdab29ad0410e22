"""Percepts (ifgm_ref.paper.percepts): obstacles as clusters and the gaps between them."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.paper.percepts.clusters import GapReading, Side, cluster_scan, gaps_between
from ifgm_ref.paper.percepts.memory import PerceptMemory
from ifgm_ref.paper.percepts.points import point_to_world, to_world
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.shapes import rectangle
from ifgm_ref.sim.world import Polygon, World


def _scan_of(*obstacles: Polygon) -> LaserScan:
    """The default sensor's scan from the origin, facing +x."""
    pose = Pose(0.0, 0.0, 0.0)
    return IRSensor(World(start=pose, goal=Point(50.0, 0.0), obstacles=obstacles)).scan(pose)


@pytest.mark.paper("percepts.obstacle_array")
def test_gap_is_the_distance_between_the_obstacles() -> None:
    """Two 6 ft squares 1.5 ft apart: the gap found is the closest pair of returns, no wider
    than the 1.5 ft between them plus the ray spacing there (1.8 degrees at 10 ft, 0.3 ft),
    and no wider than the distance between the facing borders."""
    squares = (rectangle((10.0, 5.0), 6.0, 6.0), rectangle((10.0, 12.5), 6.0, 6.0))
    clusters = cluster_scan(_scan_of(*squares), jump=2.0)
    assert len(clusters) == 2
    (gap,) = gaps_between(clusters)
    assert 1.5 <= gap.width <= 1.5 + 0.35
    assert gap.width <= math.dist(clusters[0].left_border, clusters[1].right_border)


@pytest.mark.paper("percepts.obstacle_array")
def test_means_reading_overstates_a_gap_between_walls() -> None:
    walls = (rectangle((10.0, -6.0), 2.0, 8.0), rectangle((10.0, 6.0), 2.0, 8.0))
    clusters = cluster_scan(_scan_of(*walls), jump=2.0)
    (nearest,) = gaps_between(clusters)
    (means,) = gaps_between(clusters, reading=GapReading.MEANS)
    assert nearest.width == pytest.approx(4.0, abs=0.5)  # the 4 ft between the walls' ends
    assert means.width > nearest.width + 3.0
    assert [c.side for c in clusters] == [Side.RIGHT, Side.LEFT]


#: Coordinates of a point or a pose, ft.
COORD = st.floats(-1e3, 1e3, allow_nan=False)


@given(
    st.tuples(COORD, COORD),
    st.builds(Pose, COORD, COORD, st.floats(-math.pi, math.pi)),
)
def test_one_point_to_the_world_is_the_arrays_transform_to_the_bit(
    xy: tuple[float, float], pose: Pose
) -> None:
    one = point_to_world(xy, pose)
    many = to_world(np.array([xy]), pose)[0]
    assert (one.x, one.y) == (float(many[0]), float(many[1]))


@pytest.mark.parametrize("rounded", [float, lambda t: float(np.float32(t))])
def test_the_memory_keeps_the_scan_exactly_its_horizon_old_whatever_the_rounding(
    rounded: Callable[[float], float],
) -> None:
    """Errata row 20: with scans every 0.1 s and an 8 s horizon, the memory holds the last 81
    scans at every step, in doubles and in float32 times alike. Compared with ``t - 8``
    itself, the scan exactly 8 s old was forgotten at 97 of these 320 steps in doubles and 56
    in float32: a port's rounding decided what it remembered."""
    memory = PerceptMemory(horizon=8.0, period=0.1)
    for k in range(400):
        memory.add_points(rounded(k * 0.1), np.array([[float(k), 0.0]]))
        assert len(memory.points) == min(k + 1, 81), k
