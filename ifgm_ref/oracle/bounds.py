"""The convergence bound: how long the oracle waits for a planner to reach the goal.

Origin. Lumelsky and Stepanov's Bug1 reaches the goal after a path of at most
``D + 1.5 * sum(p_i)`` (``D`` the start-goal distance, ``p_i`` the perimeters of the
obstacles that cut the disc of radius ``D`` about the goal; paper section 2.1.1). Every
planner of the paper that promises convergence (Bug1, Bug2, DistBug, IBA, IFGM) does at most
what Bug1 does, so the oracle takes Bug1's bound as the budget, with slack for a real robot:

* ``p_i`` is measured round the obstacle *inflated by the robot radius plus one foot*, the
  curve a disc robot follows at a stand-off (a planner's follow distance);
* the path is driven at the robot's top speed ``v`` and the time multiplied by
  :data:`SLACK` for slowing down in turns;
* :data:`TURN_ALLOWANCE` seconds are added for turning on the spot (the dead-end rule turns
  up to 180 degrees, at ``pi/2`` rad/s that is 2 s, several times per obstacle).

So ``time_bound = SLACK * (D + 1.5 * sum(p_i)) / v + TURN_ALLOWANCE``, in seconds. It sums
every obstacle of the world, not only those near the goal: generous, never tight.
"""

from __future__ import annotations

from ifgm_ref.pose import distance
from ifgm_ref.world import World

#: Multiplier on the driving time of Bug1's path: turns are taken at reduced speed.
SLACK = 1.5
#: Seconds added for turning on the spot.
TURN_ALLOWANCE = 20.0
#: Stand-off of the followed curve beyond the robot radius, ft.
STANDOFF = 1.0


def followed_perimeters(world: World) -> float:
    """Sum of the perimeters of the obstacles inflated by ``radius + STANDOFF``, ft."""
    inflate = world.robot.radius + STANDOFF
    return sum(ob.geometry.buffer(inflate).exterior.length for ob in world.obstacles)


def time_bound(world: World) -> float:
    """The convergence budget of ``world`` in seconds (see the module docstring).

    >>> from ifgm_ref.world import World
    >>> # no obstacle: 1.5 * 33 ft / (197/149 ft/s) + 20 s
    >>> round(time_bound(World(start=(0, 0, 0), goal=(33, 0))), 3)
    57.439
    """
    return SLACK * path_bound(world) / world.robot.speed + TURN_ALLOWANCE


def path_bound(world: World) -> float:
    """Bug1's path bound on the inflated obstacles, ``D + 1.5 * sum(p_i)``, ft."""
    return distance(world.start, world.goal) + 1.5 * followed_perimeters(world)
