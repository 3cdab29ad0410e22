"""Plots and animations of worlds and episodes (matplotlib; feet on both axes, equal aspect).

A run's path is coloured by the planner's behaviour (*move to goal*, *obstacle avoidance*,
section 2.1) or by the Figure 3 branch it took; circles mark where the behaviour switched, and
the sensor's 135-degree field of view (section 4, Figure 2) is drawn at those poses.

A run's plot and animation show :func:`frame`: the world and the path, never the sensor's
reach (BARN's sensor sees 30 m, its world is 4.5 x 10 m); wedges and rays are cut at its edge.
"""

from __future__ import annotations

import math
import textwrap
from collections import Counter
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TypedDict

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation, PillowWriter
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.patches import Circle as CirclePatch
from matplotlib.patches import Polygon as PolygonPatch
from matplotlib.patches import Wedge
from numpy.typing import NDArray

from ifgm_ref.core.progress import progress_bar
from ifgm_ref.sim.sensor import IRSensor
from ifgm_ref.sim.simulator import Result, TraceStep
from ifgm_ref.sim.world import Bounds, Circle, World

OBSTACLE_STYLE = {"facecolor": "0.55", "edgecolor": "0.2", "linewidth": 0.8}
#: Colours of the behaviours; other labels (branches) take the tab10 cycle in order.
BEHAVIOUR_COLOURS = {"move_to_goal": "tab:blue", "obstacle_avoidance": "tab:orange"}
#: At most this many field-of-view wedges on a plot (at the first behaviour switches).
MAX_WEDGES = 6
#: At most this many frames in an animation (the trace is subsampled evenly).
MAX_FRAMES = 120
#: A path label (behaviour or branch) drawn along less than this share of the path's length
#: is marked where each of its runs begins: a line that short cannot be seen.
RARE_SHARE = 0.05
#: The margin :func:`show_frame` leaves around the frame, as a share of each of its sides.
FRAME_MARGIN = 0.05


class MarkerStyle(TypedDict, total=False):
    """Marker keywords of a matplotlib line (``Axes.plot``); none given: no marker."""

    marker: str
    markersize: float
    markeredgecolor: str
    markeredgewidth: float


#: How those runs are marked: a diamond twice as large as a behaviour switch's circle.
RARE_MARKER: MarkerStyle = {
    "marker": "D",
    "markersize": 7,
    "markeredgecolor": "black",
    "markeredgewidth": 0.6,
}


def draw_world(ax: Axes, world: World, *, unit: str = "ft") -> None:
    """Draw the obstacles, the bounds, the start and the goal on ``ax``, each with a legend
    label; axes labelled in ``unit`` (ft in the paper's worlds, m in Gazebo's and BARN's)."""
    for i, ob in enumerate(world.obstacles):
        label = "obstacle" if i == 0 else None
        if isinstance(ob, Circle):
            ax.add_patch(CirclePatch(ob.center, ob.radius, label=label, **OBSTACLE_STYLE))
        else:
            ax.add_patch(PolygonPatch(ob.vertices, closed=True, label=label, **OBSTACLE_STYLE))
    if world.bounds is not None:
        b = world.bounds
        ax.plot(
            [b.xmin, b.xmax, b.xmax, b.xmin, b.xmin],
            [b.ymin, b.ymin, b.ymax, b.ymax, b.ymin],
            color="0.4",
            linewidth=0.8,
            linestyle="--",
            label="bounds",
        )
    sx, sy, _ = world.start
    ax.plot(sx, sy, marker="o", color="tab:green", markersize=8, linestyle="none", label="start")
    ax.plot(*world.goal, marker="*", color="tab:red", markersize=13, linestyle="none", label="goal")
    ax.set_aspect("equal")
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")


def finest_colouring(trace: Sequence[TraceStep]) -> str:
    """``"branch"`` (Figure 3's) when some step of ``trace`` reports one, else ``"behaviour"``:
    a program under test need not report its branch, and a path coloured by a label nobody
    gave is one colour called "none"."""
    return "branch" if any(s.branch for s in trace) else "behaviour"


def _labels(trace: Sequence[TraceStep], colour_by: str) -> list[str]:
    """The label of every segment (sample i to i + 1) of the trace."""
    return [str(getattr(s, colour_by) or "none") for s in trace[:-1]]


def _colours(labels: Sequence[str], *, by_frequency: bool) -> dict[str, str]:
    """A colour per label, in order of first appearance or, ``by_frequency``, most frequent
    first (the dict's order is that order)."""
    cycle = iter(f"C{i}" for i in range(10) if f"C{i}" not in ("C0", "C1"))
    order = [label for label, _ in Counter(labels).most_common()] if by_frequency else labels
    colours: dict[str, str] = {}
    for label in order:
        if label not in colours:
            colours[label] = BEHAVIOUR_COLOURS.get(label) or next(cycle, "0.3")
    return colours


def _run_starts(mask: NDArray[np.bool_]) -> NDArray[np.intp]:
    """Indices where a run of ``True`` in ``mask`` begins."""
    return np.flatnonzero(mask & ~np.concatenate([[False], mask[:-1]]))


def switch_indices(trace: Sequence[TraceStep]) -> list[int]:
    """Indices of the samples where the behaviour differs from the one before."""
    return [i for i in range(1, len(trace) - 1) if trace[i].behaviour != trace[i - 1].behaviour]


#: The legend label of the robot's disc where a path ends.
END_LABEL = "robot at the end"


def draw_path(
    ax: Axes,
    trace: Sequence[TraceStep],
    radius: float,
    *,
    colour_by: str = "behaviour",
    by_frequency: bool = False,
) -> None:
    """Draw the path coloured by ``behaviour`` or ``branch``, switch points and the robot's
    disc at the end (legend label :data:`END_LABEL`).

    By default each label's legend entry is its name, in order of first appearance (the paper
    figures merge them across panels). With ``by_frequency`` the entries go by how many steps
    took the label, most first, with the count; and a label whose stretches of path are
    together shorter than :data:`RARE_SHARE` of the path (a one-step branch, a turn on the
    spot) is also marked where each of its runs begins, so that it can be seen.
    """
    xy = np.array([(s.x, s.y) for s in trace])
    if len(xy) > 1:
        labels = _labels(trace, colour_by)
        segments = np.stack([xy[:-1], xy[1:]], axis=1)
        lengths = np.hypot(*(segments[:, 1] - segments[:, 0]).T)
        for label, colour in _colours(labels, by_frequency=by_frequency).items():
            mask = np.array([lab == label for lab in labels])
            name, steps = label.replace("_", " "), int(mask.sum())
            if not by_frequency:
                lines = LineCollection(segments[mask], colors=colour, linewidths=2.0, label=name)
                ax.add_collection(lines)
                continue
            ax.add_collection(LineCollection(segments[mask], colors=colour, linewidths=2.0))
            rare = lengths[mask].sum() < RARE_SHARE * lengths.sum() or not lengths.any()
            if rare:
                starts = xy[_run_starts(mask)]
                ax.plot(starts[:, 0], starts[:, 1], linestyle="none", color=colour, **RARE_MARKER)
            ax.plot(  # the legend's entry: a line, and the marker if the label is marked
                [],
                [],
                color=colour,
                linewidth=2.0,
                label=f"{name} ({steps} step{'s' if steps > 1 else ''})",
                **(RARE_MARKER if rare else MarkerStyle()),
            )
    switches = switch_indices(trace)
    if switches:
        ax.plot(
            xy[switches, 0],
            xy[switches, 1],
            "o",
            markerfacecolor="white",
            markeredgecolor="black",
            markersize=5,
            linestyle="none",
            label="behaviour switch",
        )
    end = CirclePatch(tuple(xy[-1]), radius, fill=False, edgecolor="black", label=END_LABEL)
    ax.add_patch(end)


def draw_field_of_view(ax: Axes, world: World, poses: Sequence[tuple[float, float, float]]) -> None:
    """Shade the sensor's field of view (``range_max``, ``fov``) at each pose."""
    fov, reach = world.sensor.fov, world.sensor.range_max
    for i, (x, y, theta) in enumerate(poses):
        ax.add_patch(
            Wedge(
                (x, y),
                reach,
                math.degrees(theta - fov / 2),
                math.degrees(theta + fov / 2),
                alpha=0.12,
                color="tab:purple",
                label="field of view" if i == 0 else None,
            )
        )


def frame(world: World, trace: Sequence[TraceStep]) -> Bounds:
    """The rectangle a plot of ``world`` and ``trace`` shows.

    The smallest rectangle that holds the world's bounds (if any), obstacles, start and goal,
    and the robot's disc (``world.robot.radius``) at every true and believed pose of
    ``trace`` (:func:`show_frame` adds a margin). The sensor's reach plays no part.

    Parameters
    ----------
    world : World
        The world drawn.
    trace : sequence of TraceStep
        The path drawn (may be empty).

    Returns
    -------
    Bounds
        The frame, in the world's unit.
    """
    corners = [world.start[:2], tuple(world.goal)]
    if world.bounds is not None:
        corners += [world.bounds[:2], world.bounds[2:]]
    for ob in world.obstacles:
        if isinstance(ob, Circle):
            corners += [(ob.center[0] - ob.radius, ob.center[1] - ob.radius)]
            corners += [(ob.center[0] + ob.radius, ob.center[1] + ob.radius)]
        else:
            corners += list(ob.vertices)
    radius = world.robot.radius
    for s in trace:
        for x, y in ((s.x, s.y), (s.believed_x, s.believed_y)):
            if x is not None and y is not None:
                corners += [(x - radius, y - radius), (x + radius, y + radius)]
    xy = np.array(corners, dtype=float)
    return Bounds(*xy.min(axis=0), *xy.max(axis=0))


def show_frame(ax: Axes, box: Bounds) -> None:
    """Show ``box`` on ``ax`` with a margin of :data:`FRAME_MARGIN` at equal scales, the
    axes' box kept: the data limits become ``box``, and the view widens one of its sides to
    the box's shape. Anything drawn beyond (a sensor's wedges and rays) is cut at the edge.
    Draw nothing on ``ax`` afterwards: its data limits would grow."""
    ax.ignore_existing_data_limits = True
    ax.update_datalim([(box.xmin, box.ymin), (box.xmax, box.ymax)])
    # Matplotlib's equal scales by data limits count on margins of 5 %: with none, each
    # layout pass of the figure widens the view anew.
    ax.margins(FRAME_MARGIN)
    # Equal scales by widening the data limits, not by shrinking the box: the layout keeps
    # its box, and the labels and the legend beside it stay within the figure.
    ax.set_aspect("equal", adjustable="datalim")
    ax.autoscale_view()


def _engine_note(engine: str | None) -> str:
    """The title's words for ``engine``: none without one."""
    return "" if engine is None else f" ({engine} engine)"


#: The legend label of :func:`draw_believed_path`'s dashed line.
BELIEVED_LABEL = "believed path (odometry)"


def draw_believed_path(ax: Axes, trace: Sequence[TraceStep]) -> bool:
    """Draw where the planner believed the robot was (its odometry: odometry noise,
    ``docs/noise.md``, or a physics engine's) as a dashed line labelled
    :data:`BELIEVED_LABEL`, if anywhere it was not where the robot was; return whether it
    drew."""
    believed = [(s.believed_x, s.believed_y) for s in trace]
    if all(b == (s.x, s.y) for b, s in zip(believed, trace, strict=True)):
        return False
    xy = np.array(believed, dtype=float)
    ax.plot(xy[:, 0], xy[:, 1], color="0.3", linestyle="--", linewidth=1.0, label=BELIEVED_LABEL)
    return True


#: The longest line of a run's title, characters: a ``--cmd`` program's path makes titles of
#: any length, and a title wider than the axes runs into the legend beside them (at the
#: default 12 pt, 60 characters fit the axes of :func:`plot_run`'s 9.5 in figure). A longer
#: title puts the outcome on a line of its own.
TITLE_WIDTH = 60


def plot_run(
    world: World,
    trace: Sequence[TraceStep],
    result: Result,
    *,
    colour_by: str = "behaviour",
    unit: str = "ft",
    mark: int | None = None,
    engine: str | None = None,
) -> Figure:
    """A figure of one episode: world, path by behaviour (or branch), switches, field of view,
    and the believed path where the odometry moved it off the true one; lengths in ``unit``.

    The axes show :func:`frame` (the world and the path, not the sensor's reach), and every
    line, marker and shade drawn has a legend entry. ``mark`` is a step to point at (the
    oracle's first divergence); ``engine`` the engine that moved the robot
    (:data:`ifgm_ref.core.params.ENGINES`), named in the title, or ``None`` to name none.
    """
    fig, ax = plt.subplots(figsize=(9.5, 5), layout="constrained")
    draw_world(ax, world, unit=unit)
    wedges = [(trace[i].x, trace[i].y, trace[i].theta) for i in switch_indices(trace)[:MAX_WEDGES]]
    draw_field_of_view(ax, world, wedges)
    draw_path(ax, trace, world.robot.radius, colour_by=colour_by, by_frequency=True)
    draw_believed_path(ax, trace)
    if mark is not None:
        step = trace[mark]
        ax.plot(step.x, step.y, "X", color="red", markersize=12, label=f"step {mark}")
    show_frame(ax, frame(world, trace))
    name = world.name or "world"
    run = f"{result.planner} in {name}{_engine_note(engine)}:"
    outcome = (
        f"{result.stop_reason} after {result.time_s:.1f} s, path {result.path_length:.1f} {unit}"
    )
    if len(run) + 1 + len(outcome) <= TITLE_WIDTH:
        ax.set_title(f"{run} {outcome}")
    else:  # the run on its line(s), the outcome on its own
        ax.set_title(f"{textwrap.fill(run, TITLE_WIDTH)}\n{textwrap.fill(outcome, TITLE_WIDTH)}")
    fig.legend(loc="outside right upper", fontsize="small")
    return fig


def save_figure(fig: Figure, path: str | Path) -> None:
    """Write ``fig`` to ``path`` (format from the suffix) and close it."""
    fig.savefig(path, dpi=120)
    plt.close(fig)


def animate_run(
    world: World,
    trace: Sequence[TraceStep],
    result: Result,
    path: str | Path,
    *,
    fps: int = 12,
    max_frames: int = MAX_FRAMES,
    progress: bool | None = None,
    unit: str = "ft",
    engine: str | None = None,
) -> int:
    """Write a GIF of the episode: the robot, its scan rays and the path so far, in
    :func:`frame` (the rays cut at its edge).

    The scan is re-cast from each sample's pose with the world's sensor (as the planner saw
    it, noise aside). A bar on stderr counts the frames rendered (rendering takes about
    0.15 s a frame): ``progress=None`` shows it on a terminal and writes a line every 10 s
    to a log (:func:`ifgm_ref.core.progress.progress_bar`), ``True`` always, ``False`` never.
    Lengths are labelled in ``unit``; ``engine`` (as in :func:`plot_run`) is named in the
    title. Returns the number of frames written (at most ``max_frames``).
    """
    frames = np.unique(np.linspace(0, len(trace) - 1, min(len(trace), max_frames)).astype(int))
    fig, show = _animation(world, trace, result, unit, engine)
    with progress_bar(  # every frame shown: each takes some 0.15 s to render
        total=len(frames),
        unit="frame",
        desc="GIF",
        progress=progress,
        leave=False,
        mininterval=0.0,
        miniters=1,
    ) as bar:
        FuncAnimation(fig, show, frames=frames).save(
            path, writer=PillowWriter(fps=fps), progress_callback=lambda i, n: bar.update()
        )
    plt.close(fig)
    return len(frames)


def _animation(
    world: World, trace: Sequence[TraceStep], result: Result, unit: str, engine: str | None
) -> tuple[Figure, Callable[[int], None]]:
    """Draw what stays in every frame of :func:`animate_run`'s GIF; return the figure and the
    function that shows sample ``k`` of ``trace`` in it: the path so far, the robot, its scan
    rays and a title with the time and the branch (or behaviour; the stop reason at the last
    sample, which has neither)."""
    sensor = IRSensor(world)
    fig, ax = plt.subplots(figsize=(8.5, 4.5), layout="constrained")
    draw_world(ax, world, unit=unit)
    xs = np.array([s.x for s in trace])
    ys = np.array([s.y for s in trace])
    (line,) = ax.plot([], [], color="tab:blue", linewidth=1.6, label=f"{result.planner} path")
    rays = LineCollection([], colors="tab:red", linewidths=0.5, alpha=0.6, label="scan rays")
    ax.add_collection(rays)
    disc = CirclePatch(
        (xs[0], ys[0]), world.robot.radius, fill=False, edgecolor="black", label="robot"
    )
    ax.add_patch(disc)
    show_frame(ax, frame(world, trace))
    title = ax.set_title("")
    fig.legend(loc="outside right upper", fontsize="small")
    heading = f"{result.planner} in {world.name or 'world'}{_engine_note(engine)}"

    def show(k: int) -> None:
        s = trace[k]
        line.set_data(xs[: k + 1], ys[: k + 1])
        disc.center = (s.x, s.y)
        scan = sensor.scan((s.x, s.y, s.theta))  # type: ignore[arg-type]
        reach = np.where(np.isfinite(scan.ranges), scan.ranges, scan.range_max)
        angles = s.theta + scan.angles
        ends = np.column_stack([s.x + reach * np.cos(angles), s.y + reach * np.sin(angles)])
        rays.set_segments([[(s.x, s.y), tuple(e)] for e in ends])
        doing = s.branch or s.behaviour or (result.stop_reason if k == len(trace) - 1 else None)
        title.set_text(f"{heading}: t = {s.t:.1f} s" + (f", {doing}" if doing else ""))

    return fig, show
