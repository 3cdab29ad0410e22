"""A world and a robot body as one MuJoCo model (MJCF), for :mod:`ifgm_ref.sim.physics.mujoco`.

The world becomes static geometry on a floor: a circle a vertical cylinder, a polygon (U and
H included) its triangles (a constrained Delaunay triangulation of its outline,
:func:`shapely.constrained_delaunay_triangles`), each extruded into a prism mesh, which is
convex, as MuJoCo's collision needs. The robot is the body of :mod:`ifgm_ref.sim.physics.bodies`
on a free joint: a chassis (a cylinder of radius ``r``, or the body's box) clear of the floor,
two driven wheels on
its diameter, a frictionless caster sphere in front and one behind (docs/physics.md says
why).

Which geoms touch which (MuJoCo's ``contype``/``conaffinity`` bits): wheels and caster meet
only the floor, the chassis meets only the obstacles, obstacles meet neither the floor nor
each other. So the only contact between the robot and the world is the chassis' (the disc's)
with an obstacle: the collision of :mod:`ifgm_ref.sim.physics.mujoco`. Obstacles are in geom
group :data:`OBSTACLE_GROUP`, the only group the range sensor's rays see.

Heights are relative to ``r`` (they only have to keep the rays, cast at :data:`SENSOR_HEIGHT`
``r``, within the obstacles' height); the time step is the episode's divided into whole
substeps of at most :data:`MAX_SUBSTEP` s.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import shapely

from ifgm_ref.core.params import RobotParams
from ifgm_ref.sim.physics.bodies import CASTER_OFFSET, SERVO_TIME, Body
from ifgm_ref.sim.world import Circle, Polygon, World

#: The geom group of the obstacles (rays see this group only).
OBSTACLE_GROUP = 2
#: Obstacles' height and the sensor's height above the floor, in robot radii.
OBSTACLE_HEIGHT = 4.0
SENSOR_HEIGHT = 1.0
#: Chassis: its floor clearance and height, in robot radii.
CHASSIS_CLEARANCE = 0.1
CHASSIS_HEIGHT = 0.8
#: Longest physics substep, s: 5 ms. The ``implicitfast`` integrator keeps the wheels'
#: velocity servos stable at a quarter of their time constant (:data:`SERVO_TIME`); at 1 m/s
#: the robot moves 5 mm a substep, and the trace's clearance is measured along every substep.
MAX_SUBSTEP = 0.005
#: contype/conaffinity bits: the floor's and the obstacles'.
_FLOOR_BIT = 1
_OBSTACLE_BIT = 2


def substeps(dt: float) -> int:
    """Physics substeps in one episode step ``dt``: the fewest of at most
    :data:`MAX_SUBSTEP` s.

    >>> substeps(0.1), substeps(0.05), substeps(0.001)
    (20, 10, 1)
    """
    return max(1, math.ceil(dt / MAX_SUBSTEP - 1e-9))


def _fmt(*values: float) -> str:
    return " ".join(repr(float(v)) for v in values)


def model_xml(world: World, body: Body, dt: float) -> str:
    """The MJCF text of ``world`` with ``body`` at the world's start, stepped at ``dt`` s
    split into :func:`substeps`."""
    robot = world.robot
    root = ET.Element("mujoco", model=world.name or "world")
    ET.SubElement(root, "compiler", angle="radian", autolimits="true")
    ET.SubElement(
        root,
        "option",
        timestep=repr(dt / substeps(dt)),
        gravity=_fmt(0.0, 0.0, -body.gravity),
        integrator="implicitfast",
        cone="elliptic",
        impratio="10",
    )
    asset = ET.SubElement(root, "asset")
    worldbody = ET.SubElement(root, "worldbody")
    ET.SubElement(
        worldbody,
        "geom",
        name="floor",
        type="plane",
        size=_fmt(0.0, 0.0, 1.0),
        contype="0",
        conaffinity=str(_FLOOR_BIT),
        friction=_fmt(1.0, 0.005, 0.0001),
    )
    height = OBSTACLE_HEIGHT * robot.radius
    for index, obstacle in enumerate(world.obstacles):
        _add_obstacle(worldbody, asset, index, obstacle, height)
    _add_robot(worldbody, world, body)
    _add_actuators(root, body, robot)
    return ET.tostring(root, encoding="unicode")


def _obstacle_geom(parent: ET.Element, name: str, **attrs: str) -> None:
    common = {
        "name": name,
        "group": str(OBSTACLE_GROUP),
        "contype": "0",
        "conaffinity": str(_OBSTACLE_BIT),
        "rgba": "0.55 0.55 0.6 1",
    }
    ET.SubElement(parent, "geom", common | attrs)


def _add_obstacle(
    worldbody: ET.Element, asset: ET.Element, index: int, obstacle: Circle | Polygon, height: float
) -> None:
    if isinstance(obstacle, Circle):
        x, y = obstacle.center
        _obstacle_geom(
            worldbody,
            f"obstacle{index}",
            type="cylinder",
            size=_fmt(obstacle.radius, height / 2),
            pos=_fmt(x, y, height / 2),
        )
        return
    for part, triangle in enumerate(triangles(obstacle)):
        mesh = f"obstacle{index}_{part}"
        vertices = [(x, y, z) for z in (0.0, height) for x, y in triangle]
        ET.SubElement(asset, "mesh", name=mesh, vertex=_fmt(*np.ravel(vertices)))
        _obstacle_geom(worldbody, mesh, type="mesh", mesh=mesh)


def triangles(polygon: Polygon) -> list[tuple[tuple[float, float], ...]]:
    """``polygon``'s outline cut into triangles that cover it exactly (convex pieces).

    >>> square = Polygon(((0, 0), (2, 0), (2, 2), (0, 2)))
    >>> parts = triangles(square)
    >>> len(parts), sum(shapely.Polygon(p).area for p in parts)
    (2, 4.0)
    """
    pieces = shapely.constrained_delaunay_triangles(polygon.geometry)
    out = []
    for piece in shapely.get_parts(pieces):
        ring = list(piece.exterior.coords)[:3]
        out.append(tuple((float(x), float(y)) for x, y in ring))
    return out


def _add_robot(worldbody: ET.Element, world: World, body: Body) -> None:
    robot = world.robot
    r = robot.radius
    wheel = body.scaled_wheel(robot)
    x, y, theta = world.start
    chassis_z = wheel  # the body frame at the wheels' axle height
    frame = ET.SubElement(
        worldbody,
        "body",
        name="robot",
        pos=_fmt(x, y, chassis_z),
        euler=_fmt(0.0, 0.0, theta),
    )
    ET.SubElement(frame, "freejoint", name="robot")
    izz = body.chassis_izz if body.chassis_izz is not None else 0.5 * body.chassis_mass * r * r
    ixx = izz / 2 + body.chassis_mass * (CHASSIS_HEIGHT * r) ** 2 / 12  # a uniform cylinder's
    ET.SubElement(
        frame,
        "inertial",
        pos=_fmt(0.0, 0.0, 0.0),
        mass=repr(body.chassis_mass),
        diaginertia=_fmt(ixx, ixx, izz),
    )
    bottom = CHASSIS_CLEARANCE * r - chassis_z
    height = CHASSIS_HEIGHT * r
    if body.outline is None:
        shape, size = "cylinder", _fmt(r, height / 2)
    else:
        shape, size = "box", _fmt(*(k * r / 2 for k in body.outline), height / 2)
    ET.SubElement(
        frame,
        "geom",
        name="chassis",
        type=shape,
        size=size,
        pos=_fmt(0.0, 0.0, bottom + height / 2),
        contype=str(_OBSTACLE_BIT),
        conaffinity="0",
        mass="0",
        rgba="0.2 0.4 0.8 0.6",
    )
    ET.SubElement(frame, "site", name="sensor", pos=_fmt(0.0, 0.0, SENSOR_HEIGHT * r - chassis_z))
    for side, sign in (("left", 1.0), ("right", -1.0)):
        _add_wheel(frame, body, robot, side, sign)
    caster = wheel / 2
    for end, sign in (("front", 1.0), ("rear", -1.0)):
        ET.SubElement(
            frame,
            "geom",
            name=f"caster_{end}",
            type="sphere",
            size=repr(caster),
            pos=_fmt(sign * CASTER_OFFSET * r, 0.0, caster - chassis_z),
            contype=str(_FLOOR_BIT),
            conaffinity="0",
            friction=_fmt(0.0, 0.0, 0.0),
            condim="1",
            priority="1",  # its contact with the floor takes its condim and friction: none
            mass=repr(body.wheel_mass / 4),
        )


def _add_wheel(frame: ET.Element, body: Body, robot: RobotParams, side: str, sign: float) -> None:
    wheel = body.scaled_wheel(robot)
    width = body.wheel_width_ratio * robot.radius
    link = ET.SubElement(
        frame,
        "body",
        name=f"wheel_{side}",
        pos=_fmt(0.0, sign * body.scaled_track(robot) / 2, 0.0),
    )
    ET.SubElement(link, "joint", name=f"wheel_{side}", type="hinge", axis="0 1 0")
    ET.SubElement(
        link,
        "geom",
        type="ellipsoid",
        size=_fmt(wheel, width / 2, wheel),
        contype=str(_FLOOR_BIT),
        conaffinity="0",
        condim="3",
        friction=_fmt(body.friction, 0.005, 0.0001),
        mass=repr(body.wheel_mass),
        rgba="0.1 0.1 0.1 1",
    )


def _add_actuators(root: ET.Element, body: Body, robot: RobotParams) -> None:
    """Velocity servos on both wheels; the force limit lets the whole robot reach the body's
    acceleration limit with a margin of two (the limit is the controller's, not the motor's)."""
    mass = body.chassis_mass + 2 * body.wheel_mass
    wheel = body.scaled_wheel(robot)
    torque = 2.0 * mass * body.max_accel * wheel / 2
    inertia = mass * wheel * wheel / 2  # each wheel moves half the robot
    actuators = ET.SubElement(root, "actuator")
    for side in ("left", "right"):
        ET.SubElement(
            actuators,
            "velocity",
            name=f"wheel_{side}",
            joint=f"wheel_{side}",
            kv=repr(inertia / SERVO_TIME),
            forcerange=_fmt(-torque, torque),
        )
