"""The braking governor: every planner's command, slowed so that a robot with mass stops in time.

The paper's thresholds do not know how far a robot needs to stop (errata row 36); the
governor sits between a planner and the robot and lets through only commands from which the
robot can still stop before every obstacle it sees: passive safety (Mitsch, Ghorbal,
Vogelbacher & Platzer, "Formal verification of obstacle avoidance and navigation of ground
robots", IJRR 36(12):1312-1340, 2017, Theorem 1)::

    d >= v^2 / (2 b) + (A/b + 1) (A eps^2 / 2 + eps v)                       (M)

with ``A`` the largest acceleration, ``b`` the guaranteed braking, ``eps`` the decision
period and ``d`` the room to every obstacle the robot may sweep. For a robot told a speed
with response time ``tau``, the worst case is :func:`stopping_distance`; ``u`` is a bound on
the speed, kept from the governor's own commands (:func:`next_state`); ``d`` is measured in
the fan of headings the robot may take until it stops (:func:`fan_room`); the command keeps
the planner's heading and the largest admissible speed (:func:`safe_speed`), at most
``A eps`` above ``u``, and a turn rate within ``b / u``; where not even braking fits it brakes
along the last command's heading, and turns once it stands. ``proofs/braking.py`` proves
each step; the reasons for each piece: ``docs/physics.md``, "Braking in time".

The robot's ``braking`` and ``acceleration`` are :class:`~ifgm_ref.core.params.RobotParams` fields;
with ``braking`` infinite (the paper's robot) the governor changes nothing. It uses only what a
planner is handed: the robot, the time step, the pose and the scan.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.elements import traces
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner
from ifgm_ref.paper.percepts.points import scan_points

__all__ = [
    "BrakingGovernor",
    "GovernorState",
    "Limits",
    "StopsAtOnce",
    "admissible",
    "fan_room",
    "govern",
    "next_state",
    "safe_speed",
    "stopping_distance",
]


@dataclass(frozen=True)
class Limits:
    """What the governor knows of the robot: its radius ``r`` and top speed ``v_top`` (a
    length and a length/s), its guaranteed braking ``b`` and largest acceleration ``A``
    (length/s^2), the control period ``eps`` (the time step, s) and the robot's response
    time ``tau`` (s: how long after a command it may still move as before it)."""

    radius: float
    top_speed: float
    braking: float
    acceleration: float
    period: float
    response: float = 0.0

    #: The clearance the governor keeps beyond the robot's disc from what lies ahead, in
    #: robot radii: the planners' corridor margin (``corridor_margin``, ``r/4``), so that a
    #: stop a planner decides ends about where it expects its robot to stand, not a hair from
    #: the obstacle (:func:`fan_room`).
    MARGIN: ClassVar[float] = 0.25

    @classmethod
    def of(cls, params: EpisodeParams) -> Limits:
        """The limits of an episode's robot and time step; the response time is the robot's
        ``response`` plus its ``latency`` in steps."""
        robot = params.robot
        response = robot.response + robot.latency * params.dt
        return cls(
            robot.radius, robot.speed, robot.braking, robot.acceleration, params.dt, response
        )

    @property
    def stops_at_once(self) -> bool:
        """Whether the robot stops at once (infinite ``b``): the governor then does nothing."""
        return self.braking == math.inf


@dataclass(frozen=True)
class GovernorState:
    """What the governor carries from one step to the next: a bound on the robot's speed
    (0 at the start: the robot starts at rest), the heading and speed it last let through
    (``None`` and 0 before the first command), and, for a response time longer than a period,
    the speeds of the commands before the last that the robot may still follow (newest
    last), and the robot's heading at the last decision (``None`` before the first), from
    which its present turn is read."""

    speed_bound: float = 0.0
    heading: float | None = None
    speed: float = 0.0
    earlier: tuple[float, ...] = ()
    theta: float | None = None

    @property
    def following(self) -> float:
        """The fastest command the robot may still follow during its response time."""
        return max(self.speed, *self.earlier) if self.earlier else self.speed


def stopping_distance(state: GovernorState, speed: float, limits: Limits) -> float:
    """How far the robot may travel before it stands when it is commanded ``speed`` for one
    period ``eps`` and then brakes, its speed at most ``state.speed_bound`` now: the worst
    case moves, for its response time ``tau``, towards the fastest command it may still follow
    (:attr:`GovernorState.following`: the last one, or one older for a ``tau`` over ``eps``), then
    for a period towards ``speed``, each as hard as allowed (up at ``A``, never past the
    command or the top speed; down at ``b``, never below it), then brakes at ``b``.

    With no response time, commanded faster than it can reach (``u + A eps`` at most the
    command and the top speed), the robot gives Mitsch et al.'s bound (M),
    ``u^2/(2b) + (A/b + 1)(A eps^2/2 + eps u)``:

    >>> limits = Limits(radius=0.2, top_speed=2.0, braking=4.0, acceleration=2.0, period=0.1)
    >>> u = GovernorState(speed_bound=1.0)
    >>> mitsch = 1.0**2 / 8 + (2 / 4 + 1) * (2 * 0.01 / 2 + 0.1 * 1.0)
    >>> stopping_distance(u, 2.0, limits) == mitsch, round(mitsch, 6)
    (True, 0.29)

    Holding its speed, it drives one period, then brakes; told to stop, it only brakes:

    >>> stopping_distance(u, 1.0, limits) == 0.1 + 1 / 8, stopping_distance(u, 0.0, limits)
    (True, 0.125)
    """
    late, bound = _ramp(state.speed_bound, state.following, limits.response, limits)
    return late + _period(bound, speed, limits)


def _period(bound: float, speed: float, limits: Limits) -> float:
    """:func:`stopping_distance` once the response time is over: from a speed of at most
    ``bound``, one period towards ``speed``, then braking."""
    travel, end = _ramp(bound, speed, limits.period, limits)
    return travel + end**2 / (2 * limits.braking)


def _ramp(speed: float, target: float, duration: float, limits: Limits) -> tuple[float, float]:
    """The most a robot at most at ``speed`` may travel in ``duration`` towards ``target``
    (up at ``A``, never past it or the top speed; down at ``b``, never below it), and the
    bound on its speed then."""
    target = min(target, limits.top_speed)
    rate = limits.acceleration if target >= speed else -limits.braking
    ramp = min(duration, (target - speed) / rate) if target != speed else 0.0
    end = speed + rate * ramp
    return speed * ramp + rate * ramp**2 / 2 + end * (duration - ramp), end


def safe_speed(room: float, state: GovernorState, limits: Limits) -> float | None:
    """The largest speed in ``[0, v_top]`` whose :func:`stopping_distance` fits in ``room``;
    ``None`` when none does (not even braking).

    :func:`stopping_distance` grows with the command; on each of its pieces the speed is the
    root of a quadratic where it rises (:func:`_root`).

    >>> limits = Limits(radius=0.2, top_speed=2.0, braking=4.0, acceleration=2.0, period=0.1)
    >>> u = GovernorState(speed_bound=1.0)
    >>> faster, slower = safe_speed(0.26, u, limits), safe_speed(0.2, u, limits)
    >>> round(faster, 6), round(slower, 6)  # speeding up to 1.10 fits; holding 1.0 does not
    (1.103852, 0.9245)
    >>> [round(stopping_distance(u, c, limits), 12) for c in (faster, slower)]
    [0.26, 0.2]
    >>> safe_speed(10.0, u, limits), safe_speed(0.1, u, limits)  # free; can no longer stop
    (2.0, None)
    >>> safe_speed(0.0, GovernorState(), limits)  # standing, with no room: it may only stand
    0.0
    """
    top, b, a, eps = limits.top_speed, limits.braking, limits.acceleration, limits.period
    late, bound = _ramp(state.speed_bound, state.following, limits.response, limits)
    room -= late
    if _period(bound, top, limits) <= room:
        return top
    if _period(bound, bound, limits) <= room:  # speed up to c < bound + A eps
        # c eps - (c - u)^2/(2A) + c^2/(2b) = room
        return _root((1 / b - 1 / a) / 2, eps + bound / a, -(bound**2) / (2 * a) - room)
    low = max(0.0, bound - b * eps)
    if _period(bound, low, limits) > room:
        return None
    # slow to c > bound - b eps: u^2/(2b) + c eps - c (u - c)/b = room
    return _root(1 / b, eps - bound / b, bound**2 / (2 * b) - room)


def _root(a: float, p: float, q: float) -> float:
    """The root of ``a c^2 + p c + q`` where the quadratic rises (``q <= 0``, and ``a > 0``
    wherever ``p <= 0``), at least 0; each form chosen so that nothing cancels.

    >>> _root(0.25, -2.5, -0.2) == (2.5 + math.sqrt(6.25 + 0.2)) / 0.5  # p < 0: the + root
    True
    """
    if q >= 0.0:
        return 0.0
    s = math.sqrt(p * p - 4 * a * q)
    return max(0.0, -2 * q / (p + s) if p > 0 else (s - p) / (2 * a))


def fan_room(
    points: NDArray[np.float64], low: float, high: float, radius: float, margin: float = 0.0
) -> float:
    """How far the robot's disc may go along any path whose heading stays in ``[low, high]``
    (robot frame, rad, ``low <= 0 <= high``) before it meets one of ``points`` (robot frame,
    ``(n, 2)``); ``inf`` when none is in the way. A point ahead (its distance across the
    fan below ``radius``) is kept ``margin`` farther, unless it is already within half the
    margin of that: the robot then stops short of what it would hit, passes beside what it
    would not, and is not held up by what it already stands near.

    The centre of such a path, after travelling ``D``, lies in the fan of radius ``D`` and
    angles ``[low, high]`` (a path's displacement is a sum of steps along those headings, a
    convex cone when it spans less than pi; all the plane otherwise). The room is the largest
    ``D`` for which that fan, widened by ``radius``, keeps clear of every point: for a point
    at distance ``rho`` and angle ``delta`` outside the fan, ``rho cos(delta) -
    sqrt(radius^2 - rho^2 sin(delta)^2)`` where its perpendicular distance to the fan's edge
    is below ``radius``.

    >>> ahead = np.array([[2.0, 0.0]])
    >>> fan_room(ahead, 0.0, 0.0, 0.5)  # straight at it: 2 - 0.5
    1.5
    >>> fan_room(np.array([[0.0, 2.0]]), 0.0, 0.0, 0.5)  # abeam: never met going straight
    inf
    >>> round(fan_room(np.array([[0.0, 2.0]]), 0.0, math.pi / 2, 0.5), 12)  # turning to it
    1.5
    >>> round(fan_room(np.array([[2.0, 0.3]]), 0.0, 0.0, 0.5), 6)  # 2 - sqrt(0.25 - 0.09)
    1.6
    >>> fan_room(ahead, 0.0, 0.0, 0.5, margin=0.25), fan_room(ahead, 0.0, 0.0, 1.5, margin=1.2)
    (1.25, 0.5)
    >>> fan_room(np.array([[2.0, 0.6]]), 0.0, 0.0, 0.5, margin=0.25)  # beside: passed
    inf
    """
    if len(points) == 0:
        return math.inf
    rho = np.hypot(points[:, 0], points[:, 1])
    if high - low >= math.pi:
        delta = np.zeros_like(rho)
    else:
        phi = np.arctan2(points[:, 1], points[:, 0])
        past_high = np.mod(phi - high, 2 * math.pi)
        before_low = np.mod(low - phi, 2 * math.pi)
        inside = (phi >= low) & (phi <= high)
        delta = np.where(inside, 0.0, np.minimum(past_high, before_low))
    across = rho * np.sin(np.minimum(delta, math.pi / 2))
    along = rho * np.cos(delta)
    ahead = (across < radius) & (rho >= radius + margin / 2)
    kept = np.where(ahead, radius + margin, radius)
    reach = np.sqrt(np.maximum(kept**2 - across**2, 0.0))
    met = (delta < math.pi / 2) & (across < kept)
    room = np.where(met, along - reach, np.where(rho < kept, 0.0, np.inf))
    return max(0.0, float(room.min()))


def _fan(
    heading: float, observation: Observation, state: GovernorState, limits: Limits
) -> tuple[float, float]:
    """The robot-frame headings the robot may face until it stops: the present one (0), the
    command's, the last command's, and the present one turned on at the rate of the last
    period for its response time (at least a period): a robot that brakes while it turns may
    carry its turn past the command."""
    theta = observation.pose.theta
    turns = [0.0, wrap_angle(heading - theta)]
    if state.heading is not None:
        turns.append(wrap_angle(state.heading - theta))
    if state.theta is not None:
        carried = max(1.0, limits.response / limits.period)
        turns.append(wrap_angle(theta - state.theta) * carried)
    return min(turns), max(turns)


def _room(heading: float, observation: Observation, state: GovernorState, limits: Limits,
          margin: float = 0.0) -> float:  # fmt: skip
    """The room the robot of ``radius`` has to stop in when it turns towards ``heading``,
    keeping ``margin`` more (:func:`fan_room`): the fan's, and no farther than the sensor
    sees."""
    low, high = _fan(heading, observation, state, limits)
    scan = observation.scan
    radius = limits.radius
    room = fan_room(scan_points(scan).xy, low, high, radius, margin)
    return min(room, max(0.0, scan.range_max - radius - margin))


def next_state(state: GovernorState, heading: float, speed: float, limits: Limits,
               theta: float | None = None) -> GovernorState:  # fmt: skip
    """The governor's state one period after ``state`` when it let ``heading`` and ``speed``
    through with the robot at heading ``theta``: the speed bound after the response time
    towards the fastest command the robot may still follow and the rest of the period, if
    any, towards this one (up at ``A`` at most, never past the command; down at ``b`` at least
    until it reaches it).

    >>> limits = Limits(radius=0.2, top_speed=2.0, braking=4.0, acceleration=2.0, period=0.1)
    >>> next_state(GovernorState(), 0.0, 2.0, limits).speed_bound
    0.2
    >>> [next_state(GovernorState(1.0, 0.0, 1.0), 0.0, c, limits).speed_bound for c in (0, 0.9)]
    [0.6, 0.9]
    """
    eps = limits.period
    tau = min(limits.response, eps)
    bound = _ramp(state.speed_bound, state.following, tau, limits)[1]
    bound = _ramp(bound, speed, eps - tau, limits)[1]
    kept = math.ceil(limits.response / eps - 1e-9) - 1  # older commands still in effect
    earlier = (*state.earlier, state.speed)[-kept:] if kept > 0 else ()
    return GovernorState(bound, heading, min(speed, limits.top_speed), earlier, theta)


@traces("s3.safe_near_obstacles")
def govern(
    command: Command, observation: Observation, state: GovernorState, limits: Limits
) -> tuple[Command, GovernorState]:
    """``command`` as the robot may carry it out and stop in time, and the governor's next
    state (module docstring). A robot that stops at once, and a command that stops the
    episode, pass unchanged.

    >>> from ifgm_ref.core.laserscan import LaserScan
    >>> from ifgm_ref.core.pose import Point, Pose
    >>> limits = Limits(radius=0.2, top_speed=2.0, braking=4.0, acceleration=2.0, period=0.1)
    >>> wall = LaserScan(-0.1, 0.1, 0.1, 0.0, 10.0, [0.45, 0.45, 0.45])  # 0.2 of room ahead
    >>> seen = Observation(0.0, Pose(0.0, 0.0, 0.0), Point(5.0, 0.0), wall)
    >>> govern(Command(0.0, 2.0), seen, GovernorState(), limits)[0].speed  # from rest: A eps
    0.2
    >>> command, state = govern(Command(0.0, 2.0), seen, GovernorState(1.0, 0.0), limits)
    >>> round(command.speed, 4), round(state.speed_bound, 4)  # at 1.0: slow to what fits
    (0.9245, 0.9245)
    >>> moving = GovernorState(speed_bound=1.8, heading=0.0)  # too fast: brake, straight on
    >>> govern(Command(1.0, 2.0), seen, moving, limits)[0]
    Command(heading=0.0, speed=0.0, behaviour=None, branch=None, stop=None, turn_rate=None)
    """
    if limits.stops_at_once or command.stop is not None:
        return command, state
    bound = state.speed_bound
    heading = _within_grip(command.heading, observation.pose.theta, bound, limits)
    room = _room(heading, observation, state, limits, limits.radius * Limits.MARGIN)
    allowed = safe_speed(room, state, limits)
    if allowed is not None:
        speed = min(command.speed, allowed, bound + limits.acceleration * limits.period)
    else:  # brake along the last command's heading, whose fan the stop fits in; turn at rest
        speed = 0.0
        if stopping_distance(state, 0.0, limits) > 0.0 and state.heading is not None:
            heading = state.heading
    governed = _with(command, heading, speed, observation, limits)
    return governed, next_state(state, heading, speed, limits, observation.pose.theta)


def _within_grip(heading: float, theta: float, bound: float, limits: Limits) -> float:
    """``heading``, or the nearest one a robot at ``bound`` can turn to in a period without
    asking its tyres for more sideways than the braking ``b`` (``u w <= b``)."""
    if bound <= 0.0:
        return heading
    turn = limits.braking / bound * limits.period
    error = wrap_angle(heading - theta)
    return heading if abs(error) <= turn else wrap_angle(theta + math.copysign(turn, error))


def _with(
    command: Command, heading: float, speed: float, observation: Observation, limits: Limits
) -> Command:
    """``command`` with this heading and speed (a velocity command's turn rate follows its
    heading)."""
    if (heading, speed) == (command.heading, command.speed):
        return command
    if command.turn_rate is None or heading == command.heading:
        return replace(command, heading=heading, speed=speed)
    rate = wrap_angle(heading - observation.pose.theta) / limits.period
    return replace(command, heading=heading, speed=speed, turn_rate=rate)


def admissible(
    command: Command, observation: Observation, state: GovernorState, limits: Limits
) -> tuple[bool, float, float]:
    """Whether the robot can still stop after ``command`` (the runtime monitor of the
    oracle's ``stops_in_time``): its :func:`stopping_distance` fits in the fan of its turn,
    counted from the robot's disc (no margin), or it brakes (speed 0) along the last heading
    let through, whose stop the last step counted (Mitsch et al.'s braking branch; for a
    response time over a period the count from one step is coarser than the last step's).
    Standing, any turn fits (a disc turning in place sweeps nothing). Also the stopping
    distance and the room.
    """
    room = _room(command.heading, observation, state, limits)
    needed = stopping_distance(state, command.speed, limits)
    kept = state.heading is not None and abs(wrap_angle(command.heading - state.heading)) < 1e-9
    return needed <= room or (command.speed == 0.0 and kept), needed, room


class BrakingGovernor:
    """A planner's governor for one episode: :func:`govern` with its state kept.

    >>> from ifgm_ref.core.params import RobotParams
    >>> governor = BrakingGovernor()
    >>> governor.reset(EpisodeParams())  # the paper's robot stops at once: no change
    >>> governor.limits.stops_at_once
    True
    """

    def __init__(self) -> None:
        self.reset(EpisodeParams())

    def reset(self, params: EpisodeParams) -> None:
        """Start an episode: the robot's limits, at rest."""
        self.limits = Limits.of(params)
        self.state = GovernorState()

    def __call__(self, command: Command, observation: Observation) -> Command:
        """``command`` governed (:func:`govern`)."""
        command, self.state = govern(command, observation, self.state, self.limits)
        return command


class StopsAtOnce:
    """``planner`` told that the robot stops at once (infinite braking and acceleration, no
    response time), whatever the robot: its governor lets every command through, as the
    paper's planners are. For measuring what the governor changes on a robot with mass
    (``benchmarks/bench_ungoverned.py``, ``notebooks/06_physics.ipynb``).

    >>> from ifgm_ref.core.params import RobotParams
    >>> from ifgm_ref.planners import make_planner
    >>> planner = StopsAtOnce(make_planner("ifgm"))
    >>> heavy = EpisodeParams(robot=RobotParams(braking=1.0, acceleration=1.0, response=0.1))
    >>> planner.reset(Pose(0.0, 0.0, 0.0), Point(5.0, 0.0), heavy)
    >>> planner.name, planner.planner.governor.limits.stops_at_once
    ('ifgm', True)
    """

    def __init__(self, planner: Planner) -> None:
        self.planner, self.name = planner, planner.name

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start the episode as told, but with the paper's robot's dynamics."""
        robot = replace(params.robot, braking=math.inf, acceleration=math.inf, response=0.0)
        self.planner.reset(start, goal, replace(params, robot=robot))

    def step(self, observation: Observation) -> Command:
        """The planner's command."""
        return self.planner.step(observation)
