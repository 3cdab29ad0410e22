"""DWA: BARN's baseline, ROS move_base with navfn and base_local_planner's dynamic window.

Reference
---------
D. Fox, W. Burgard, S. Thrun, "The dynamic window approach to collision avoidance", *IEEE
Robotics & Automation Magazine* 4(1):23-33, 1997; the configuration is BARN's
(``Daffan/the-barn-challenge``, ``jackal_helper/launch/move_base_DWA.launch`` and
``jackal_helper/configs/params/``: ``base_local_planner_params.yaml``,
``costmap_common_params.yaml``, ``move_base_params.yaml``; summed up in the README beside
BARN's worlds, ``ifgm_ref/io/barn_worlds/README.md``).

Unlike the paper's planners, which "decide from current percepts only" (section 3), this one
keeps a map: a costmap built from its own scans (:mod:`ifgm_ref.planners.costmap`), in the
frame of the poses it is told. It still imports nothing that knows the world: no world, no
sensor, no simulator; what it maps is what it has seen. Each step it

1. clears along every ray and marks every return of the scan (:class:`Costmap`);
2. plans a global path on the costmap (:func:`~ifgm_ref.planners.grid_path.plan_path`, navfn's
   role) when ``planner_period`` has passed since the last plan (move_base's
   ``planner_frequency``), when the path crosses a cell that became lethal or inscribed, or
   when the grid grew;
3. scores the dynamic window's trajectories (:mod:`ifgm_ref.planners.dwa_rollout`) against
   MapGrid's distances to the path and to the local goal (the last point of the path inside
   the local window) and commands the cheapest.

Choices where the configuration does not fit a planner of this package, each documented:

* The current velocity, which TrajectoryPlannerROS reads from odometry, is the last command
  (the observation carries no velocity; the kinematic robot executes each command exactly).
* The robot does not reverse (a command's speed is >= 0), so where no trajectory is legal
  it turns in place at ``max_vel_theta`` towards the path instead of backing up at
  ``escape_vel`` (-0.5 m/s); without a path (the goal walled off on the costmap) it turns in
  place too, as move_base's rotate recovery does. TrajectoryPlannerROS's oscillation flags
  (``stuck_left``, ``stuck_right``) are left out.
* The footprint is the robot's disc, so its inscribed radius is ``r`` (BARN's Jackal has a
  padded 0.42 x 0.33 m rectangle); the goal tolerance is the episode's.
* The global grid covers the start, the goal and ``obstacle_range`` round them, and grows
  round the robot, where BARN's global costmap is a fixed 40 x 40 m; the local window is a
  ``local_size`` square of the same grid round the robot.

Every parameter is a formula in the robot, the time step and the sensor (:mod:`ifgm_ref.
planners.tuning`); each gives BARN's configured value for BARN's robot (r 0.22 m, v 1 m/s,
w pi rad/s, dt 0.05 s, the Jackal's LiDAR): see :class:`CostmapParams` and :class:`DWAParams`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.core.formulas import Unit
from ifgm_ref.core.pose import Point, Pose, wrap_angle
from ifgm_ref.core.protocol import Behaviour, Command, EpisodeParams, Observation
from ifgm_ref.planners.costmap import Costmap, CostmapSettings
from ifgm_ref.planners.dwa_rollout import Samples, Window, legal_costs, rollout, samples
from ifgm_ref.planners.grid_path import blocked, plan_path, wavefront
from ifgm_ref.planners.tuning import Tuning, check_names, derived, parameter_names

__all__ = ["CostmapParams", "DWABranch", "DWAParams", "DWAPlanner", "choose"]


class DWABranch(StrEnum):
    """What DWA commanded at one step (the trace's ``branch``)."""

    TRAJECTORY = "trajectory"  #: the cheapest legal trajectory moving forward
    ROTATE = "rotate"  #: the cheapest was a turn in place
    ESCAPE = "escape"  #: no legal trajectory: turn in place towards the path
    NO_PLAN = "no_plan"  #: no path to the goal on the costmap: turn in place


@dataclass(frozen=True)
class CostmapParams(Tuning):
    """The costmaps' settings (``costmap_common_params.yaml`` and ``local_costmap_params``).

    Lengths are counted in BARN's cells: ``r/4.4`` is 0.05 m for BARN's 0.22 m robot.

    Parameters
    ----------
    resolution : float, default ``r/4.4``
        Cell side: BARN's 0.05 m.
    obstacle_range : float, default ``50*r/4.4``
        Returns up to this range mark their cell: BARN's 2.5 m (50 cells).
    raytrace_range : float, default ``60*r/4.4``
        Rays clear what they cross up to this range: BARN's 3.0 m (60 cells).
    inflation_radius : float, default ``6*r/4.4``
        Cells this near a marked cell get a cost: BARN's 0.30 m (6 cells).
    cost_decay : float, default ``2*r/4.4``
        ``1 / cost_scaling_factor``: costmap_2d's default factor 10 per metre, 0.1 m.
    local_size : float, default ``200*r/4.4``
        Side of the local window the trajectories are scored in: BARN's 10 m local costmap.
    """

    resolution: float = derived("r/4.4", Unit.LENGTH)
    obstacle_range: float = derived("50*r/4.4", Unit.LENGTH)
    raytrace_range: float = derived("60*r/4.4", Unit.LENGTH)
    inflation_radius: float = derived("6*r/4.4", Unit.LENGTH)
    cost_decay: float = derived("2*r/4.4", Unit.LENGTH)
    local_size: float = derived("200*r/4.4", Unit.LENGTH)


@dataclass(frozen=True)
class DWAParams(Tuning):
    """TrajectoryPlannerROS's settings (``base_local_planner_params.yaml``) and move_base's
    planner period (``move_base_params.yaml``), BARN's values for BARN's robot.

    Parameters
    ----------
    max_vel_x : float, default ``v/2``
        Top forward speed: BARN's 0.5 m/s.
    min_vel_x : float, default ``v/10``
        Least forward speed: BARN's 0.1 m/s.
    max_vel_theta : float, default ``w/2``
        Top turn rate: BARN's 1.57 rad/s (pi/2).
    min_in_place_vel_theta : float, default ``w/10``
        Least turn rate in place: BARN's 0.314 rad/s (pi/10).
    acc_lim_x : float, default ``v/(2*dt)``
        Acceleration limit: BARN's 10 m/s^2, ``max_vel_x`` gained in one control period.
    acc_lim_theta : float, default ``w/(pi*dt)``
        Angular acceleration limit: BARN's 20 rad/s^2, 1 rad/s (``w/pi``) per period.
    sim_time : float, default ``2*pi/w``
        Time each trajectory is simulated for: BARN's 2.0 s, one full turn at ``w``.
    sim_granularity : float, default ``0.4*r/4.4``
        Step between checked points: BARN's 0.02 m.
    angular_sim_granularity : float, default ``0.02``
        Angular step, rad: ROS's default, ``sim_granularity``'s number (0.02).
    vx_samples : float, default ``6``
        Forward speeds sampled: BARN's 6.
    vtheta_samples : float, default ``20``
        Turn rates sampled: BARN's 20.
    pdist_scale : float, default ``0.75``
        Weight of the distance to the path: BARN's 0.75.
    gdist_scale : float, default ``1``
        Weight of the distance to the local goal: BARN's 1.0.
    occdist_scale : float, default ``0.1``
        Weight of the largest cell cost: BARN's 0.1.
    heading_lookahead : float, default ``6.5*r/4.4``
        How far ahead of a turn in place its goal distance is read: ROS's default 0.325 m.
    planner_period : float, default ``dt``
        Time between global plans: BARN's ``planner_frequency`` 20 Hz, one control period.
    """

    max_vel_x: float = derived("v/2", Unit.SPEED)
    min_vel_x: float = derived("v/10", Unit.SPEED)
    max_vel_theta: float = derived("w/2", Unit.TURN_RATE)
    min_in_place_vel_theta: float = derived("w/10", Unit.TURN_RATE)
    acc_lim_x: float = derived("v/(2*dt)", Unit.ACCELERATION)
    acc_lim_theta: float = derived("w/(pi*dt)", Unit.TURN_ACCELERATION)
    sim_time: float = derived("2*pi/w", Unit.TIME)
    sim_granularity: float = derived("0.4*r/4.4", Unit.LENGTH)
    angular_sim_granularity: float = derived("0.02", Unit.ANGLE)
    vx_samples: float = derived("6", Unit.NUMBER)
    vtheta_samples: float = derived("20", Unit.NUMBER)
    pdist_scale: float = derived("0.75", Unit.NUMBER)
    gdist_scale: float = derived("1", Unit.NUMBER)
    occdist_scale: float = derived("0.1", Unit.NUMBER)
    heading_lookahead: float = derived("6.5*r/4.4", Unit.LENGTH)
    planner_period: float = derived("dt", Unit.TIME)

    def window(self) -> Window:
        """The velocity limits and sample counts."""
        return Window(
            self.min_vel_x,
            self.max_vel_x,
            self.max_vel_theta,
            self.min_in_place_vel_theta,
            self.acc_lim_x,
            self.acc_lim_theta,
            max(round(self.vx_samples), 1),
            max(round(self.vtheta_samples), 1),
        )


def choose(costs: NDArray[np.float64], chosen: Samples, ahead: NDArray[np.float64]) -> int | None:
    """The sample TrajectoryPlanner keeps, or ``None`` when none is legal (``nan`` cost).

    The cheapest forward trajectory (the first of equal ones); then a turn in place replaces
    it when it costs no more, its unlimited rate exceeds the sampling step ``dvth``, and the
    goal distance ``ahead`` of its end (``heading_lookahead`` along its heading; ``nan``
    off the window) is the least of such turns so far.

    >>> s = Samples(np.array([0.1, 0.2, 0.0]), np.array([0.0, 0.0, 0.5]), 2, 0.1,
    ...             np.array([0.0, 0.0, 0.5]))
    >>> choose(np.array([3.0, 2.0, 2.5]), s, np.array([0.0, 0.0, 1.0]))
    1
    >>> choose(np.array([3.0, 2.0, 2.0]), s, np.array([0.0, 0.0, 1.0]))
    2
    >>> choose(np.array([np.nan, np.nan, np.nan]), s, np.zeros(3)) is None
    True
    """
    best: int | None = None
    for i in range(chosen.forward):
        if not math.isnan(costs[i]) and (best is None or costs[i] < costs[best]):
            best = i
    heading = math.inf
    for i in range(chosen.forward, len(costs)):
        if math.isnan(costs[i]) or (best is not None and costs[i] > costs[best]):
            continue
        if abs(chosen.raw_vth[i]) > chosen.dvth and ahead[i] < heading:
            best, heading = i, float(ahead[i])
    return best


@dataclass
class _Plan:
    """A global plan: its cells and the time it was made; ``done`` indexes the nearest."""

    rows: NDArray[np.intp]
    cols: NDArray[np.intp]
    made: float
    generation: int
    done: int = 0


class DWAPlanner:
    """BARN's move_base DWA baseline: a scan-built costmap, a grid plan, a dynamic window.

    Examples
    --------
    In the open it drives straight at the goal at ``max_vel_x`` (half the robot's speed):

    >>> from ifgm_ref.core.laserscan import LaserScan
    >>> planner = DWAPlanner()
    >>> planner.reset(Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), EpisodeParams())
    >>> empty = LaserScan(-1.0, 1.0, 1.0, 0.0, 15.0, [math.inf] * 3)
    >>> command = planner.step(Observation(0.0, Pose(0.0, 0.0, 0.0), Point(10.0, 0.0), empty))
    >>> command.branch, round(command.speed, 4), command.turn_rate
    ('trajectory', 0.6611, 0.0)
    """

    name: ClassVar[str] = "dwa"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (CostmapParams, DWAParams)
    #: Names of the settings read from ``EpisodeParams.params``.
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self) -> None:
        self.reset(Pose(0.0, 0.0, 0.0), Point(1.0, 0.0), EpisodeParams())

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Read the settings, start an empty costmap round the start and the goal."""
        check_names(params.params, self.parameters, self.name)
        self.params = params
        self.grid_params = CostmapParams.for_episode(params)
        self.tuning = DWAParams.for_episode(params)
        g = self.grid_params
        settings = CostmapSettings(
            g.resolution, params.robot.radius, g.inflation_radius, g.cost_decay,
            g.obstacle_range, g.raytrace_range, g.obstacle_range,
        )  # fmt: skip
        self.costmap = Costmap(settings, start.position, goal)
        self.goal = goal
        self.plan: _Plan | None = None
        #: The current velocity estimate: the last command ``(v, w)``.
        self.velocity = (0.0, 0.0)

    def step(self, observation: Observation) -> Command:
        """Map the scan, keep a plan, score the window, command the cheapest trajectory."""
        pose = observation.pose
        self.costmap.update(pose, observation.scan)
        if self._replan_due(observation.t):
            self._replan(pose, observation.t)
        if self.plan is None:
            return self._command(pose, 0.0, self.tuning.max_vel_theta, DWABranch.NO_PLAN)
        linear, angular, branch = self._local(pose)
        return self._command(pose, linear, angular, branch)

    def _command(self, pose: Pose, linear: float, angular: float, branch: DWABranch) -> Command:
        self.velocity = (linear, angular)
        behaviour = (
            Behaviour.MOVE_TO_GOAL
            if branch is DWABranch.TRAJECTORY
            else Behaviour.OBSTACLE_AVOIDANCE
        )
        return Command.from_twist(
            linear, angular, pose, self.params, behaviour=behaviour, branch=str(branch)
        )

    def _replan_due(self, t: float) -> bool:
        """Whether the plan is missing, old, on a grown grid, or crosses a blocked cell."""
        plan = self.plan
        if plan is None or plan.generation != self.costmap.generation:
            return True
        if t - plan.made >= self.tuning.planner_period - 1e-9:
            return True
        ahead = self.costmap.cost[plan.rows[plan.done :], plan.cols[plan.done :]]
        return bool(blocked(ahead).any())

    def _replan(self, pose: Pose, t: float) -> None:
        grid = self.costmap
        start = grid.cell_of(pose.x, pose.y)
        chain = plan_path(grid.cost, start, grid.cell_of(self.goal.x, self.goal.y))
        if chain is None:
            self.plan = None
            return
        cells = np.asarray(chain, dtype=np.intp).reshape(-1, 2)
        self.plan = _Plan(cells[:, 0], cells[:, 1], t, grid.generation)

    def _window(self, pose: Pose) -> tuple[int, int, int, int]:
        """The local window round the robot, clipped to the grid: rows ``r0:r1``, columns
        ``c0:c1``."""
        grid = self.costmap
        half = math.ceil(self.grid_params.local_size / 2.0 / grid.settings.resolution)
        row, col = grid.cell_of(pose.x, pose.y)
        rows, cols = grid.shape
        return (
            max(row - half, 0),
            min(row + half + 1, rows),
            max(col - half, 0),
            min(col + half + 1, cols),
        )

    def _local_plan(self, pose: Pose, window: tuple[int, int, int, int]) -> tuple[int, int] | None:
        """The part of the plan the local planner follows, ``(first, end)``: from the plan
        cell nearest the robot, among the run inside the window from the last one, to the
        last of that run (the local goal); ``None`` when no cell of the plan is inside."""
        plan = self.plan
        assert plan is not None
        r0, r1, c0, c1 = window
        inside = (plan.rows >= r0) & (plan.rows < r1) & (plan.cols >= c0) & (plan.cols < c1)
        run = np.flatnonzero(inside[plan.done :])
        if len(run) == 0:
            return None
        first = plan.done + int(run[0])
        out = np.flatnonzero(~inside[first:])
        end = first + int(out[0]) if len(out) else len(plan.rows)
        row, col = self.costmap.cell_of(pose.x, pose.y)
        near = (plan.rows[first:end] - row) ** 2 + (plan.cols[first:end] - col) ** 2
        plan.done = first + int(np.argmin(near))
        return plan.done, end

    def _local(self, pose: Pose) -> tuple[float, float, DWABranch]:
        """Score the dynamic window on the local window; the chosen ``(v, w)`` and branch."""
        plan, grid, tuning = self.plan, self.costmap, self.tuning
        assert plan is not None
        window = self._window(pose)
        span = self._local_plan(pose, window)
        if span is None:
            return self._escape(pose, None)
        r0, r1, c0, c1 = window
        cost = grid.cost[r0:r1, c0:c1]
        path_dist, goal_dist = self._distances(pose, window, span)
        final = span[1] == len(plan.rows)
        top = math.dist(pose.position, self.goal) / tuning.sim_time if final else None
        limits = tuning.window()
        chosen = samples(limits, *self.velocity, self.params.dt, top)
        roll = rollout(
            (pose.x, pose.y, pose.theta), self.velocity, chosen, limits,
            sim_time=tuning.sim_time, granularity=tuning.sim_granularity,
            angular_granularity=tuning.angular_sim_granularity,
        )  # fmt: skip
        rows, cols = grid.cells_of(np.stack((roll.x, roll.y), -1))
        c = grid.settings.resolution
        scales = (c * tuning.pdist_scale, c * tuning.gdist_scale, c * tuning.occdist_scale)
        costs = legal_costs((rows - r0, cols - c0), roll.valid, cost, path_dist, goal_dist, scales)
        last = roll.valid.sum(axis=1) - 1
        k = np.arange(len(last))
        heading = roll.theta[k, last]
        ahead_x = roll.x[k, last] + tuning.heading_lookahead * np.cos(heading)
        ahead_y = roll.y[k, last] + tuning.heading_lookahead * np.sin(heading)
        ar, ac = grid.cells_of(np.stack((ahead_x, ahead_y), -1))
        ar, ac = ar - r0, ac - c0
        seen = (ar >= 0) & (ar < r1 - r0) & (ac >= 0) & (ac < c1 - c0)
        ahead = np.where(seen, goal_dist[np.where(seen, ar, 0), np.where(seen, ac, 0)], np.nan)
        best = choose(costs, chosen, ahead.astype(np.float64))
        if best is None:
            return self._escape(pose, span)
        linear, angular = float(chosen.vx[best]), float(chosen.vth[best])
        return linear, angular, DWABranch.TRAJECTORY if linear > 0.0 else DWABranch.ROTATE

    def _distances(
        self, pose: Pose, window: tuple[int, int, int, int], span: tuple[int, int]
    ) -> tuple[NDArray[np.int32], NDArray[np.int32]]:
        """MapGrid's distances over the window: to the local plan and to the local goal."""
        plan, grid, tuning = self.plan, self.costmap, self.tuning
        assert plan is not None
        r0, r1, c0, c1 = window
        passable = ~blocked(grid.cost[r0:r1, c0:c1])
        rows, cols = plan.rows[span[0] : span[1]] - r0, plan.cols[span[0] : span[1]] - c0
        on_path = np.zeros_like(passable)
        on_path[rows, cols] = True
        at_goal = np.zeros_like(passable)
        at_goal[rows[-1], cols[-1]] = True
        reach = math.ceil((tuning.max_vel_x * tuning.sim_time + tuning.heading_lookahead)
                          / grid.settings.resolution) + 2  # fmt: skip
        row, col = grid.cell_of(pose.x, pose.y)
        box = (
            slice(max(row - r0 - reach, 0), max(row - r0 + reach + 1, 0)),
            slice(max(col - c0 - reach, 0), max(col - c0 + reach + 1, 0)),
        )
        return wavefront(passable, on_path, box), wavefront(passable, at_goal, box)

    def _escape(self, pose: Pose, span: tuple[int, int] | None) -> tuple[float, float, DWABranch]:
        """No legal trajectory: turn in place at ``max_vel_theta`` towards the local goal
        (to the left when there is none)."""
        rate = self.tuning.max_vel_theta
        if span is not None and self.plan is not None:
            target = self.costmap.centre(
                int(self.plan.rows[span[1] - 1]), int(self.plan.cols[span[1] - 1])
            )
            bearing = math.atan2(target.y - pose.y, target.x - pose.x)
            if wrap_angle(bearing - pose.theta) < 0.0:
                rate = -rate
        return 0.0, rate, DWABranch.ESCAPE
