"""IFGM, the Intelligent Follow the Gap Method (section 4 and Figure 3 of the paper).

Every step the robot resolves its scan into obstacles (clusters of returns, "average
clustered value" as position, the nearest first), measures the gaps between consecutive
obstacles and computes the atoms of the flowchart (:mod:`ifgm_ref.flowchart`); the flowchart
alone picks the branch, and this module carries it out:

* *move to goal*: head for the goal along the regenerated reference path (eq. (3));
* *Case-1* (max gap > ``d_th``, nearest obstacle > ``d_obs``, obstacles on both sides):
  steer through the middle of the widest gap, eqs. (1)-(4);
* *Case-2* and *too close*: avoid with IBA (:class:`~ifgm_ref.planners.iba.IBAPlanner`),
  following the edge bidirectionally until a free path towards the goal appears -- or, after
  a lap without progress, Bug1's round: along the loop to its point nearest the goal, and
  leave there (:mod:`~ifgm_ref.planners.circuit`, errata row 34);
* *Case-3*: while avoiding, a nearer obstacle pre-empts the followed one; the followed one is
  pushed on a stack and resumed if it is met again (the recursion of section 4);
* *dead end* (inside a U or an H): turn in place in 45-degree steps, 45, 90, 135, 180 degrees,
  until the corridor ahead is free as far as the paper's sensor sees (``view_range``); go that
  way to the end of the wall (section 5.2), then follow the wall round from outside with IBA
  and regenerate the path.

The planner is composed, not inherited: it holds IBA's parts (an
:class:`~ifgm_ref.planners.boundary.EdgeFollower` and an :class:`~ifgm_ref.planners.iba.IBARule`)
and its own frozen state (:class:`~ifgm_ref.planners.ifgm_atoms.IFGMState`), whose
:class:`~ifgm_ref.planners.ifgm_atoms.Mode` changes only where a Figure 3 branch says so. The
atoms are a pure function of the step's percepts and the state
(:func:`~ifgm_ref.planners.ifgm_atoms.read`).

On a sensor wider than the paper's (a 270-degree LiDAR) Figure 3 reads the paper's 135-degree
view of the scan (:meth:`~ifgm_ref.laserscan.LaserScan.window`); the whole scan is remembered
for following edges (errata row 30).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import ClassVar

import numpy as np

from ifgm_ref.equations import eq1_gap_midpoint, eq2_gap_angle, eq4_final_heading
from ifgm_ref.errors import ParameterError, present
from ifgm_ref.flowchart import Atoms, Branch, decide
from ifgm_ref.laserscan import Beam, LaserScan
from ifgm_ref.paper import traces
from ifgm_ref.percepts.clusters import Gap, cluster_points, gaps_between
from ifgm_ref.percepts.corridor import free_length
from ifgm_ref.percepts.memory import PerceptMemory
from ifgm_ref.percepts.points import scan_points, to_world
from ifgm_ref.planners.boundary import EdgeFollower, keep_clear, steer
from ifgm_ref.planners.circuit import Circuit, CircuitPhase
from ifgm_ref.planners.distbug import DistBugParams
from ifgm_ref.planners.edge_following import FollowSide
from ifgm_ref.planners.iba import IBARule, freer_side
from ifgm_ref.planners.ifgm_atoms import (
    DeadEndTurn,
    IFGMParams,
    IFGMState,
    Mode,
    Percepts,
    read,
)
from ifgm_ref.planners.sight import Body, BoundaryParams, Sight, goal_bearing
from ifgm_ref.planners.tuning import Tuning, check_names, parameter_names
from ifgm_ref.pose import Point, Pose, distance, wrap_angle
from ifgm_ref.protocol import Behaviour, Command, EpisodeParams, Observation

__all__ = ["DEAD_END_MAX_STEPS", "DEAD_END_STEP", "IFGMParams", "IFGMPlanner"]

#: The dead-end rule's step, radians (section 4: "turns in steps of 45 degrees").
DEAD_END_STEP = math.pi / 4
#: At most four steps: 45, 90, 135 and 180 degrees ("until it finds obstacle free path (on
#: 180 degrees)").
DEAD_END_MAX_STEPS = 4


def nearest_remembered(sight: Sight, near: Point | None, jump: float) -> Point | None:
    """The remembered point nearest the robot; with ``near``, among those within ``jump`` of
    it (the same obstacle's edge, tracked as the robot moves along it)."""
    pts, d = sight.points, sight.point_distances
    if near is None:
        if len(d) == 0:
            return None
        i = int(d.argmin())
    else:
        (kept,) = (np.hypot(pts[:, 0] - near.x, pts[:, 1] - near.y) <= jump).nonzero()
        if len(kept) == 0:
            return None
        i = int(kept[d[kept].argmin()])
    return Point(float(pts[i, 0]), float(pts[i, 1]))


@traces("s3.critical_shapes", "s3.safe_near_obstacles")
class IFGMPlanner:
    """IFGM: FGM through wide gaps, IBA round the rest, 45-degree turns out of dead ends.

    What it holds is public for observers (traces, ``tests/test_flowchart_properties.py``):
    to be read, not written.

    Attributes
    ----------
    state : IFGMState
        The mode and what is carried from step to step.
    follower : EdgeFollower
        IBA's edge following: the side the followed edge is kept on, the hit point.
    iba : IBARule
        IBA's leaving rules and their ``d_min``.
    memory : PerceptMemory
        The obstacle points of the last ``memory_horizon`` seconds.
    ifgm : IFGMParams
        The thresholds and weights of this episode.
    last_atoms : Atoms or None
        The flowchart atoms computed at the last step, before it acted on them.
    last_branch : Branch or None
        The branch :func:`~ifgm_ref.flowchart.decide` chose for ``last_atoms``.
    last_gap : Gap or None
        The gap chosen at the last step: the maximum gap, or the one steered through at the
        step before while it stays wider than ``d_th`` (errata row 19).
    """

    name: ClassVar[str] = "ifgm"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (IFGMParams, BoundaryParams, DistBugParams)
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self) -> None:
        self.iba = IBARule()
        self.circuit = Circuit()
        self.last_atoms: Atoms | None = None
        self.last_branch: Branch | None = None
        self.last_gap: Gap | None = None
        self.reset(Pose(0.0, 0.0, 0.0), Point(0.0, 0.0), EpisodeParams())  # until reset

    # -- read-only views for observers ------------------------------------------------------
    @property
    def goal(self) -> Point:
        """The destination."""
        return self.body.goal

    @property
    def d_th(self) -> float:
        """The gap threshold of this episode."""
        return self.ifgm.d_th

    @property
    def d_obs(self) -> float:
        """The nearest-obstacle threshold of this episode."""
        return self.ifgm.d_obs

    @property
    def following(self) -> bool:
        """IBA is following an edge (:attr:`IFGMState.following`)."""
        return self.state.following

    @property
    def turning(self) -> bool:
        """A dead-end turn is under way (:attr:`IFGMState.turning`)."""
        return self.state.turning

    @property
    def short_look(self) -> bool:
        """Meeting obstacles at IBA's short encounter distance, Case-1 off (errata row 24)."""
        return self.state.short_look

    @property
    def side(self) -> FollowSide:
        """The side the followed edge is kept on (IBA's freer side, section 4.1)."""
        return self.follower.side

    @property
    def followed(self) -> Point | None:
        """The followed obstacle's point, world frame."""
        return self.state.followed

    @property
    def stack(self) -> tuple[tuple[Point, FollowSide], ...]:
        """Case-3: the pre-empted obstacles and their sides, the last pushed resumed first."""
        return self.state.stack

    # -- protocol ---------------------------------------------------------------------------
    @traces("d_th", "d_obs")
    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start in *move to goal*; derive and validate the thresholds."""
        check_names(params.params, self.parameters, self.name)
        tuning = BoundaryParams.for_episode(params)
        self.body = Body.of(goal, params, tuning)
        self.memory = PerceptMemory(tuning.memory_horizon)
        self.follower = EdgeFollower()
        self.follower.reset()
        self.iba.reset(start, goal, params)
        self.circuit.reset()
        p = IFGMParams.for_episode(params)
        r = params.robot.radius
        if p.d_th <= 2.0 * r:
            raise ParameterError(
                f"`d_th` must be > the robot diameter {2.0 * r!r} (section 4), got {p.d_th!r}"
            )
        self.ifgm = p
        sensor = params.sensor
        try:  # the flowchart reads the paper's 135-degree view of the scan
            LaserScan(
                -sensor.fov / 2, sensor.fov / 2, sensor.angle_increment, 0.0, 1.0,
                np.full(sensor.rays, math.inf),
            ).window()  # fmt: skip
        except ValueError as err:
            raise ParameterError(f"IFGM reads the paper's 135-degree view: {err}") from None
        # The goal is reached during this step when it is within the episode's tolerance plus
        # one step of travel: the robot then drives straight onto it.
        self.goal_tolerance = params.goal_tolerance + params.robot.speed * params.dt
        self.state = IFGMState()
        self.last_branch = None
        self.last_atoms = None
        self.last_gap = None

    def step(self, observation: Observation) -> Command:
        """Perceive, decide (:meth:`carry_out`), then never drive into a remembered obstacle
        (the clearance filter)."""
        percepts = self.perceive(observation)
        return keep_clear(self.carry_out(percepts), percepts.sight)

    def act(self, observation: Observation) -> Command:
        """IFGM's decision for ``observation`` before the clearance filter: :meth:`perceive`, then
        :meth:`carry_out`."""
        return self.carry_out(self.perceive(observation))

    def goal_bearing(self, pose: Pose) -> float:
        """The destination angle theta_d of eq. (3), world frame (:func:`goal_bearing`)."""
        return goal_bearing(pose, self.body.goal)

    # -- percepts ---------------------------------------------------------------------------
    def perceive(self, observation: Observation) -> Percepts:
        """Remember the scan and compute this step's percepts, each once.

        The whole field of view is remembered, for edge following; Figure 3 reads the paper's
        view, 135 degrees and ``view_range`` deep (the scan itself for the paper's sensor).
        While following, the followed point is tracked along its edge and IBA notes the
        distance to the goal before its leaving rules are asked."""
        pose, view_range = observation.pose, self.body.tuning.view_range
        scan = observation.scan.limited(view_range)
        points = scan_points(scan)
        self.memory.add_points(observation.t, to_world(points.xy, pose))
        view = observation.scan.window().limited(view_range)
        clusters = cluster_points(points if view is scan else scan_points(view), self.ifgm.jump)
        sight = Sight(pose, self.body, self.memory.points, self.goal_bearing(pose))
        self.circuit.note(sight, following=self.state.following)
        may_leave = False
        if self.state.following:
            tracked = self._track(sight, self.state.followed)
            if tracked != self.state.followed:
                self.state = replace(self.state, followed=tracked)
            self.iba.note(sight)
            may_leave = self.may_leave(sight)
        return Percepts(
            sight, view, clusters, gaps_between(clusters), may_leave, self.ifgm, self.goal_tolerance
        )

    def _track(self, sight: Sight, followed: Point | None) -> Point | None:
        """The followed point, moved along its edge: the remembered point nearest the robot
        within ``jump`` of it, or else the nearest of all."""
        jump = self.ifgm.jump
        tracked = nearest_remembered(sight, followed, jump) if followed else None
        return tracked or nearest_remembered(sight, None, jump)

    def may_leave(self, sight: Sight) -> bool:
        """IBA's leaving rules (errata row 24): a free path, or DistBug's progress rule --
        but not while following the wall round from outside after a dead end, where the
        progress rule would lead straight back into the U or H (``tests/worlds/small_u``).
        Beside them, Bug1's round (:mod:`~ifgm_ref.planners.circuit`, errata row 34): one
        round from the first obstacle met until the robot leaves at a Q, its trail laid in
        every mode, so that it also closes when IFGM leaves an edge by IBA's rules, meets the
        same obstacles again and goes the same way round (a lap without progress); once the
        loop closes, only Q is left from: along the loop to the point Q nearest the goal, and
        leave there. IFGM has no "goal unreachable": a loop that shows the goal cannot be
        reached is left at its Q all the same."""
        circuit = self.circuit
        if circuit.returning:
            if not circuit.at_q(sight):
                return False
            circuit.leave()
            return True
        if (back_at := circuit.closing(sight)) is not None:
            side = self.follower.side
            if not circuit.close(sight, back_at, side):  # no way on this way round
                other = FollowSide.LEFT if side is FollowSide.RIGHT else FollowSide.RIGHT
                self.state = replace(self.state, turn_other_way=other)
            return False
        return self.iba.leaves(sight, by_progress=not self.state.escaped)

    # -- the planner ------------------------------------------------------------------------
    @traces("fig3.move_to_goal", "fig3.regenerate", "fig3.case2", "fig3.case3")
    def carry_out(self, percepts: Percepts) -> Command:
        """Decide with Figure 3, then act on the branch."""
        reading = read(percepts, self.state)
        state = self.state
        if (reading.gap_mid, reading.short_look) != (state.gap_mid, state.short_look):
            self.state = replace(state, gap_mid=reading.gap_mid, short_look=reading.short_look)
        self.last_atoms, self.last_gap = reading.atoms, reading.gap
        branch = self.last_branch = decide(reading.atoms)
        sight = percepts.sight
        pose = sight.pose
        if branch is Branch.GOAL_REACHED:
            speed = min(self.body.speed, sight.goal_distance / self.body.dt)
            return Command(sight.bearing, speed, behaviour=Behaviour.MOVE_TO_GOAL, branch=branch)
        if branch is Branch.MOVE_TO_GOAL:
            if self.state.mode is not Mode.MOVE_TO_GOAL:
                self.state = replace(self.state, mode=Mode.MOVE_TO_GOAL)
            return steer(sight.bearing, pose, self.body, Behaviour.MOVE_TO_GOAL, branch)
        if branch is Branch.PATH_REGENERATED:
            # Left by the progress rule, with an obstacle still ahead: meet it at IBA's short
            # encounter distance, not d_look (the followed one is still the nearest, and at
            # d_look the robot would go back to following it: tests/worlds/two_posts_in_line).
            at_q = self.circuit.phase is CircuitPhase.LEFT_AT_Q
            self.state = replace(
                self.state,
                mode=Mode.MOVE_TO_GOAL,
                short_look=at_q or not sight.path_free(),
                escaped=False,
                followed=None,
                stack=(),
            )
            return steer(sight.bearing, pose, self.body, Behaviour.MOVE_TO_GOAL, branch)
        if branch is Branch.CASE1_GAP:
            self.state = replace(self.state, mode=Mode.THROUGH_GAP)
            heading = self.gap_heading(pose, present(reading.gap, "the gap Case-1 steers through"))
            return steer(heading, pose, self.body, Behaviour.OBSTACLE_AVOIDANCE, branch)
        if branch is Branch.DEAD_END_TURN:
            return self.dead_end(percepts)
        if branch is Branch.CASE3_PREEMPT:
            followed = present(self.state.followed, "the edge Case-3 pre-empts")
            stack = (*self.state.stack, (followed, self.follower.side))
            preemptor = present(reading.preemptor, "Case-3's obstacle of most impact")
            self.state = replace(self.state, stack=stack, followed=preemptor)
            self.follower.side = freer_side(percepts.view, pose, sight.bearing)
        elif branch is Branch.FOLLOW_EDGE:
            self._resume_if_back(sight)
        else:  # Case-2 (narrow gap, one-sided) or too close: IBA takes over
            self._start_following(percepts)
        return self._follow(sight, branch)

    @traces("fig3.case1", "eq1", "eq2", "eq3", "eq4")
    def gap_heading(self, pose: Pose, gap: Gap) -> float:
        """Case-1: the final heading through ``gap`` by eqs. (1)-(4), world frame."""
        x_g, y_g = eq1_gap_midpoint(gap.right, gap.left)
        theta_g = pose.theta + eq2_gap_angle(x_g, y_g)
        theta_d = self.goal_bearing(pose)
        return eq4_final_heading(
            theta_g,
            theta_d,
            w_g=self.ifgm.w_g,
            w_d=self.ifgm.w_d,
            d_th=self.ifgm.d_th,
            heading=pose.theta,
        )

    def _start_following(self, percepts: Percepts) -> None:
        """IBA takes over: follow the nearest obstacle on the freer side, nothing pre-empted."""
        sight = percepts.sight
        side = self.state.turn_other_way or freer_side(percepts.view, sight.pose, sight.bearing)
        self.follower.start(sight.pose.position, side)
        self.iba.on_hit(sight, self.follower)
        if self.circuit.phase is not CircuitPhase.FIRST_PASS:
            self.circuit.on_hit()
        self.state = replace(
            self.state,
            mode=Mode.FOLLOWING,
            turn=None,
            short_look=False,
            escaped=False,
            followed=nearest_remembered(sight, None, self.ifgm.jump),
            stack=(),
            turn_other_way=None,
        )

    def _follow(self, sight: Sight, branch: Branch) -> Command:
        """Follow the edge with IBA -- after a whole loop, retrace it to Q (Bug1's round,
        errata row 34); if the edge is forgotten, head for the goal instead."""
        circuit = self.circuit
        heading = circuit.heading_to_q(sight) if circuit.returning else self.follower.heading(sight)
        if heading is None:  # the edge is forgotten: the obstacle is behind us
            self.state = replace(self.state, mode=Mode.MOVE_TO_GOAL)
            return steer(sight.bearing, sight.pose, self.body, Behaviour.MOVE_TO_GOAL, branch)
        return steer(heading, sight.pose, self.body, Behaviour.OBSTACLE_AVOIDANCE, branch)

    def _resume_if_back(self, sight: Sight) -> None:
        """Case-3 recursion: once the pre-empting obstacle is no longer the nearest, resume
        avoiding the one it interrupted, on the side it was followed on."""
        state = self.state
        nearest = nearest_remembered(sight, None, self.ifgm.jump)
        if (
            state.stack
            and nearest is not None
            and state.followed is not None
            and distance(nearest, state.followed) > self.ifgm.jump
        ):
            _, self.follower.side = state.stack[-1]
            self.state = replace(state, stack=state.stack[:-1], followed=nearest)

    @traces("fig3.dead_end", "s5.ifgm_u_h")
    def dead_end(self, percepts: Percepts) -> Command:
        """Turn in 45-degree steps until the way ahead is free; then go that way."""
        sight = percepts.sight
        pose = sight.pose
        turn = self.state.turn
        if turn is None:  # entering the dead end: turn towards the freer beam
            side = freer_side(percepts.view, pose, sight.bearing)
            turn = DeadEndTurn(pose.theta, 1 if side is FollowSide.RIGHT else -1, 1)
            self.state = replace(self.state, mode=Mode.DEAD_END_TURN, turn=turn)
        target = wrap_angle(turn.start + turn.sign * turn.steps * DEAD_END_STEP)
        turning = turn.escape_from is None
        if turning and abs(wrap_angle(pose.theta - target)) > self.ifgm.turn_done:
            return self._turn_command(target)
        ahead = free_length(sight.points, (pose.x, pose.y), pose.theta, self.body.half_width)
        if turning:
            if ahead < self.body.tuning.view_range and turn.steps < DEAD_END_MAX_STEPS:
                turn = replace(turn, steps=turn.steps + 1)
                self.state = replace(self.state, turn=turn)
                return self._turn_command(
                    wrap_angle(turn.start + turn.sign * turn.steps * DEAD_END_STEP)
                )
            turn = replace(turn, escape_from=pose.position)  # free (or 180 degrees): go
            self.state = replace(self.state, mode=Mode.ESCAPING, turn=turn)
        escape_from = present(turn.escape_from, "where the escape from the dead end began")
        walls = self.side_walls(percepts.view)
        walled = (turn.walled[0] or walls[0], turn.walled[1] or walls[1])
        wall_ended = any(seen and not now for seen, now in zip(walled, walls, strict=True))
        if walled != turn.walled:
            self.state = replace(self.state, turn=replace(turn, walled=walled))
        if (
            distance(pose, escape_from) < self.ifgm.d_look
            and ahead > self.body.encounter
            and not wall_ended
        ):
            return Command(
                target,
                self.body.speed,
                behaviour=Behaviour.OBSTACLE_AVOIDANCE,
                branch=Branch.DEAD_END_TURN,
            )
        # Escaped: follow the nearest wall round from outside (IBA), then regenerate the path.
        self._start_following(percepts)
        self.state = replace(self.state, escaped=True)
        followed = nearest_remembered(sight, None, self.ifgm.jump)
        if followed is not None:
            rel = wrap_angle(math.atan2(followed.y - pose.y, followed.x - pose.x) - pose.theta)
            self.follower.side = FollowSide.LEFT if rel > 0.0 else FollowSide.RIGHT
        return self._follow(sight, Branch.DEAD_END_TURN)

    def side_walls(self, view: LaserScan) -> tuple[bool, bool]:
        """Whether the left and the right beam of the view have a return within ``d_look``.

        Section 5.2: driving out of a dead end, the robot "detects the side wall in 135
        degrees FOV and finds the clear path in respective direction after reaching to the
        end of wall". We read: the escape ends where a side beam that has seen a wall since
        the robot started driving out sees none within ``d_look`` (errata row 34); the
        robot then follows the wall it has passed the end of. Driving on to ``d_look``, it
        could meet another obstacle first, follow that one, and come back into the dead end
        for ever (``tests/worlds/rigid_motion_long_mixed.json``)."""
        d_look = self.ifgm.d_look
        return (
            bool((view.ranges[view.beam_mask(Beam.LEFT)] <= d_look).any()),
            bool((view.ranges[view.beam_mask(Beam.RIGHT)] <= d_look).any()),
        )

    def _turn_command(self, target: float) -> Command:
        return Command(
            target, 0.0, behaviour=Behaviour.OBSTACLE_AVOIDANCE, branch=Branch.DEAD_END_TURN
        )
