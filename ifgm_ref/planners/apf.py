"""Artificial Potential Field (APF): the goal attracts, every obstacle point in range repels.

Reference
---------
O. Khatib, "Real-time obstacle avoidance for manipulators and mobile robots", *The
International Journal of Robotics Research* 5(1):90-98, 1986 -- the APF of the IFGM paper's
section 2 ("the robot is considered as a test charge attracted by the goal and repelled by the
obstacles") and Table 1 ("The algo. cannot avoid U, H-shaped and symmetric obstacles";
section 5.2: "Similar to FGM, APF is also unable to take decision in this critical
scenario").

The robot heads along the total force ``F = F_att + sum_i F_rep,i``, the negative gradient of

* the attractive well ``U_att = 0.5 k_att |p - p_goal|^2``, so ``F_att = k_att (p_goal - p)``;
* one repulsive barrier per scan return ``i`` at range ``d_i`` (Khatib's FIRAS function)
  ``U_rep,i = 0.5 eta (1/d_i - 1/d0)^2`` for ``d_i <= d0`` and 0 beyond, so
  ``F_rep,i = eta (1/d_i - 1/d0) / d_i^2`` along the unit vector from the return to the robot.

Each return is its own point obstacle (the scan has no notion of objects), so ``eta`` is per
return and a wall repels more the more rays hit it. Distances are those the scan measures,
from the robot's centre. Only the current scan counts: a wall that leaves the field of view
stops repelling.

A safety rule keeps the failure a *trap*, not a crash: the speed is 0 whenever the corridor
the robot is about to drive along (as wide as the robot plus ``stop_margin`` each side) holds
a return nearer than ``radius + stop_margin`` plus one step's travel. The robot then only
turns towards the force; where the force keeps pointing into the obstacle it stays there, at
the local minimum.

A wide obstacle across the start-goal line traps it, as Table 1 says (where and why,
measured: ``docs/benchmark.md``, "Measured").

==================  ===============  ============================================
Khatib symbol       here             meaning
==================  ===============  ============================================
``k_p``             ``k_att``        attractive gain, 1/s (force per ft)
``eta``             ``eta``          repulsive gain, per return, ft^3/s
``rho_0``           ``d0``           influence distance of a return, ft
``rho``             ``d_i``          range of return ``i``, ft
==================  ===============  ============================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.elements import traces
from ifgm_ref.core.formulas import Unit
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import Behaviour, Command, EpisodeParams, Observation
from ifgm_ref.paper.percepts.corridor import free_length
from ifgm_ref.paper.percepts.points import scan_points
from ifgm_ref.planners.edge_following import turn_speed
from ifgm_ref.planners.governor import BrakingGovernor
from ifgm_ref.planners.tuning import Tuning, check_names, derived, parameter_names

__all__ = [
    "APFBranch",
    "APFParams",
    "APFPlanner",
    "attractive_force",
    "repulsive_force",
]


class APFBranch(StrEnum):
    """The decision APF took at one step (the trace's ``branch``)."""

    ATTRACT = "attract"  #: no return within d0: the goal alone pulls
    REPEL = "repel"  #: some return within d0 pushes the robot away
    BLOCKED = "blocked"  #: the safety rule holds the robot (speed 0); it only turns
    EQUILIBRIUM = "equilibrium"  #: the forces cancel exactly: stop where the robot is


@dataclass(frozen=True)
class APFParams(Tuning):
    """APF's settings, read from ``EpisodeParams.params`` by name.

    The IFGM paper gives no values; the defaults are ours, each a formula in the robot's
    radius ``r`` with its reason (the numbers are the paper's 1 ft robot's).

    Parameters
    ----------
    k_att : float, default 1
        Attractive gain, > 0, a number. Only the *direction* of the total force steers the
        robot, so the scale is set by ``k_att`` alone and ``eta`` is chosen relative to it.
    eta : float, default ``50 r^4``
        Repulsive gain per return, > 0, a length to the fourth power: the pull grows with a
        length and each push with ``eta`` over a length cubed, so only ``eta / r^4`` keeps
        their balance at every scale. A straight wall across the default 76-ray view then
        pushes back with 128 at 2 ft, 52 at 2.5 ft and 23 at 3 ft, as hard as a goal 128,
        52 or 23 ft away pulls (``k_att = 1``): with goals tens of feet away the robot turns
        off, or halts, 2.5-3 ft from a wall, before the safety rule (1.5 ft plus one step)
        has to act.
    d0 : float, default ``5 r``
        Influence distance, > 0, a length: two and a half robot diameters, a third of the
        paper's sensor range, so only nearby returns push.
    stop_margin : float, default ``r/2``
        Free space the safety rule keeps in front of the robot's disc, > 0, a length.
    """

    k_att: float = derived("1", Unit.NUMBER)
    eta: float = derived("50*r**4", Unit.LENGTH4)
    d0: float = derived("5*r", Unit.LENGTH)
    stop_margin: float = derived("r/2", Unit.LENGTH)


def attractive_force(to_goal: tuple[float, float], k_att: float) -> NDArray[np.float64]:
    """``F_att = k_att (p_goal - p)``: the negative gradient of the quadratic well.

    >>> attractive_force((3.0, -4.0), 2.0).tolist()
    [6.0, -8.0]
    """
    return k_att * np.asarray(to_goal, dtype=np.float64)


def repulsive_force(scan: LaserScan, *, eta: float, d0: float) -> tuple[NDArray[np.float64], int]:
    """The sum of the FIRAS forces of every return within ``d0``, robot frame.

    ``F_rep,i = eta (1/d_i - 1/d0) / d_i^2 * (-u_i)``, with ``u_i`` the unit vector from the
    robot to return ``i``. A return at range 0 (the robot touching) is skipped: its direction
    is undefined.

    Returns
    -------
    force : (2,) array
        ``(F_x, F_y)`` in the robot frame.
    count : int
        Number of returns that pushed.

    Examples
    --------
    One return 2 ft ahead with d0 = 4: ``eta (1/2 - 1/4) / 4 = eta / 16``, pushing back:

    >>> scan = LaserScan(-0.5, 0.5, 0.5, 0.0, 10.0, [math.inf, 2.0, 5.0])
    >>> force, count = repulsive_force(scan, eta=16.0, d0=4.0)
    >>> force.tolist(), count
    ([-1.0, -0.0], 1)
    """
    pts = scan_points(scan)
    near = (pts.ranges <= d0) & (pts.ranges > 0.0)
    d = pts.ranges[near]
    if len(d) == 0:
        return np.zeros(2), 0
    magnitude = eta * (1.0 / d - 1.0 / d0) / (d * d)
    unit = pts.xy[near] / d[:, np.newaxis]
    return -(magnitude[:, np.newaxis] * unit).sum(axis=0), len(d)


@traces("apf", "t1.apf_u_h_symmetric")
class APFPlanner:
    """Head along the total potential-field force; stop short of what is straight ahead.

    Speed is :func:`~ifgm_ref.planners.edge_following.turn_speed` of the heading error, or 0
    when the safety rule blocks the way (see the module docstring).

    Examples
    --------
    >>> planner = APFPlanner()
    >>> planner.reset(Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), EpisodeParams())
    >>> empty = LaserScan(-1.0, 1.0, 1.0, 0.0, 15.0, [math.inf] * 3)
    >>> command = planner.step(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), empty))
    >>> command.heading, round(command.speed, 3), command.branch
    (0.0, 1.322, 'attract')
    >>> wall = LaserScan(-1.0, 1.0, 1.0, 0.0, 15.0, [math.inf, 1.2, math.inf])
    >>> planner.step(Observation(0.1, Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), wall)).speed
    0.0
    """

    name: ClassVar[str] = "apf"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (APFParams,)
    #: Names of the settings read from ``EpisodeParams.params``.
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self) -> None:
        self.tuning = APFParams.for_episode(EpisodeParams())
        self.radius = 1.0
        self.speed = 1.0
        self.max_turn = math.pi
        self.step_length = 0.0
        self.force = np.zeros(2)
        self.governor = BrakingGovernor()

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Read the settings from ``params.params`` (see :class:`APFParams`)."""
        check_names(params.params, self.parameters, self.name)
        self.tuning = APFParams.for_episode(params)
        self.radius = params.robot.radius
        self.speed = params.robot.speed
        self.max_turn = params.robot.max_turn_rate * params.dt
        self.step_length = params.robot.speed * params.dt
        self.force = np.zeros(2)
        self.governor.reset(params)

    def step(self, observation: Observation) -> Command:
        """Decide (:meth:`decide`), then stop in time (the braking governor,
        :mod:`~ifgm_ref.planners.governor`)."""
        return self.governor(self.decide(observation), observation)

    def decide(self, observation: Observation) -> Command:
        """Sum the forces in the robot frame, steer along them, stop if the way is blocked."""
        pose, goal, scan = observation.pose, observation.goal, observation.scan
        c, s = math.cos(pose.theta), math.sin(pose.theta)
        dx, dy = goal.x - pose.x, goal.y - pose.y
        to_goal = (c * dx + s * dy, -s * dx + c * dy)  # robot frame
        repulsion, pushing = repulsive_force(scan, eta=self.tuning.eta, d0=self.tuning.d0)
        self.force = attractive_force(to_goal, self.tuning.k_att) + repulsion
        fx, fy = float(self.force[0]), float(self.force[1])
        if fx == 0.0 and fy == 0.0:
            return Command(
                pose.theta,
                0.0,
                behaviour=Behaviour.OBSTACLE_AVOIDANCE,
                branch=str(APFBranch.EQUILIBRIUM),
            )
        relative = math.atan2(fy, fx)
        heading = wrap_angle(pose.theta + relative)
        branch = APFBranch.REPEL if pushing else APFBranch.ATTRACT
        speed = turn_speed(relative, self.speed)
        if speed > 0.0 and self._blocked(scan, relative):
            branch, speed = APFBranch.BLOCKED, 0.0
        behaviour = Behaviour.MOVE_TO_GOAL if pushing == 0 else Behaviour.OBSTACLE_AVOIDANCE
        return Command(heading, speed, behaviour=behaviour, branch=str(branch))

    def _blocked(self, scan: LaserScan, relative: float) -> bool:
        """Whether a return lies in the robot's path for this step, within the stop distance.

        The robot first turns by at most ``max_turn_rate * dt`` towards the heading, then
        drives along its new heading (:mod:`ifgm_ref.sim.robot`); that is the corridor tested.
        """
        direction = max(-self.max_turn, min(self.max_turn, relative))
        reach = self.radius + self.tuning.stop_margin
        pts = scan_points(scan)
        ahead = free_length(pts.xy, (0.0, 0.0), direction, reach)
        return ahead < reach + self.step_length
