"""Bug1: go all the way round the obstacle, then leave from its point nearest the goal.

Reference: V. J. Lumelsky and A. A. Stepanov, "Path-planning strategies for a point mobile
automaton moving amidst unknown obstacles of arbitrary shape", *Algorithmica* 2 (1987)
403-430. Paper, section 2.1.1: "after detecting an obstacle, the robot moves around the
obstacle completely in order to find the point (leaving point) having minimum distance to
destination. The robot restarts following the edge until it reaches to the computed leaving
point and generates a new referenced path to destination."

Bug1's round of one obstacle -- circumnavigate from the hit point H noting the point Q
nearest the goal, go on to Q along the loop, leave there, or report the goal unreachable if
the loop shows that the obstacle stands between the robot and the goal -- is what every
boundary follower here falls back on after a whole loop (:mod:`~ifgm_ref.planners.circuit`).
Bug1 is that round alone: the :class:`~ifgm_ref.planners.boundary.BoundaryPlanner` skeleton
with a leaving rule that never leaves earlier (:class:`~ifgm_ref.planners.boundary.LeaveRule`).

Symbols: H (hit point, :attr:`EdgeFollower.hit_point`), Q (:attr:`Circuit.q_point`),
d(x, T) (distance to the goal). Ours goes on to Q the same way round (errata row 34), so
Lumelsky and Stepanov's bound ``D + 1.5 * sum(p_i)`` becomes ``D + 2 * sum(p_i)``
(``docs/ifgm-state.md``).
"""

from __future__ import annotations

from typing import ClassVar

from ifgm_ref.core.elements import traces
from ifgm_ref.planners.boundary import BoundaryPlanner, LeaveRule
from ifgm_ref.planners.sight import BoundaryParams
from ifgm_ref.planners.tuning import Tuning, parameter_names


@traces("bug1", "t1.bug_long_paths")
class Bug1Planner(BoundaryPlanner):
    """Lumelsky and Stepanov's Bug1: the boundary-following skeleton with no earlier leaving
    rule than Bug1's round of the obstacle (:mod:`~ifgm_ref.planners.circuit`).

    Tunables (``params`` mapping of :func:`ifgm_ref.sim.simulator.simulate`) are those of
    :class:`~ifgm_ref.planners.sight.BoundaryParams`; ``return_radius`` doubles as the
    radius within which Q counts as reached.

    Examples
    --------
    >>> from ifgm_ref.io.scenarios import resolve_world
    >>> from ifgm_ref.sim.simulator import simulate
    >>> run = simulate(resolve_world("box"), Bug1Planner())
    >>> run.result.stop_reason, run.result.collided
    ('goal_reached', False)
    >>> [b for b in dict.fromkeys(s.branch for s in run.trace) if b]
    ['move_to_goal', 'follow_edge', 'loop_closed', 'follow_to_q', 'leave_at_q']
    """

    name: ClassVar[str] = "bug1"
    tunings: ClassVar[tuple[type[Tuning], ...]] = (BoundaryParams,)
    parameters: ClassVar[tuple[str, ...]] = parameter_names(tunings)

    def __init__(self) -> None:
        super().__init__(LeaveRule())
