"""DistBug: leave the obstacle as soon as the free range towards the goal promises progress.

Reference: I. Kamon and E. Rivlin, "Sensory-based motion planning with global proofs",
*IEEE Transactions on Robotics and Automation* 13(6) (1997) 814-822. Paper, section 2.1.3:
"when the robot encounters an obstacle in its path, it starts following the edges of the
obstacle calculating and simultaneously storing the distance from its current and next
positions to destination"; section 5.1, Figure 5a: "the robot is following the edge of
obstacle until it reaches to the leaving point having minimum distance to destination".

Kamon and Rivlin's leaving rule (errata row 22): while following the obstacle met at the
hit point H, with x the robot's position and T the goal, leave when ``d(x, T) - F <= 0`` (T
is visible) or ``d(x, T) - F <= d_min - Step``, where ``d_min`` is the least d(x, T) seen
since H and ``F`` the free range towards T (:meth:`DistBugRule.free_range`). For a disc
robot that sees 135 degrees ahead:

* ``F = 0`` when the goal is outside the field of view;
* ``F = d(x, T)`` when the robot-wide corridor towards the goal
  (:attr:`~ifgm_ref.planners.sight.Sight.goal_free_length`) is free up to a goal within
  ``view_range``, the farthest the planners remember (errata row 34);
* otherwise ``F = min(free length, view_range) - (standoff + hit_margin)``, at least 0: as
  far as the robot can go before it meets the wall again (errata row 22).

``Step`` is ``step_length``, the robot's diameter. After a whole loop without having left,
Bug1's round (:mod:`~ifgm_ref.planners.circuit`). The rule is :class:`DistBugRule`; IBA's
rule builds on it. The reasons at length: ``docs/ifgm-state.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from ifgm_ref.core.elements import traces
from ifgm_ref.core.formulas import Unit
from ifgm_ref.core.pose import Point, Pose, distance
from ifgm_ref.core.protocol import EpisodeParams
from ifgm_ref.planners.boundary import BoundaryPlanner, EdgeFollower, LeaveRule
from ifgm_ref.planners.sight import BoundaryParams, Sight
from ifgm_ref.planners.tuning import Tuning, derived, parameter_names


@dataclass(frozen=True)
class DistBugParams(Tuning):
    """DistBug's own parameter.

    Parameters
    ----------
    step_length : float, default ``2 r``
        Step, a length: the least progress towards the goal, beyond the best distance seen
        on this obstacle, that the free range must promise before the robot leaves.
    """

    step_length: float = derived("2*r", Unit.LENGTH)


class DistBugRule(LeaveRule):
    """Kamon and Rivlin's leaving rule: ``d - F <= 0`` or ``d - F <= d_min - Step``.

    Attributes
    ----------
    d_min : float
        Least distance to the goal seen while following the current obstacle.
    step_length : float
        Step (:class:`DistBugParams`).
    """

    tunings: ClassVar[tuple[type[Tuning], ...]] = (DistBugParams,)
    leave_branch: ClassVar[str] = "leave_distbug"

    def __init__(self) -> None:
        super().__init__()
        self.step_length: float  # read at reset
        self.d_min = math.inf

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Read ``step_length`` (default ``2 r``); no distance seen yet."""
        super().reset(start, goal, params)
        self.step_length = DistBugParams.for_episode(params).step_length
        self.d_min = math.inf

    def on_hit(self, sight: Sight, follower: EdgeFollower) -> None:
        """A new obstacle: ``d_min`` starts at d(H, T)."""
        self.d_min = distance(follower.hit_point, sight.episode.goal)

    def note(self, sight: Sight) -> None:
        """Count this step's distance to the goal into ``d_min``."""
        self.d_min = min(self.d_min, sight.goal_distance)

    def update(self, sight: Sight, follower: EdgeFollower) -> bool:
        """Note the distance (:meth:`note`), then apply the rule (:meth:`progress`)."""
        self.note(sight)
        return self.progress(sight)

    def progress(self, sight: Sight) -> bool:
        """Kamon and Rivlin's rule on this step's sight, with the ``d_min`` noted so far
        (:func:`makes_progress`)."""
        return makes_progress(sight, self.d_min, self.step_length)

    @staticmethod
    def free_range(sight: Sight) -> float:
        """F: how far the robot can move towards the goal, as the sensor tells (see the
        module docstring)."""
        if not sight.goal_in_view():
            return 0.0
        d = sight.goal_distance
        free = sight.goal_free_length
        seen = sight.episode.tuning.view_range  # the planner knows nothing beyond it
        if free >= d and d <= seen:
            return d
        return max(0.0, min(free, seen) - sight.episode.encounter)


def makes_progress(sight: Sight, d_min: float, step_length: float) -> bool:
    """Kamon and Rivlin's leaving rule: ``d - F <= 0`` or ``d - F <= d_min - Step``, with
    ``F`` the free range (:meth:`DistBugRule.free_range`)."""
    reach = sight.goal_distance - DistBugRule.free_range(sight)
    return reach <= 0.0 or reach <= d_min - step_length


@traces("distbug")
class DistBugPlanner(BoundaryPlanner):
    """Kamon and Rivlin's DistBug: the boundary-following skeleton with :class:`DistBugRule`.

    Parameters (``params`` mapping of :func:`ifgm_ref.sim.simulator.simulate`): those of
    :class:`~ifgm_ref.planners.sight.BoundaryParams` and :class:`DistBugParams`.

    Examples
    --------
    >>> from ifgm_ref.io.scenarios import resolve_world
    >>> from ifgm_ref.sim.simulator import simulate
    >>> run = simulate(resolve_world("box"), DistBugPlanner())
    >>> run.result.stop_reason, run.result.collided
    ('goal_reached', False)
    >>> "leave_distbug" in {s.branch for s in run.trace}
    True
    >>> simulate(resolve_world("box"), DistBugPlanner(), params={"step_length": -1.0})
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `step_length` must be a finite number > 0, got -1.0
    >>> simulate(resolve_world("box"), DistBugPlanner(), params={"step_lenght": 1.0})
    ... # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: distbug has no parameter `step_lenght`; it has: ...
    """

    name: ClassVar[str] = "distbug"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (BoundaryParams, DistBugParams)
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self) -> None:
        super().__init__(DistBugRule())
