"""The Gazebo SDF loader (ifgm_ref/io/gazebo.py): poses composed, cylinders and boxes, errors."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from ifgm_ref.core.errors import WorldError
from ifgm_ref.core.params import RobotParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.io.gazebo import load_sdf_world
from ifgm_ref.sim.world import Circle, Polygon

BARN = Path(__file__).parent / "worlds" / "barn"
ROBOT = RobotParams(radius=0.2)
START = Pose(0.0, 0.0, 0.0)
GOAL = Point(10.0, 0.0)


def _sdf(models: str, *, state: str = "") -> str:
    return f"<sdf version='1.6'><world name='default'>{models}{state}</world></sdf>"


#: A rotated box and a cylinder, each under nested model / link / collision poses, a ground
#: plane, a non-static model, and a visual that must be ignored.
NESTED = _sdf(
    """
    <model name='ground_plane'><static>1</static><link name='link'><collision name='c'>
      <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
    </collision></link></model>
    <model name='box'>
      <static>true</static>
      <pose>4 1 0 0 0 1.5707963267948966</pose>
      <link name='link'>
        <pose>1 0 0 0 0 0</pose>
        <collision name='c'>
          <pose>0 0 0.5 0 0 -0.7853981633974483</pose>
          <geometry><box><size>2 1 1</size></box></geometry>
        </collision>
        <visual name='v'><geometry><sphere><radius>9</radius></sphere></geometry></visual>
      </link>
    </model>
    <model name='post'>
      <static>1</static>
      <pose>5 -3 0 0 0 3.141592653589793</pose>
      <link name='link'>
        <pose>1 2 0 0 0 1.5707963267948966</pose>
        <collision name='c'>
          <pose>0.5 0 0 0 0 0</pose>
          <geometry><cylinder><radius>0.3</radius><length>1</length></cylinder></geometry>
        </collision>
      </link>
    </model>
    <model name='robot'><static>0</static><link name='l'><collision name='c'>
      <geometry><sphere><radius>1</radius></sphere></geometry></collision></link></model>
    """,
    state="<state world_name='default'><model name='post'><pose>99 99 0 0 0 0</pose>"
    "</model></state>",
)


def _write(tmp_path: Path, text: str, name: str = "w.world") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def _load(path: Path) -> object:
    return load_sdf_world(path, start=START, goal=GOAL, robot=ROBOT)


def test_nested_poses_rotated_box_and_cylinder(tmp_path: Path) -> None:
    world = _load(_write(tmp_path, NESTED))
    assert world.name == "w"
    box, post = world.obstacles  # the plane, the visual and the non-static model are skipped
    # Box: model (4, 1, 90 deg) * link (1, 0) = (4, 2, 90 deg); the collision turns it by -45
    # degrees: centre (4, 2), yaw 45 degrees, half sizes 1 and 0.5.
    assert isinstance(box, Polygon)
    c, h = math.sqrt(0.5), 0.5 * math.sqrt(0.5)
    expected = [
        (4 - c + h, 2 - c - h),  # (-1, -0.5) rotated by 45 degrees
        (4 + c + h, 2 + c - h),  # (1, -0.5)
        (4 + c - h, 2 + c + h),  # (1, 0.5)
        (4 - c - h, 2 - c + h),  # (-1, 0.5)
    ]
    assert np.allclose(box.vertices, expected, rtol=0, atol=1e-12)
    # Cylinder: model (5, -3, 180 deg) * link (1, 2, 90 deg) = (4, -5, 270 deg); the collision
    # 0.5 ahead along 270 degrees: (4, -5.5). The <state> pose (99, 99) is not read.
    assert isinstance(post, Circle)
    assert post.center == pytest.approx((4.0, -5.5), abs=1e-12)
    assert post.radius == 0.3


def test_given_name_bounds_and_robot(tmp_path: Path) -> None:
    world = load_sdf_world(
        _write(tmp_path, NESTED), start=START, goal=GOAL, name="n", robot=ROBOT,
        bounds=(-1, -8, 12, 8),
    )  # fmt: skip
    assert (world.name, world.robot, tuple(world.bounds)) == ("n", ROBOT, (-1, -8, 12, 8))


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("<sdf><world>", "malformed XML"),
        ("<world/>", "not an SDF file"),
        ("<sdf version='1.6'/>", "no <world> element"),
        (_sdf(""), "no obstacles"),
        (
            _sdf(
                "<model name='m'><static>1</static><link><collision><geometry><sphere>"
                "<radius>1</radius></sphere></geometry></collision></link></model>"
            ),
            "static model 'm' has unsupported geometry <sphere>",
        ),
        (
            _sdf(
                "<model name='m'><static>1</static><pose>1 2 3</pose><link><collision>"
                "<geometry><box><size>1 1 1</size></box></geometry></collision></link></model>"
            ),
            "m.pose: expected 6 finite numbers, got '1 2 3'",
        ),
        (
            _sdf(
                "<model name='m'><static>1</static><link><collision><geometry><box>"
                "<size>1 -1 1</size></box></geometry></collision></link></model>"
            ),
            "m.collision.box.size: must be a finite number > 0",
        ),
        (
            _sdf(
                "<model name='m'><static>1</static><link><collision><geometry><cylinder>"
                "</cylinder></geometry></collision></link></model>"
            ),
            "missing <radius>",
        ),
        (
            _sdf(
                "<model name='m'><static>1</static><link><collision><geometry><cylinder>"
                "<radius>1</radius></cylinder></geometry></collision></link></model>"
            ),
            "start: (0.0, 0.0) is inside obstacles[0]",
        ),
    ],
)
def test_errors(tmp_path: Path, text: str, message: str) -> None:
    with pytest.raises(WorldError, match="^" + re.escape(str(tmp_path))) as err:
        _load(_write(tmp_path, text))
    assert message in str(err.value)
    assert "\n" not in str(err.value)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(WorldError, match="cannot read"):
        _load(tmp_path / "absent.world")


def test_barn_world_cylinders() -> None:
    world = load_sdf_world(
        BARN / "world_1.world", start=Pose(-2, 3, math.pi / 2), goal=Point(-2, 13), robot=ROBOT
    )
    assert len(world.obstacles) == 237  # 238 models less the ground plane
    assert all(isinstance(ob, Circle) and ob.radius == 0.075 for ob in world.obstacles)
    # unit_cylinder_0, the file's first model: <pose>-0.075000 0.075000 0 0 0 0</pose>.
    assert world.obstacles[0].center == (-0.075, 0.075)
    # The first one in the field, unit_cylinder_126: <pose>-4.275000 5.325000 0 0 0 0</pose>.
    assert world.obstacles[126].center == (-4.275, 5.325)
    # The last, unit_cylinder_236, ends the right-hand wall at the field's top.
    assert world.obstacles[-1].center == (-0.075, 9.525)
