"""IFGM, the Intelligent Follow the Gap Method (section 4 and Figure 3 of the paper).

Every step the robot resolves its scan into obstacles (clusters of returns, "average
clustered value" as position, the nearest first), measures the gaps between consecutive
obstacles and computes the atoms of the flowchart (:mod:`ifgm_ref.paper.flowchart`); the flowchart
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
  and regenerate the path. Each phase is labelled in the trace: ``dead_end_turn``,
  ``dead_end_escape``, ``dead_end_handover`` (errata row 35).

A step is four parts, and the state (:class:`~ifgm_ref.planners.ifgm.atoms.IFGMState`, one
immutable record) is written in one place, :meth:`IFGMPlanner._decide`:
:meth:`~IFGMPlanner.perceive` (the percepts, and the state as they update it), the atoms
(:func:`~ifgm_ref.planners.ifgm.atoms.read_atoms`, pure), the branch
(:func:`~ifgm_ref.paper.flowchart.decide`), and :meth:`~IFGMPlanner.transition`, one ``match``
over the branch that returns the next state and the command (``docs/ifgm-state.md``).

On a sensor wider than the paper's (a 270-degree LiDAR) Figure 3 reads the paper's 135-degree
view of the scan (:meth:`~ifgm_ref.core.laserscan.LaserScan.window`); the whole scan is remembered
for following edges (errata row 30).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import ClassVar

import numpy as np

from ifgm_ref.core.elements import traces
from ifgm_ref.core.errors import ParameterError, present
from ifgm_ref.core.laserscan import Beam, LaserScan
from ifgm_ref.core.pose import Point, Pose, distance, wrap_angle
from ifgm_ref.core.protocol import Behaviour, Command, EpisodeParams, Observation
from ifgm_ref.paper.equations import eq1_gap_midpoint, eq2_gap_angle, eq4_final_heading
from ifgm_ref.paper.flowchart import DEAD_END_STEP, Atoms, Branch, decide
from ifgm_ref.paper.percepts.clusters import Gap, cluster_points, gaps_between
from ifgm_ref.paper.percepts.corridor import free_length
from ifgm_ref.paper.percepts.memory import PerceptMemory
from ifgm_ref.paper.percepts.points import scan_points, to_world
from ifgm_ref.planners.boundary import edge_heading, keep_clear, steer
from ifgm_ref.planners.circuit import Circuit, CircuitPhase
from ifgm_ref.planners.distbug import DistBugParams
from ifgm_ref.planners.edge_following import FollowSide
from ifgm_ref.planners.governor import BrakingGovernor
from ifgm_ref.planners.iba import freer_side, leaves, yardstick_at_hit
from ifgm_ref.planners.ifgm.atoms import (
    DeadEndTurn,
    IFGMParams,
    IFGMState,
    Mode,
    StepAtoms,
    StepInputs,
    read_atoms,
)
from ifgm_ref.planners.ifgm.readings import DeadEndSide, LeavingRule, Readings
from ifgm_ref.planners.sight import BoundaryParams, Episode, Sight, goal_bearing
from ifgm_ref.planners.tuning import Tuning, check_names, parameter_names

__all__ = ["DEAD_END_MAX_STEPS", "DEAD_END_STEP", "IFGMParams", "IFGMPlanner"]

#: The two behaviours a command reports (section 2.1).
TO_GOAL, AVOIDING = Behaviour.MOVE_TO_GOAL, Behaviour.OBSTACLE_AVOIDANCE
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

    Parameters
    ----------
    readings : Readings or None
        The readings of the paper's open choices to run (:mod:`ifgm_ref.planners.ifgm.readings`);
        ``None``: ours, as the errata table records them.

    Attributes
    ----------
    state : IFGMState
        Everything carried from step to step.
    memory : PerceptMemory
        The obstacle points of the last ``memory_horizon`` seconds (a handle the state
        leaves out: a growing log).
    ifgm : IFGMParams
        The thresholds and weights of this episode.
    last_branch : Branch or None
        The branch :func:`~ifgm_ref.paper.flowchart.decide` chose for ``last_atoms``.
    last_seen : (StepInputs, IFGMState, StepAtoms) or None
        The last step's percepts, the state they were read in, and what
        :func:`~ifgm_ref.planners.ifgm.atoms.read_atoms` made of them
        (:func:`~ifgm_ref.planners.ifgm.margins.margins` measures its ties).
    """

    name: ClassVar[str] = "ifgm"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (IFGMParams, BoundaryParams, DistBugParams)
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self, readings: Readings | None = None) -> None:
        self.readings = Readings() if readings is None else readings
        self.governor = BrakingGovernor()
        self.last_branch: Branch | None = None
        self.last_seen: tuple[StepInputs, IFGMState, StepAtoms] | None = None
        self.reset(Pose(0.0, 0.0, 0.0), Point(0.0, 0.0), EpisodeParams())  # until reset

    # -- read-only views for observers ------------------------------------------------------
    @property
    def last_atoms(self) -> Atoms | None:
        """The flowchart atoms computed at the last step, before it acted on them."""
        return None if self.last_seen is None else self.last_seen[2].atoms

    @property
    def last_gap(self) -> Gap | None:
        """The gap chosen at the last step: the maximum gap, or the one steered through at the
        step before while it stays wider than ``d_th`` (errata row 19)."""
        return None if self.last_seen is None else self.last_seen[2].gap

    @property
    def goal(self) -> Point:
        """The destination."""
        return self.episode.goal

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
        return self.state.side

    @property
    def followed(self) -> Point | None:
        """The followed obstacle's point, world frame."""
        return self.state.followed

    @property
    def circuit(self) -> Circuit:
        """Bug1's round (:attr:`IFGMState.circuit`)."""
        return self.state.circuit

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
        self.episode = Episode.of(goal, params, tuning)
        self.memory = PerceptMemory(tuning.memory_horizon, params.dt)
        self.step_length = DistBugParams.for_episode(params).step_length
        self.governor.reset(params)
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
        self.last_seen = None

    def step(self, observation: Observation) -> Command:
        """Decide (:meth:`advance`), then never drive into a remembered obstacle (the clearance
        filter, :func:`~ifgm_ref.planners.boundary.keep_clear`), and stop in time (the braking
        governor, :mod:`~ifgm_ref.planners.governor`)."""
        command, percepts = self._decide(observation)
        return self.governor(keep_clear(command, percepts.sight), observation)

    def advance(self, observation: Observation) -> Command:
        """Advance the state one step on ``observation``; IFGM's command before the clearance
        filter."""
        return self._decide(observation)[0]

    def _decide(self, observation: Observation) -> tuple[Command, StepInputs]:
        """One step: perceive, read the atoms, let Figure 3 pick the branch, carry it out.
        The only place the state is written after :meth:`reset`."""
        read_in, percepts = self.perceive(self.state, observation)
        step_atoms = read_atoms(percepts, read_in)
        branch = decide(step_atoms.atoms)
        state, command = self.transition(read_in, percepts, step_atoms, branch)
        self.state, self.last_branch, self.last_seen = (
            state,
            branch,
            (percepts, read_in, step_atoms),
        )
        return command, percepts

    def goal_bearing(self, pose: Pose) -> float:
        """The destination angle theta_d of eq. (3), world frame (:func:`goal_bearing`)."""
        return goal_bearing(pose, self.episode.goal)

    # -- percepts ---------------------------------------------------------------------------
    def perceive(self, state: IFGMState, observation: Observation) -> tuple[IFGMState, StepInputs]:
        """This step's percepts, each computed once, and ``state`` as they update it.

        The whole field of view is remembered, for edge following; Figure 3 reads the paper's
        view, 135 degrees and ``view_range`` deep (the scan itself for the paper's sensor).
        While following, the followed point is tracked along its edge, ``d_min`` notes the
        distance to the goal, and Bug1's round and IBA's leaving rules are asked
        (:meth:`advance_round`)."""
        pose, view_range = observation.pose, self.episode.tuning.view_range
        scan = observation.scan.limited(view_range)
        points = scan_points(scan)
        self.memory.add_points(observation.t, to_world(points.xy, pose))
        view = observation.scan.window().limited(view_range)
        clusters = cluster_points(points if view is scan else scan_points(view), self.ifgm.jump)
        sight = Sight(pose, self.episode, self.memory.points, self.goal_bearing(pose))
        state = replace(state, circuit=state.circuit.noted(sight, following=state.following))
        may_leave = False
        if state.following:
            followed = self._track(sight, state.followed)
            state = replace(state, followed=followed, d_min=min(state.d_min, sight.goal_distance))
            state, may_leave = self.advance_round(state, sight)
        gaps = gaps_between(clusters, reading=self.readings.gap_points)
        percepts = StepInputs(
            sight, view, clusters, gaps, may_leave, self.ifgm, self.goal_tolerance, self.readings,
            self.step_length,
        )  # fmt: skip
        return state, percepts

    def _track(self, sight: Sight, followed: Point | None) -> Point | None:
        """The followed point, moved along its edge: the remembered point nearest the robot
        within ``jump`` of it, or else the nearest of all."""
        jump = self.ifgm.jump
        tracked = nearest_remembered(sight, followed, jump) if followed else None
        return tracked or nearest_remembered(sight, None, jump)

    def advance_round(self, state: IFGMState, sight: Sight) -> tuple[IFGMState, bool]:
        """``state`` with Bug1's round advanced by this step of following, and whether to
        leave the edge: by IBA's rules, a free path or, unless ``escaped``, DistBug's
        progress (errata row 24); once the round has closed its loop, only at Q (errata row
        34). A loop closed with no way on sets ``turn_other_way`` (IFGM has no "goal
        unreachable": it leaves at that Q all the same)."""
        circuit = state.circuit
        if circuit.returning:
            if not circuit.at_q(sight):
                return state, False
            return replace(state, circuit=circuit.left_at_q()), True
        if (back_at := circuit.closing(sight)) is not None:
            circuit, way_on = circuit.closed(sight, back_at, state.side)
            other = FollowSide.LEFT if state.side is FollowSide.RIGHT else FollowSide.RIGHT
            turn_other_way = state.turn_other_way if way_on else other
            return replace(state, circuit=circuit, turn_other_way=turn_other_way), False
        by_progress = (
            not state.escaped and self.readings.leaving_rule is LeavingRule.FREE_PATH_OR_PROGRESS
        )
        return state, leaves(sight, state.d_min, self.step_length, by_progress=by_progress)

    # -- the planner ------------------------------------------------------------------------
    @traces("fig3.move_to_goal", "fig3.regenerate", "fig3.case2", "fig3.case3")
    def transition(
        self, state: IFGMState, percepts: StepInputs, step_atoms: StepAtoms, branch: Branch
    ) -> tuple[IFGMState, Command]:
        """Carry out Figure 3's ``branch``: the next state, which keeps the gap chosen and
        the look of ``step_atoms``, and this step's command."""
        if (step_atoms.gap_mid, step_atoms.short_look) != (state.gap_mid, state.short_look):
            state = replace(state, gap_mid=step_atoms.gap_mid, short_look=step_atoms.short_look)
        sight = percepts.sight
        pose, bearing = sight.pose, sight.bearing
        match branch:
            case Branch.GOAL_REACHED:
                speed = min(self.episode.speed, sight.goal_distance / self.episode.dt)
                return state, Command(bearing, speed, behaviour=TO_GOAL, branch=branch)
            case Branch.MOVE_TO_GOAL:
                if state.mode is not Mode.MOVE_TO_GOAL:
                    state = replace(state, mode=Mode.MOVE_TO_GOAL)
                return state, steer(bearing, pose, self.episode, TO_GOAL, branch)
            case Branch.PATH_REGENERATED:
                # Left by the progress rule, with an obstacle still ahead: meet it at IBA's
                # short encounter distance, not d_look (the followed one is still the nearest,
                # and at d_look the robot would go back to following it:
                # tests/worlds/two_posts_in_line).
                at_q = state.circuit.phase is CircuitPhase.LEFT_AT_Q
                short_look = at_q or not sight.path_free()
                state = replace(
                    state, mode=Mode.MOVE_TO_GOAL, short_look=short_look, escaped=False,
                    followed=None, stack=(),
                )  # fmt: skip
                return state, steer(bearing, pose, self.episode, TO_GOAL, branch)
            case Branch.CASE1_GAP:
                gap = present(step_atoms.gap, "the gap Case-1 steers through")
                heading = self.gap_heading(pose, gap)
                state = replace(state, mode=Mode.THROUGH_GAP)
                return state, steer(heading, pose, self.episode, AVOIDING, branch)
            case Branch.DEAD_END_TURN:
                return self.dead_end(state, percepts)
            case Branch.CASE3_PREEMPT:  # a nearer obstacle first; the followed one waits
                followed = present(state.followed, "the edge Case-3 pre-empts")
                state = replace(
                    state,
                    stack=(*state.stack, (followed, state.side)),
                    followed=present(step_atoms.preemptor, "Case-3's obstacle of most impact"),
                    side=freer_side(percepts.view, pose, bearing),
                )
            case Branch.FOLLOW_EDGE:
                state = self._resume_if_back(state, sight)
            case _:  # Case-2 (narrow gap, one-sided) or too close: IBA takes over
                state = self._start_following(state, percepts)
        return self._follow(state, sight, branch)

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

    def _start_following(self, state: IFGMState, percepts: StepInputs) -> IFGMState:
        """IBA takes over: follow the nearest obstacle on the freer side (or the side a round
        of Bug1's left for it), nothing pre-empted; ``d_min`` counts the hit point."""
        sight = percepts.sight
        side = state.turn_other_way or freer_side(percepts.view, sight.pose, sight.bearing)
        d_min = yardstick_at_hit(state.d_min, sight.pose.position, sight.episode.goal)
        circuit = state.circuit
        return replace(
            state,
            mode=Mode.FOLLOWING,
            turn=None,
            short_look=False,
            escaped=False,
            followed=nearest_remembered(sight, None, self.ifgm.jump),
            side=side,
            stack=(),
            turn_other_way=None,
            d_min=d_min,
            circuit=circuit if circuit.phase is CircuitPhase.FIRST_PASS else circuit.hit(),
        )

    def _follow(self, state: IFGMState, sight: Sight, branch: Branch) -> tuple[IFGMState, Command]:
        """Follow the edge with IBA -- after a whole loop, retrace it to Q (Bug1's round,
        errata row 34); if the edge is forgotten, head for the goal instead."""
        if state.circuit.returning:
            state = replace(state, circuit=state.circuit.advanced(sight))
            heading: float | None = state.circuit.heading_to_q(sight)
        else:
            heading = edge_heading(sight, state.side)
        if heading is None:  # the edge is forgotten: the obstacle is behind us
            state = replace(state, mode=Mode.MOVE_TO_GOAL)
            return state, steer(sight.bearing, sight.pose, self.episode, TO_GOAL, branch)
        return state, steer(heading, sight.pose, self.episode, AVOIDING, branch)

    def _resume_if_back(self, state: IFGMState, sight: Sight) -> IFGMState:
        """Case-3 recursion: once the pre-empting obstacle is no longer the nearest, resume
        avoiding the one it interrupted, on the side it was followed on."""
        nearest = nearest_remembered(sight, None, self.ifgm.jump)
        if (
            state.stack
            and nearest is not None
            and state.followed is not None
            and distance(nearest, state.followed) > self.ifgm.jump
        ):
            _, side = state.stack[-1]
            return replace(state, stack=state.stack[:-1], followed=nearest, side=side)
        return state

    @traces("fig3.dead_end", "s5.ifgm_u_h")
    def dead_end(self, state: IFGMState, percepts: StepInputs) -> tuple[IFGMState, Command]:
        """Figure 3's dead end, in its three phases (each its own label): turn in 45-degree
        steps until the way ahead is free (``dead_end_turn``); go that way to the end of the
        wall (``dead_end_escape``); then hand over to IBA, following the wall round from
        outside (``dead_end_handover``)."""
        sight = percepts.sight
        pose = sight.pose
        turn = state.turn
        if turn is None:  # entering the dead end: turn towards the freer beam (errata row 17)
            turn = DeadEndTurn(pose.theta, self._dead_end_sign(percepts), 1)
            state = replace(state, mode=Mode.DEAD_END_TURN, turn=turn)
        target = wrap_angle(turn.start + turn.sign * turn.steps * DEAD_END_STEP)
        turning = turn.escape_from is None
        if turning and abs(wrap_angle(pose.theta - target)) > self.ifgm.turn_done:
            return state, self._turn_command(target)
        ahead = free_length(sight.points, (pose.x, pose.y), pose.theta, self.episode.half_width)
        if turning:
            if ahead < self.episode.tuning.view_range and turn.steps < DEAD_END_MAX_STEPS:
                turn = replace(turn, steps=turn.steps + 1)
                target = wrap_angle(turn.start + turn.sign * turn.steps * DEAD_END_STEP)
                return replace(state, turn=turn), self._turn_command(target)
            turn = replace(turn, escape_from=pose.position)  # free (or 180 degrees): go
            state = replace(state, mode=Mode.ESCAPING, turn=turn)
        escape_from = present(turn.escape_from, "where the escape from the dead end began")
        walls = self.side_walls(percepts.view)
        walled = (turn.walled[0] or walls[0], turn.walled[1] or walls[1])
        wall_ended = any(seen and not now for seen, now in zip(walled, walls, strict=True))
        if walled != turn.walled:
            state = replace(state, turn=replace(turn, walled=walled))
        if (
            distance(pose, escape_from) < self.ifgm.d_look
            and ahead > self.episode.encounter
            and not wall_ended
        ):
            return state, Command(
                target, self.episode.speed, behaviour=AVOIDING, branch=Branch.DEAD_END_ESCAPE
            )
        # Escaped: follow the nearest wall round from outside (IBA), then regenerate the path.
        state = replace(self._start_following(state, percepts), escaped=True)
        followed = nearest_remembered(sight, None, self.ifgm.jump)
        if followed is not None:
            rel = wrap_angle(math.atan2(followed.y - pose.y, followed.x - pose.x) - pose.theta)
            state = replace(state, side=FollowSide.LEFT if rel > 0.0 else FollowSide.RIGHT)
        return self._follow(state, sight, Branch.DEAD_END_HANDOVER)

    def _dead_end_sign(self, percepts: StepInputs) -> int:
        """The way the dead end turns, +1 counter-clockwise: :attr:`Readings.dead_end_side`,
        by default towards the freer side beam (keeping the wall on the right, turning left)."""
        way = self.readings.dead_end_side
        if way is DeadEndSide.FREER:
            sight = percepts.sight
            keep = freer_side(percepts.view, sight.pose, sight.bearing)
            return 1 if keep is FollowSide.RIGHT else -1
        return 1 if way is DeadEndSide.LEFT else -1

    def side_walls(self, view: LaserScan) -> tuple[bool, bool]:
        """Whether the left and the right beam of the view have a return within ``d_look``:
        the dead-end escape ends where a side beam that has seen a wall sees none, "after
        reaching to the end of wall" (section 5.2; errata row 34)."""
        d_look = self.ifgm.d_look
        return (
            bool((view.ranges[view.beam_mask(Beam.LEFT)] <= d_look).any()),
            bool((view.ranges[view.beam_mask(Beam.RIGHT)] <= d_look).any()),
        )

    def _turn_command(self, target: float) -> Command:
        return Command(target, 0.0, behaviour=AVOIDING, branch=Branch.DEAD_END_TURN)
