"""IFGM, the Intelligent Follow the Gap Method (section 4 and Figure 3 of the paper).

Every step the robot resolves its scan into obstacles (clusters of returns, "average
clustered value" as position, the nearest first), measures the gaps between consecutive
obstacles and computes the atoms of the flowchart (:mod:`ifgm_ref.flowchart`); the flowchart
alone picks the branch, and this module carries it out:

* *move to goal*: head for the goal along the regenerated reference path (eq. (3));
* *Case-1* (max gap > ``d_th``, nearest obstacle > ``d_obs``, obstacles on both sides):
  steer through the middle of the widest gap, eqs. (1)-(4);
* *Case-2* and *too close*: avoid with IBA (:class:`~ifgm_ref.planners.iba.IBAPlanner`),
  following the edge bidirectionally until a free path towards the goal appears;
* *Case-3*: while avoiding, a nearer obstacle pre-empts the followed one; the followed one is
  pushed on a stack and resumed if it is met again (the recursion of section 4);
* *dead end* (inside a U or an H): turn in place in 45-degree steps, 45, 90, 135, 180 degrees,
  until the corridor ahead is free as far as the paper's sensor sees (``view_range``); go that
  way, then follow the wall round from outside with IBA and regenerate the path.

On a sensor wider than the paper's (a 270-degree LiDAR) Figure 3 reads the paper's 135-degree
view of the scan (:meth:`~ifgm_ref.laserscan.LaserScan.window`); the whole scan is remembered
for following edges (errata row 30).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from ifgm_ref.equations import eq1_gap_midpoint, eq2_gap_angle, eq3_goal_angle, eq4_final_heading
from ifgm_ref.errors import ParameterError
from ifgm_ref.flowchart import Atoms, Branch, decide
from ifgm_ref.laserscan import Beam, LaserScan
from ifgm_ref.paper import traces
from ifgm_ref.percepts.clusters import Cluster, Gap, Side, cluster_scan, gaps_between
from ifgm_ref.percepts.corridor import free_length
from ifgm_ref.percepts.points import to_world
from ifgm_ref.planners.boundary import BoundaryParams
from ifgm_ref.planners.distbug import DistBugParams
from ifgm_ref.planners.edge_following import FollowSide, turn_speed
from ifgm_ref.planners.iba import IBAPlanner, freer_side
from ifgm_ref.planners.tuning import Tuning, Unit, derived
from ifgm_ref.pose import Point, Pose, distance, wrap_angle
from ifgm_ref.protocol import Behaviour, Command, EpisodeParams, Observation

#: The dead-end rule's step, radians (section 4: "turns in steps of 45 degrees").
DEAD_END_STEP = math.pi / 4
#: At most four steps: 45, 90, 135 and 180 degrees ("until it finds obstacle free path (on
#: 180 degrees)").
DEAD_END_MAX_STEPS = 4


@traces("d_th", "d_obs", "s3.robot_dimensions")
@dataclass(frozen=True)
class IFGMParams(Tuning):
    """IFGM's thresholds and weights (section 4), each derived from the robot.

    Parameters
    ----------
    d_th : float, default ``3 r``
        Gap threshold, a length: Case-1 needs a gap wider than this. The paper: greater than
        the robot's size (we read: its diameter 2 r, errata row 12); one more radius leaves
        half a radius of clearance either side when passing through the middle.
    d_obs : float, default ``r + v/2``
        Nearest-obstacle threshold: at or below it IBA takes over. The paper: it "depends on
        speed of the robot"; we take the robot's radius plus half a second of travel, so that
        a robot passing through the middle of a gap just wider than ``d_th`` is not "too close".
    d_look : float, default ``8 r``
        Encounter distance: an obstacle in the robot-wide corridor towards the goal nearer
        than this makes the robot leave *move to goal*; four robot diameters (about half the
        paper's sensor range), so that gaps are measured while there is still room to steer.
        After leaving an edge by DistBug's progress rule with an obstacle still ahead, the
        encounter distance is IBA's short one (``standoff + hit_margin``) and Case-1 is off
        until the corridor towards the goal is free for ``d_look`` again (errata row 24).
    w_g : float, default ``9 r``
        Gap weight of eq. (4), a length: eq. (4) weighs the gap by ``w_g / d_th``, so only a
        length keeps the balance with the goal at every scale (the oracle's
        ``scale_invariant`` check found a plain 9). With the default ``d_th`` = 3 r the gap
        counts three times as much as the goal (``w_g / d_th = 3``), so the robot commits to
        the gap.
    w_d : float, default 1
        Goal weight of eq. (4), a number.
    jump : float, default ``2 r``
        Two consecutive returns further apart than this belong to different obstacles: a
        robot cannot pass between returns nearer than its diameter anyway.
    preempt_margin : float, default ``r/2``
        Case-3: another obstacle pre-empts the followed edge when it is this much nearer.
    turn_done : float, default ``w dt / 2``
        A dead-end turn is done when the heading is within this angle of its target: half
        the turn of one step. A robot turning at ``w`` and deciding every ``dt`` cannot
        promise more (one more step would overshoot by more than it corrects), and a port's
        rounding or a real robot's heading noise stays within it. The reference's simulated
        robot lands on the target exactly (its last step of a turn is clipped), so the
        tolerance changes nothing there; with an exact comparison a robot whose heading
        is a hair off turns in place for ever.
    """

    d_th: float = derived("3*r", Unit.LENGTH)
    d_obs: float = derived("r + v/2", Unit.LENGTH)
    d_look: float = derived("8*r", Unit.LENGTH)
    w_g: float = derived("9*r", Unit.LENGTH)
    w_d: float = derived("1", Unit.NUMBER)
    jump: float = derived("2*r", Unit.LENGTH)
    preempt_margin: float = derived("r/2", Unit.LENGTH)
    turn_done: float = derived("w*dt/2", Unit.ANGLE)


@traces("s3.critical_shapes", "s3.safe_near_obstacles")
class IFGMPlanner(IBAPlanner):
    """IFGM: FGM through wide gaps, IBA round the rest, 45-degree turns out of dead ends.

    Its state is public for observers (traces, ``tests/test_flowchart_properties.py``): to be
    read, not written.

    Attributes
    ----------
    last_atoms : Atoms or None
        The flowchart atoms computed at the last step, before it acted on them.
    last_branch : Branch or None
        The branch :func:`~ifgm_ref.flowchart.decide` chose for ``last_atoms``.
    last_gap : Gap or None
        The gap chosen at the last step: the maximum gap, or the one steered through at the
        step before while it stays wider than ``d_th`` (errata row 19).
    turning : bool
        A dead-end turn sequence (45, 90, 135, 180 degrees) is under way.
    following : bool
        IBA is following an edge (*obstacle avoidance*).
    side : FollowSide
        The side the followed edge is kept on (IBA's freer side, section 4.1).
    followed : Point or None
        The followed obstacle's point, world frame, tracked along its edge.
    stack : list of (Point, FollowSide)
        Case-3: the pre-empted obstacles and their sides, the last pushed resumed first.
    short_look : bool
        Meeting obstacles at IBA's short encounter distance, Case-1 off (errata row 24).
    """

    name = "ifgm"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (IFGMParams, BoundaryParams, DistBugParams)
    parameters: ClassVar[tuple[str, ...]] = IFGMParams.names() + IBAPlanner.parameters

    @traces("d_th", "d_obs")
    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Start in *move to goal*; derive and validate the thresholds."""
        super().reset(start, goal, params)
        p = IFGMParams.for_episode(params)
        r = params.robot.radius
        if p.d_th <= 2.0 * r:
            raise ParameterError(
                f"`d_th` must be > the robot diameter {2.0 * r!r} (section 4), got {p.d_th!r}"
            )
        self.d_th, self.d_obs, self.jump = p.d_th, p.d_obs, p.jump
        self.ifgm = p
        sensor = params.sensor
        try:  # the flowchart reads the paper's 135-degree view of the scan
            LaserScan(
                -sensor.fov / 2, sensor.fov / 2, sensor.angle_increment, 0.0, 1.0,
                [math.inf] * sensor.rays,
            ).window()  # fmt: skip
        except ValueError as err:
            raise ParameterError(f"IFGM reads the paper's 135-degree view: {err}") from None
        # The goal is reached during this step when it is within the episode's tolerance plus
        # one step of travel: the robot then drives straight onto it.
        self.goal_tolerance = params.goal_tolerance + params.robot.speed * params.dt
        self.dt = params.dt
        self.turning = False
        self.turn_start = 0.0
        self.turn_sign = 1
        self.turn_steps = 0
        self.escaping = 0.0
        self.stack: list[tuple[Point, FollowSide]] = []
        self.followed: Point | None = None
        self._gap_mid: Point | None = None
        self._preemptor: Point | None = None
        self.last_branch: Branch | None = None
        self.last_atoms: Atoms | None = None
        self.last_gap: Gap | None = None
        self.short_look = False
        self.escaped = False

    def goal_bearing(self, pose: Pose) -> float:
        """The destination angle theta_d of eq. (3), world frame (the reading we run); at the
        goal itself, where eq. (3) has no direction, the robot's heading."""
        if pose.position == self.goal:
            return pose.theta
        return eq3_goal_angle(pose.position, self.goal)

    # -- percepts -> atoms ------------------------------------------------------------------
    @traces("fig3.both_conditions", "fig3.case1", "fig3.case2", "fig3.dead_end")
    def atoms(self, observation: Observation, clusters: tuple[Cluster, ...]) -> Atoms:
        """The flowchart's atoms for this observation."""
        pose, scan = observation.pose, observation.scan
        widest = self._chosen_gap(pose, gaps_between(clusters))
        self.last_gap = widest
        nearest = min((c.nearest for c in clusters), default=math.inf)
        sides = {c.side for c in clusters}
        one_sided = bool(clusters) and (sides == {Side.LEFT} or sides == {Side.RIGHT})
        gap_wide = widest is not None and widest.width > self.d_th
        free_ahead = self.goal_free_length(pose)
        if self.short_look and free_ahead >= self.ifgm.d_look:
            self.short_look = False  # in the open again
        look = self.encounter if self.short_look else self.ifgm.d_look
        blocked = free_ahead < min(look, distance(pose, self.goal))
        front = scan.beam_mask(Beam.FRONT)
        front_near = bool(np.any(scan.ranges[front] <= self.ifgm.d_look))
        # Every ray returns within the view range (-inf too): the view ahead is closed.
        enclosed = bool(np.all(scan.ranges <= self.tuning.view_range))
        dead_end = front_near and enclosed and not gap_wide
        return Atoms(
            at_goal=distance(pose, self.goal) <= self.goal_tolerance,
            turning=self.turning,
            avoiding=self.following,
            blocked=blocked,
            free=self.following and self._may_leave(observation),
            close=nearest <= self.d_obs,
            # Case-1 needs a gap measured from afar (d_look): near, gaps look wider than
            # they are (errata row 23), so not while looking short.
            wide=gap_wide and not self.short_look,
            one_sided=one_sided,
            dead_end=dead_end,
            preempt=self.following and self._preempting(pose, clusters),
        )

    def _may_leave(self, observation: Observation) -> bool:
        """IBA's leaving rules (errata row 24): a free path, or DistBug's progress rule --
        but not while following the wall round from outside after a dead end, where the
        progress rule would lead straight back into the U or H (``tests/worlds/small_u``)."""
        progress = self.should_leave(observation)  # IBA's rules; keeps d_min up to date
        return self.free_path_leads_on(observation.pose) or (progress and not self.escaped)

    def _chosen_gap(self, pose: Pose, gaps: tuple[Gap, ...]) -> Gap | None:
        """The maximum gap (section 4) -- but the gap steered through at the last step while
        it stays wider than ``d_th``, so that two near-equal gaps (symmetric obstacles,
        Figure 7) do not make the robot swerve from one to the other at every step."""
        self._gap_mid, previous = None, self._gap_mid
        if not gaps:
            return None
        chosen = max(gaps, key=lambda g: g.width)
        if previous is not None:
            for gap in gaps:
                mid = to_world(np.array([eq1_gap_midpoint(gap.right, gap.left)]), pose)[0]
                if gap.width > self.d_th and math.dist(mid, previous) <= self.jump:
                    chosen = gap
                    break
        if chosen.width > self.d_th:
            mid = to_world(np.array([eq1_gap_midpoint(chosen.right, chosen.left)]), pose)[0]
            self._gap_mid = Point(float(mid[0]), float(mid[1]))
        return chosen

    def _nearest_remembered(self, pose: Pose, near: Point | None = None) -> Point | None:
        """The remembered point nearest the robot; with ``near``, among those within ``jump``
        of it (the same obstacle's edge, tracked as the robot moves along it)."""
        pts = self.memory.points
        if near is not None:
            pts = pts[np.hypot(pts[:, 0] - near.x, pts[:, 1] - near.y) <= self.jump]
        if len(pts) == 0:
            return None
        i = int(np.argmin(np.hypot(pts[:, 0] - pose.x, pts[:, 1] - pose.y)))
        return Point(float(pts[i, 0]), float(pts[i, 1]))

    def on_hit(self, observation: Observation) -> None:
        """A new avoidance starts: follow the nearest obstacle, with nothing pre-empted yet."""
        super().on_hit(observation)  # DistBug's d_min
        self.short_look = False
        self.escaped = False
        self.followed = self._nearest_remembered(observation.pose)
        self.stack.clear()

    def _track_followed(self, pose: Pose) -> None:
        """Keep :attr:`followed` on the edge of the obstacle being avoided."""
        tracked = self._nearest_remembered(pose, self.followed) if self.followed else None
        self.followed = tracked or self._nearest_remembered(pose)

    @traces("fig3.case3", "t1.bug_other_obstacles")
    def _preempting(self, pose: Pose, clusters: tuple[Cluster, ...]) -> bool:
        """Case-3: an obstacle apart from the followed one and nearer than it by a margin;
        of several, the nearest (the one of most impact: "the obstacle near to the robot is
        given higher priority", section 4)."""
        self._preemptor = None
        if self.followed is None:
            return False
        reach = distance(pose, self.followed) - self.ifgm.preempt_margin
        candidates = []
        for c in clusters:
            if c.nearest >= reach:
                continue
            world = to_world(c.xy, pose)
            apart = np.hypot(world[:, 0] - self.followed.x, world[:, 1] - self.followed.y)
            if apart.min() > self.jump:
                candidates.append((c.nearest, world[int(np.argmin(c.ranges))]))
        if not candidates:
            return False
        _, point = min(candidates, key=lambda candidate: candidate[0])
        self._preemptor = Point(float(point[0]), float(point[1]))
        return True

    # -- the planner ------------------------------------------------------------------------
    @traces("fig3.move_to_goal", "fig3.regenerate", "fig3.case2", "fig3.case3")
    def act(self, observation: Observation) -> Command:
        """Decide with Figure 3, then act on the branch."""
        pose = observation.pose
        self.observe(observation)  # the whole field of view is remembered, for edge following
        # Figure 3 reads the paper's view, 135 degrees and view_range deep (the scan itself
        # for the paper's sensor).
        view = observation.scan.window().limited(self.tuning.view_range)
        observation = replace(observation, scan=view)
        clusters = cluster_scan(observation.scan, jump=self.jump)
        if self.following:
            self._track_followed(pose)
        self.last_atoms = self.atoms(observation, clusters)
        branch = decide(self.last_atoms)
        self.last_branch = branch
        if branch is Branch.GOAL_REACHED:
            heading = self.goal_bearing(pose)
            speed = min(self.speed, distance(pose, self.goal) / self.dt)
            return Command(heading, speed, behaviour=Behaviour.MOVE_TO_GOAL, branch=branch)
        if branch is Branch.MOVE_TO_GOAL:
            return self._to_goal(pose, branch)
        if branch is Branch.PATH_REGENERATED:
            # Left by the progress rule, with an obstacle still ahead: meet it at IBA's short
            # encounter distance, not d_look (the followed one is still the nearest, and at
            # d_look the robot would go back to following it: tests/worlds/two_posts_in_line).
            self.short_look = not self.path_free(pose)
            self.escaped = False
            self.following = False
            self.followed = None
            self.stack.clear()
            return self._to_goal(pose, branch)
        if branch is Branch.CASE1_GAP:
            return self._through_gap(pose)
        if branch is Branch.DEAD_END_TURN:
            return self._dead_end(observation)
        if branch is Branch.CASE3_PREEMPT:
            assert self.followed is not None and self._preemptor is not None
            self.stack.append((self.followed, self.side))
            self.followed = self._preemptor
            self.side = freer_side(observation.scan, pose, self.goal_bearing(pose))
        elif branch is Branch.FOLLOW_EDGE:
            self._resume_if_back(pose)
        else:  # Case-2 (narrow gap, one-sided) or too close: IBA takes over
            self.start_following(observation)
        return self._follow(pose, branch)

    def _to_goal(self, pose: Pose, branch: Branch) -> Command:
        heading = self.goal_bearing(pose)
        return Command(
            heading,
            turn_speed(wrap_angle(heading - pose.theta), self.speed),
            behaviour=Behaviour.MOVE_TO_GOAL,
            branch=branch,
        )

    def _follow(self, pose: Pose, branch: Branch) -> Command:
        command = self.follow(pose, branch)
        return Command(command.heading, command.speed, behaviour=command.behaviour, branch=branch)

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
            d_th=self.d_th,
            heading=pose.theta,
        )

    def _through_gap(self, pose: Pose) -> Command:
        assert self.last_gap is not None
        heading = self.gap_heading(pose, self.last_gap)
        return Command(
            heading,
            turn_speed(wrap_angle(heading - pose.theta), self.speed),
            behaviour=Behaviour.OBSTACLE_AVOIDANCE,
            branch=Branch.CASE1_GAP,
        )

    def _resume_if_back(self, pose: Pose) -> None:
        """Case-3 recursion: once the pre-empting obstacle is no longer the nearest, resume
        avoiding the one it interrupted, on the side it was followed on."""
        nearest = self._nearest_remembered(pose)
        if (
            self.stack
            and nearest is not None
            and self.followed is not None
            and distance(nearest, self.followed) > self.jump
        ):
            _, self.side = self.stack.pop()
            self.followed = nearest

    @traces("fig3.dead_end", "s5.ifgm_u_h")
    def _dead_end(self, observation: Observation) -> Command:
        """Turn in 45-degree steps until the way ahead is free; then go that way."""
        pose = observation.pose
        if not self.turning:  # entering the dead end
            self.turning = True
            self.turn_start = pose.theta
            self.turn_steps = 1
            self.escaping = 0.0
            side = freer_side(observation.scan, pose, self.goal_bearing(pose))
            self.turn_sign = 1 if side is FollowSide.RIGHT else -1  # turn towards the freer beam
        target = wrap_angle(self.turn_start + self.turn_sign * self.turn_steps * DEAD_END_STEP)
        if self.escaping == 0.0 and abs(wrap_angle(pose.theta - target)) > self.ifgm.turn_done:
            return self._turn_command(target)
        ahead = free_length(self.memory.points, (pose.x, pose.y), pose.theta, self.half_width)
        if self.escaping == 0.0:
            if ahead < self.tuning.view_range and self.turn_steps < DEAD_END_MAX_STEPS:
                self.turn_steps += 1
                return self._turn_command(
                    wrap_angle(self.turn_start + self.turn_sign * self.turn_steps * DEAD_END_STEP)
                )
            self.escaping = 1e-9  # free (or 180 degrees reached): go that way
            self._escape_from = pose.position
        gone = distance(pose, self._escape_from)
        if gone < self.ifgm.d_look and ahead > self.standoff + self.tuning.hit_margin:
            self.escaping = max(gone, 1e-9)
            return Command(
                target,
                self.speed,
                behaviour=Behaviour.OBSTACLE_AVOIDANCE,
                branch=Branch.DEAD_END_TURN,
            )
        # Escaped: follow the nearest wall round from outside (IBA), then regenerate the path.
        self.turning = False
        self.escaping = 0.0
        self.start_following(observation)
        self.escaped = True
        followed = self._nearest_remembered(pose)
        if followed is not None:
            rel = wrap_angle(math.atan2(followed.y - pose.y, followed.x - pose.x) - pose.theta)
            self.side = FollowSide.LEFT if rel > 0.0 else FollowSide.RIGHT
        return self._follow(pose, Branch.DEAD_END_TURN)

    def _turn_command(self, target: float) -> Command:
        return Command(
            target, 0.0, behaviour=Behaviour.OBSTACLE_AVOIDANCE, branch=Branch.DEAD_END_TURN
        )
