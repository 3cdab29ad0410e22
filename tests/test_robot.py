"""Unicycle kinematics (ifgm_ref.sim.robot): straight motion and the turn-rate limit."""

from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.params import RobotParams
from ifgm_ref.core.pose import Pose, wrap_angle
from ifgm_ref.core.protocol import Command
from ifgm_ref.sim.robot import advance

angles = st.floats(-math.pi, math.pi, allow_nan=False)
speeds = st.floats(0.1, 10.0)
dts = st.sampled_from([0.01, 0.05, 0.1, 0.25])


@given(theta=angles, speed=speeds, dt=dts, steps=st.integers(1, 200))
def test_straight_motion_covers_speed_times_time(
    theta: float, speed: float, dt: float, steps: int
) -> None:
    robot = RobotParams(speed=speed)
    pose = Pose(3.0, -2.0, theta)
    for _ in range(steps):
        pose = advance(pose, Command(heading=theta, speed=speed), robot, dt)
    travelled = math.hypot(pose.x - 3.0, pose.y + 2.0)
    assert math.isclose(travelled, speed * dt * steps, rel_tol=1e-9), (
        f"travelled={travelled}, but should be v*t={speed * dt * steps}"
    )
    assert math.isclose(math.atan2(pose.y + 2.0, pose.x - 3.0), theta, abs_tol=1e-9) or (
        math.isclose(abs(theta), math.pi, abs_tol=1e-9)
    )


@given(theta=angles, target=angles, rate=st.floats(0.1, 6.0), dt=dts)
def test_turn_rate_limit_holds_and_turns_the_short_way(
    theta: float, target: float, rate: float, dt: float
) -> None:
    robot = RobotParams(max_turn_rate=rate)
    after = advance(Pose(0.0, 0.0, theta), Command(heading=target, speed=0.0), robot, dt)
    turned = wrap_angle(after.theta - theta)
    wanted = wrap_angle(target - theta)
    assert abs(turned) <= rate * dt + 1e-12, f"turned {turned} rad, limit {rate * dt}"
    if abs(wanted) <= rate * dt:
        assert math.isclose(wrap_angle(after.theta - target), 0.0, abs_tol=1e-9)
    else:
        assert math.copysign(1.0, turned) == math.copysign(1.0, wanted), "turned the long way"
        assert math.isclose(abs(turned), rate * dt, rel_tol=1e-9)


def test_zero_speed_turns_in_place() -> None:
    after = advance(Pose(1.0, 2.0, 0.0), Command(heading=1.0, speed=0.0), RobotParams(), 0.1)
    assert (after.x, after.y) == (1.0, 2.0)
    assert after.theta > 0.0


def test_speed_above_robot_speed_is_clipped() -> None:
    robot = RobotParams(speed=1.5)
    after = advance(Pose(0.0, 0.0, 0.0), Command(heading=0.0, speed=100.0), robot, 1.0)
    assert after.x == 1.5
