"""Explore IFGM's parameters: one run in a U world, its path coloured by Figure 3 branch.

Reference: "An Improved Algorithm for Collision Avoidance in Environments Having U and H
Shaped Obstacles" (IFGM / IBA), section 4 and Figure 3. ``notebooks/05_explore.ipynb`` puts
sliders on the six values of :class:`ExploreSetting` and redraws :func:`plot_explore`.

The setting's values and their symbols in the paper:

================  ===================  ===================================================
here              paper                meaning
================  ===================  ===================================================
``d_th``          ``d_th``             gap threshold (section 4): Case-1 needs a gap wider
                                       than it; it also divides the gap weight in eq. (4)
``w_g``           ``w_g``              gap weight of eq. (4) (as ``w_g / d_th``)
``w_d``           ``w_d``              goal weight of eq. (4)
``sensor_range``  (not given)          the IR sensor's reach, ft (section 4, Figure 2)
``u_width``       (Figure 8, not       the U's outer size across its mouth, ft
``u_depth``       given)               the U's outer size from back to mouth, ft
================  ===================  ===================================================

The world (:func:`explore_world`) is ``u_trap``'s arena, 60 ft from start to goal along +x,
with a U across that line, opening towards the start (the paper's Figure 8 trap), and a
*gate* before it: two posts 14 ft out, one on the line and one beside it,
:data:`GATE_GAP` = 4 ft apart. Without the gate ``d_th``, ``w_g`` and ``w_d`` change almost
nothing: IFGM meets a lone U head-on, finds a dead end (every ray returns, no gap) and turns
out of it in 45-degree steps, a rule that reads none of the three. The gate is a gap between
two obstacles across the robot's way, where Figure 3 chooses between Case-1 (the gap is wider
than ``d_th``: steer through it by eqs. (1)-(4)) and Case-2 (IBA round the posts).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Final

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from numpy.typing import NDArray

from ifgm_ref.core.errors import ParameterError
from ifgm_ref.core.params import SensorParams
from ifgm_ref.core.validate import POSITIVE, require
from ifgm_ref.io.scenarios import resolve_world
from ifgm_ref.paper.flowchart import Branch
from ifgm_ref.planners import make_planner
from ifgm_ref.planners.ifgm.atoms import IFGMParams
from ifgm_ref.sim.plotting import draw_field_of_view, draw_world
from ifgm_ref.sim.shapes import circle, u_shape
from ifgm_ref.sim.simulator import Run
from ifgm_ref.sim.simulator import simulate as run_episode
from ifgm_ref.sim.world import World

__all__ = [
    "BRANCH_COLOURS",
    "GATE_GAP",
    "PRESETS",
    "Exploration",
    "ExploreSetting",
    "branch_changes",
    "explore_figure",
    "explore_run",
    "explore_world",
    "plot_explore",
]

#: The U's centre (its bounding box's), ft: 38 ft along the line, so that the deepest U
#: allowed (:data:`U_DEPTH_RANGE`) keeps 7.5 ft from the gate and 7 ft from the goal.
U_CENTER: Final = (38.0, 0.0)
#: Wall thickness of the U, ft (``u_trap``'s and Scenario 2's).
U_THICKNESS: Final = 1.0
#: Allowed ``u_width``, ft: from twice the wall and a foot of cavity up to 40 ft, which
#: leaves 15 ft between the U and the arena's side walls (y = +-35 ft) to go round.
U_WIDTH_RANGE: Final = (4.0, 40.0)
#: Allowed ``u_depth``, ft: from two walls' thickness up to 30 ft (see :data:`U_CENTER`).
U_DEPTH_RANGE: Final = (2.0, 30.0)
#: Allowed ``sensor_range``, ft: from four robot diameters (the encounter distance ``d_look``
#: is 8 ft) to twice the paper robot's 15 ft.
SENSOR_RANGE_RANGE: Final = (4.0, 30.0)
#: The gate's posts: x, radius, ft. One on the line, one beside it at +y.
GATE_X: Final = 14.0
GATE_RADIUS: Final = 1.5
#: The gate's gap (between the posts' surfaces), ft: wider than the robot (2 ft) and than
#: IFGM's default ``d_th`` (3 ft), so the default run takes Case-1 there; ``d_th`` >= 4 ft
#: makes it a narrow gap (Case-2).
GATE_GAP: Final = 4.0

#: A fixed colour for every Figure 3 branch, so that panels side by side agree.
BRANCH_COLOURS: Final[dict[Branch, str]] = {
    Branch.MOVE_TO_GOAL: "tab:blue",
    Branch.CASE1_GAP: "tab:green",
    Branch.CASE2_NARROW_GAP: "tab:red",
    Branch.CASE2_ONE_SIDED: "tab:pink",
    Branch.TOO_CLOSE: "tab:brown",
    Branch.CASE3_PREEMPT: "tab:cyan",
    Branch.FOLLOW_EDGE: "tab:orange",
    Branch.DEAD_END_TURN: "tab:purple",
    Branch.DEAD_END_ESCAPE: "tab:gray",
    Branch.DEAD_END_HANDOVER: "gold",
    Branch.PATH_REGENERATED: "tab:olive",
    Branch.GOAL_REACHED: "black",
}

#: The legend label of the markers at branch changes.
CHANGE_LABEL: Final = "branch change (filled: the new branch)"
#: Space left round the obstacles and the path on a plot, ft.
PLOT_MARGIN: Final = 3.0

_PAPER = IFGMParams.paper()


def _within(name: str, value: float, bounds: tuple[float, float]) -> None:
    """Raise :class:`ParameterError` unless ``value`` is a number in ``bounds``."""
    require(name, value)
    if not bounds[0] <= value <= bounds[1]:
        raise ParameterError(f"`{name}` must be in [{bounds[0]}, {bounds[1]}], got {value!r}")


@dataclass(frozen=True)
class ExploreSetting:
    """The six values the sliders set; defaults are the paper robot's (1 ft radius).

    Parameters
    ----------
    d_th : float, default 3.0
        Gap threshold, ft (section 4): > the robot's diameter, 2 ft.
    w_g : float, default 9.0
        Gap weight of eq. (4), ft, > 0.
    w_d : float, default 1.0
        Goal weight of eq. (4), > 0.
    sensor_range : float, default 15.0
        The sensor's ``range_max``, ft, in :data:`SENSOR_RANGE_RANGE`.
    u_width, u_depth : float, default 24.0, 16.0
        The U's outer size across the mouth and from back to mouth, ft, in
        :data:`U_WIDTH_RANGE` and :data:`U_DEPTH_RANGE` (``u_trap``'s U by default).

    Examples
    --------
    >>> ExploreSetting().planner_params()
    {'d_th': 3.0, 'w_g': 9.0, 'w_d': 1.0}
    >>> ExploreSetting(d_th=2.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `d_th` must be > the robot diameter 2.0 (section 4), ...
    >>> ExploreSetting(u_width=50.0)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `u_width` must be in [4.0, 40.0], got 50.0
    """

    d_th: float = _PAPER.d_th
    w_g: float = _PAPER.w_g
    w_d: float = _PAPER.w_d
    sensor_range: float = SensorParams().range_max
    u_width: float = 24.0
    u_depth: float = 16.0

    def __post_init__(self) -> None:
        diameter = 2.0 * resolve_world("u_trap").robot.radius
        if require("d_th", self.d_th, POSITIVE) <= diameter:
            raise ParameterError(
                f"`d_th` must be > the robot diameter {diameter!r} (section 4), got {self.d_th!r}"
            )
        require("w_g", self.w_g, POSITIVE)
        require("w_d", self.w_d, POSITIVE)
        _within("sensor_range", self.sensor_range, SENSOR_RANGE_RANGE)
        _within("u_width", self.u_width, U_WIDTH_RANGE)
        _within("u_depth", self.u_depth, U_DEPTH_RANGE)

    def planner_params(self) -> dict[str, float]:
        """The planner's share of the setting, as ``simulate(..., params=...)`` takes it."""
        return {"d_th": float(self.d_th), "w_g": float(self.w_g), "w_d": float(self.w_d)}


#: The static section's settings: each moves one value from the default, to a value where
#: the run changes visibly.
PRESETS: Final[dict[str, ExploreSetting]] = {
    "default": ExploreSetting(),
    "d_th = 5 ft (gate gap 4 ft now narrow)": ExploreSetting(d_th=5.0),
    "w_g = 40 ft (the gap outweighs the goal)": ExploreSetting(w_g=40.0),
    "sensor range 6 ft": ExploreSetting(sensor_range=6.0),
}


@dataclass(frozen=True)
class Exploration:
    """One run of IFGM for a setting: the setting, the world built for it and the run."""

    setting: ExploreSetting
    world: World
    run: Run


def explore_world(setting: ExploreSetting) -> World:
    """Build the world of ``setting``: ``u_trap``'s arena, the gate and the U (module docs).

    Examples
    --------
    >>> world = explore_world(ExploreSetting(u_width=12.0, u_depth=8.0, sensor_range=6.0))
    >>> len(world.obstacles), world.sensor.range_max
    (3, 6.0)
    >>> [round(v, 9) for v in world.obstacles[-1].geometry.bounds]  # the U, across y = 0
    [34.0, -6.0, 42.0, 6.0]
    """
    arena = resolve_world("u_trap")
    gate_y = 2.0 * GATE_RADIUS + GATE_GAP
    u = u_shape(
        U_CENTER,
        width=setting.u_width,
        depth=setting.u_depth,
        thickness=U_THICKNESS,
        opening=math.pi,
    )
    return replace(
        arena,
        name="explore",
        obstacles=(
            circle((GATE_X, 0.0), GATE_RADIUS),
            circle((GATE_X, gate_y), GATE_RADIUS),
            u,
        ),
        sensor=replace(arena.sensor, range_max=float(setting.sensor_range)),
    )


def explore_run(
    d_th: float = _PAPER.d_th,
    w_g: float = _PAPER.w_g,
    w_d: float = _PAPER.w_d,
    sensor_range: float = SensorParams().range_max,
    u_width: float = 24.0,
    u_depth: float = 16.0,
) -> Exploration:
    """Run IFGM once in :func:`explore_world` with these values (:class:`ExploreSetting`).

    Raises :class:`~ifgm_ref.core.errors.ParameterError` for a value out of its domain. A run
    takes 0.1-0.3 s.

    Examples
    --------
    >>> done = explore_run()
    >>> done.run.result.reached, Branch.CASE1_GAP in {s.branch for s in done.run.trace}
    (True, True)
    """
    setting = ExploreSetting(d_th, w_g, w_d, sensor_range, u_width, u_depth)
    world = explore_world(setting)
    run = run_episode(world, make_planner("ifgm"), params=setting.planner_params())
    return Exploration(setting, world, run)


def branch_changes(run: Run) -> list[int]:
    """Indices of the trace samples whose branch differs from the sample before.

    >>> for d_th in (3.0, 5.0):  # at the gate (4 ft): Case-1, then Case-2 once d_th >= 4 ft
    ...     run = explore_run(d_th=d_th).run
    ...     print(d_th, [str(run.trace[i].branch) for i in branch_changes(run)[:2]])
    3.0 ['case1_gap', 'too_close']
    5.0 ['case2_narrow_gap', 'path_regenerated']
    """
    trace = run.trace
    return [i for i in range(1, len(trace) - 1) if trace[i].branch != trace[i - 1].branch]


def _colour(branch: str | None) -> str:
    """The colour of ``branch`` (white for none: the last sample carries no command)."""
    return "white" if branch is None else BRANCH_COLOURS[Branch(branch)]


def plot_explore(exploration: Exploration, ax: Axes, *, title: str | None = None) -> None:
    """Draw the world, the sensor's reach at the start and the path coloured by branch.

    Every segment of the path takes its :data:`BRANCH_COLOURS` colour; white circles mark
    :func:`branch_changes`. The branches drawn, the changes and the world get legend labels
    (``ax.legend()`` or the figure's legend collects them). ``title`` defaults to the stop
    reason, time and path length.
    """
    world, run = exploration.world, exploration.run
    draw_world(ax, world)
    draw_field_of_view(ax, world, [world.start])
    trace = run.trace
    xy = np.array([(s.x, s.y) for s in trace])
    segments = np.stack([xy[:-1], xy[1:]], axis=1)
    branches = [s.branch for s in trace[:-1]]
    for branch, colour in BRANCH_COLOURS.items():
        mask = np.array([b == branch for b in branches], dtype=bool)
        if mask.any():
            label = branch.replace("_", " ")
            ax.add_collection(
                LineCollection(
                    segments[mask], colors=colour, linewidths=2.2, capstyle="round", label=label
                )
            )
    # Each change filled with the colour of the branch it enters, the earliest on top: a
    # one-step branch (Case-2 at the gate, then straight on) shows under its successors.
    changes = branch_changes(run)[::-1]
    ax.scatter(
        xy[changes, 0],
        xy[changes, 1],
        s=22,
        c=[_colour(trace[i].branch) for i in changes],
        edgecolors="black",
        linewidths=0.7,
        zorder=3,
        label=CHANGE_LABEL,
    )
    _zoom(ax, world, xy)
    r = run.result
    ax.set_title(
        title
        if title is not None
        else f"{r.stop_reason} after {r.time_s:.1f} s, path {r.path_length:.1f} ft",
        fontsize="medium",
    )


def _zoom(ax: Axes, world: World, path: NDArray[np.float64]) -> None:
    """Limit ``ax`` to the obstacles, the start, the goal and ``path``, with a margin."""
    boxes = np.array([ob.geometry.bounds for ob in world.obstacles]).reshape(-1, 4)
    points = np.vstack(
        [path, boxes[:, :2], boxes[:, 2:], [world.start[:2]], [(world.goal.x, world.goal.y)]]
    )
    low, high = points.min(axis=0) - PLOT_MARGIN, points.max(axis=0) + PLOT_MARGIN
    ax.set_xlim(low[0], high[0])
    ax.set_ylim(low[1], high[1])


def explore_figure(explorations: Sequence[tuple[str, Exploration]], *, ncols: int = 2) -> Figure:
    """A grid of :func:`plot_explore` panels, one per ``(title, exploration)``, one legend.

    Each panel's title is its given title over the run's outcome.
    """
    if ncols < 1 or not explorations:
        raise ParameterError(
            f"`ncols` must be >= 1 and `explorations` non-empty, got {ncols}, {len(explorations)}"
        )
    nrows = math.ceil(len(explorations) / ncols)
    fig, axes = plt.subplots(
        nrows, ncols, figsize=(5.0 * ncols + 2.8, 2.9 * nrows), layout="constrained", squeeze=False
    )
    labels: dict[str, Artist] = {}
    for ax, (name, exploration) in zip(axes.flat, explorations, strict=False):
        r = exploration.run.result
        outcome = f"{r.stop_reason} after {r.time_s:.1f} s, {r.path_length:.1f} ft"
        plot_explore(exploration, ax, title=f"{name}\n{outcome}")
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            labels.setdefault(label, handle)
    used = axes.flat[: len(explorations)]
    for ax in axes.flat[len(explorations) :]:
        ax.set_axis_off()
    xs = [x for ax in used for x in ax.get_xlim()]
    ys = [y for ax in used for y in ax.get_ylim()]
    for ax in used:  # the same scale in every panel
        ax.set_xlim(min(xs), max(xs))
        ax.set_ylim(min(ys), max(ys))
    # The world's entries, then the branches in Figure 3's order, then the change marker.
    branches = [b.replace("_", " ") for b in BRANCH_COLOURS]
    order = [k for k in labels if k not in branches and k != CHANGE_LABEL]
    order += [k for k in (*branches, CHANGE_LABEL) if k in labels]
    fig.legend([labels[k] for k in order], order, loc="outside right upper", fontsize="small")
    return fig
