"""The convergence bound: how long the oracle waits for a planner to reach the goal.

Bug1 reaches the goal after a path of at most ``D + 1.5 * sum(p_i)`` (``D`` the start-goal
distance, ``p_i`` the obstacles' perimeters; paper section 2.1.1), and every planner of the
paper that promises convergence does at most what Bug1 does; the budget adds slack for a
real robot:

* ``p_i`` is measured round the obstacle *inflated by twice the robot radius*, the curve a
  disc robot follows at a stand-off of one radius (a planner's follow distance);
* the path is driven at the robot's top speed ``v`` and the time multiplied by
  :data:`SLACK`, for slowing down in turns and for a port a little slower than the reference;
* :data:`TURN_ALLOWANCE` half turns on the spot at the robot's turn rate ``w`` are added (the
  dead-end rule turns up to 180 degrees, several times per obstacle).

So ``time_bound = SLACK * (D + 1.5 * sum(p_i)) / v + TURN_ALLOWANCE * pi / w``, in seconds. It
sums every obstacle of the world, not only those near the goal: generous, never tight. Every
term scales with the robot, so the bound holds in any length unit. The margin the reference
planners leave, measured: ``docs/oracle.md``, "Time bound".
"""

from __future__ import annotations

import math

import shapely

from ifgm_ref.core.pose import distance
from ifgm_ref.sim.world import World

#: Multiplier on the driving time of Bug1's path at top speed.
SLACK = 2.5
#: Half turns on the spot allowed on top of the driving time.
TURN_ALLOWANCE = 10


def followed_perimeters(world: World) -> float:
    """Sum of the perimeters of the obstacles inflated by twice the robot radius."""
    inflate = 2.0 * world.robot.radius
    # 16 chords per quarter circle: what ``Geometry.buffer`` has always used here
    return sum(
        shapely.buffer(ob.geometry, inflate, quad_segs=16).exterior.length for ob in world.obstacles
    )


def time_bound(world: World) -> float:
    """The convergence budget of ``world`` in seconds (see the module docstring).

    >>> from ifgm_ref.sim.world import World
    >>> # no obstacle: 2.5 * 33 ft / (197/149 ft/s) + 10 * pi / (pi/2 rad/s)
    >>> round(time_bound(World(start=(0, 0, 0), goal=(33, 0))), 3)
    82.398
    """
    robot = world.robot
    return SLACK * path_bound(world) / robot.speed + TURN_ALLOWANCE * math.pi / robot.max_turn_rate


def path_bound(world: World) -> float:
    """Bug1's path bound on the inflated obstacles, ``D + 1.5 * sum(p_i)``."""
    return distance(world.start.position, world.goal) + 1.5 * followed_perimeters(world)
