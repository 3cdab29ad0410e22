"""Gazebo SDF worlds as 2D worlds: the static models' collision cylinders and boxes.

An SDF world (http://sdformat.org/spec, ``<world>``) holds ``<model>`` elements; a model holds
``<link>`` elements, a link ``<collision>`` elements, each with one ``<geometry>``. Every level
may carry a ``<pose>``: ``x y z roll pitch yaw`` relative to its parent (SDF 1.6; the
``frame`` attribute, empty in the files we read, means the parent frame). A collision's pose
in the world is ``model pose * link pose * collision pose``.

What is read, and how it becomes 2D (the robot moves in the plane ``z = 0``):

* only models with ``<static>`` true (``1`` or ``true``): obstacles that never move;
* only ``<collision>`` geometry (``<visual>`` is what a camera sees, not what the robot hits);
* ``<cylinder>`` (``<radius>``) becomes a :class:`~ifgm_ref.sim.world.Circle`, ``<box>``
  (``<size>x y z</size>``) a rectangle :class:`~ifgm_ref.sim.world.Polygon` rotated by the yaw;
  a ``<plane>`` (the ground) is skipped; any other geometry in a static model is an error
  that names the model;
* poses are composed in 2D: x, y and yaw. Roll and pitch are ignored, which is exact for
  upright shapes (what a 2D world holds) and would be wrong for a tilted one;
* the ``<state>`` block (the world as Gazebo last saved it) repeats model poses; it is *not*
  read. In all 200 bundled BARN worlds (``ifgm_ref/io/barn_worlds``) every state pose
  equals the model's own ``<pose>`` (checked when this module was written), and a model's
  own pose is what Gazebo spawns it at.

Units are those of the file (metres for Gazebo), so the robot and sensor must be in metres too.
The standard library's :mod:`xml.etree.ElementTree` reads the XML: the SDF subset above needs
no SDF library (sdformat's Python bindings come with the C++ library and Gazebo).
"""

from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import NamedTuple

from ifgm_ref.core.errors import WorldError
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.validate import POSITIVE, violation
from ifgm_ref.sim.world import Bounds, Circle, Obstacle, Polygon, World

#: Geometry skipped without complaint: the ground.
SKIPPED_GEOMETRY = frozenset({"plane"})


class Pose2D(NamedTuple):
    """The planar part ``(x, y, yaw)`` of an SDF pose."""

    x: float
    y: float
    yaw: float

    def compose(self, child: Pose2D) -> Pose2D:
        """This frame followed by ``child`` (given in this frame): the child in the parent.

        >>> Pose2D(1.0, 0.0, math.pi / 2).compose(Pose2D(1.0, 0.0, 0.0))  # doctest: +ELLIPSIS
        Pose2D(x=1.0, y=1.0, yaw=1.57...)
        """
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return Pose2D(
            self.x + c * child.x - s * child.y, self.y + s * child.x + c * child.y,
            self.yaw + child.yaw,
        )  # fmt: skip


IDENTITY = Pose2D(0.0, 0.0, 0.0)


def _numbers(text: str | None, count: int, where: str) -> list[float]:
    """``count`` finite numbers separated by white space, or a WorldError naming ``where``."""
    parts = (text or "").split()
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise WorldError(f"{where}: expected {count} numbers, got {text!r}") from None
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise WorldError(f"{where}: expected {count} finite numbers, got {text!r}")
    return values


def _pose(element: ET.Element, where: str) -> Pose2D:
    """The planar pose of ``element``'s ``<pose>`` child (identity when it has none)."""
    node = element.find("pose")
    if node is None:
        return IDENTITY
    x, y, _z, _roll, _pitch, yaw = _numbers(node.text, 6, f"{where}.pose")
    return Pose2D(x, y, yaw)


def _positive(element: ET.Element, tag: str, count: int, where: str) -> list[float]:
    """The ``count`` numbers of ``element``'s child ``tag``, each > 0."""
    node = element.find(tag)
    if node is None:
        raise WorldError(f"{where}: missing <{tag}>")
    values = _numbers(node.text, count, f"{where}.{tag}")
    for value in values:
        if why := violation(value, POSITIVE, shown=repr(node.text)):
            raise WorldError(f"{where}.{tag}: {why}")
    return values


def box_polygon(pose: Pose2D, size_x: float, size_y: float) -> Polygon:
    """The footprint of an SDF box of ``size_x`` by ``size_y`` centred at ``pose``.

    Vertices counter-clockwise from the box's (-x, -y) corner in its own frame.

    >>> box_polygon(Pose2D(0.0, 0.0, 0.0), 2.0, 1.0).vertices
    ((-1.0, -0.5), (1.0, -0.5), (1.0, 0.5), (-1.0, 0.5))
    """
    hx, hy = size_x / 2.0, size_y / 2.0
    corners = [Pose2D(dx, dy, 0.0) for dx, dy in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]
    return Polygon(tuple(pose.compose(c)[:2] for c in corners))


def _geometry(geometry: ET.Element, pose: Pose2D, model: str, where: str) -> Obstacle | None:
    """The obstacle of one ``<geometry>`` at ``pose`` (``None`` for a skipped ground plane)."""
    shapes = list(geometry)
    if len(shapes) != 1:
        raise WorldError(f"{where}: model {model!r}: <geometry> must hold exactly one shape")
    shape = shapes[0]
    if shape.tag == "cylinder":
        (radius,) = _positive(shape, "radius", 1, f"{where}.cylinder")
        return Circle((pose.x, pose.y), radius)
    if shape.tag == "box":
        size_x, size_y, _size_z = _positive(shape, "size", 3, f"{where}.box")
        return box_polygon(pose, size_x, size_y)
    if shape.tag in SKIPPED_GEOMETRY:
        return None
    raise WorldError(
        f"{where}: static model {model!r} has unsupported geometry <{shape.tag}> "
        "(supported: cylinder, box; plane is skipped)"
    )


def _is_static(model: ET.Element) -> bool:
    node = model.find("static")
    return node is not None and (node.text or "").strip().lower() in {"1", "true"}


def sdf_obstacles(root: ET.Element, source: str) -> list[Obstacle]:
    """The obstacles of every static model of the ``<world>`` under ``root`` (an ``<sdf>``)."""
    if root.tag != "sdf":
        raise WorldError(f"{source}: not an SDF file (root element <{root.tag}>, expected <sdf>)")
    world = root.find("world")
    if world is None:
        raise WorldError(f"{source}: no <world> element")
    obstacles: list[Obstacle] = []
    for m, model in enumerate(world.findall("model")):
        if not _is_static(model):
            continue
        name = model.get("name") or f"model[{m}]"
        where = f"{source}: {name}"
        model_pose = _pose(model, where)
        for link in model.findall("link"):
            link_pose = model_pose.compose(_pose(link, f"{where}.link"))
            for collision in link.findall("collision"):
                here = f"{where}.collision"
                geometry = collision.find("geometry")
                if geometry is None:
                    raise WorldError(f"{here}: missing <geometry>")
                pose = link_pose.compose(_pose(collision, here))
                obstacle = _geometry(geometry, pose, name, here)
                if obstacle is not None:
                    obstacles.append(obstacle)
    return obstacles


def load_sdf_world(
    path: str | os.PathLike[str],
    *,
    start: Pose,
    goal: Point,
    name: str | None = None,
    robot: RobotParams | None = None,
    sensor: SensorParams | None = None,
    bounds: Bounds | None = None,
) -> World:
    """A :class:`~ifgm_ref.sim.world.World` from a Gazebo SDF world file.

    SDF has no start or goal (a Gazebo world holds no task), so the caller gives them.

    Parameters
    ----------
    path : the ``.world`` (or ``.sdf``) file.
    start, goal : the robot's start pose and goal, in the file's units (metres).
    name : a label; default the file's stem.
    robot, sensor : the robot and sensor (default: the package defaults, sized in feet; give
        metre-sized ones for a Gazebo world).
    bounds : an arena ``Bounds(xmin, ymin, xmax, ymax)``, or ``None`` for the unbounded plane.

    Raises
    ------
    WorldError
        When the file cannot be read or parsed, has no ``<world>``, a static model has a
        malformed pose or an unsupported geometry (the message names the model), there is no
        obstacle at all, or the start or goal is not clear of the obstacles.
    """
    file = Path(path)
    try:
        root = ET.parse(file).getroot()
    except OSError as err:
        raise WorldError(f"{file}: cannot read: {err.strerror or err}") from None
    except ET.ParseError as err:
        raise WorldError(f"{file}: malformed XML: {err}") from None
    obstacles = sdf_obstacles(root, str(file))
    if not obstacles:
        raise WorldError(f"{file}: no obstacles (no static model with collision geometry)")
    try:
        return World(
            start=start, goal=goal, obstacles=tuple(obstacles), bounds=bounds,
            robot=robot or RobotParams(), sensor=sensor or SensorParams(),
            name=file.stem if name is None else name,
        )  # fmt: skip
    except WorldError as err:
        raise WorldError(f"{file}: {err}") from None
