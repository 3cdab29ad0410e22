"""Plots of worlds and episodes (matplotlib; feet on both axes, equal aspect)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Circle as CirclePatch
from matplotlib.patches import Polygon as PolygonPatch

from ifgm_ref.simulator import Result, TraceStep
from ifgm_ref.world import Circle, World

OBSTACLE_STYLE = {"facecolor": "0.55", "edgecolor": "0.2", "linewidth": 0.8}


def draw_world(ax: Axes, world: World) -> None:
    """Draw the obstacles, the bounds, the start (with its heading) and the goal on ``ax``."""
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
        )
    sx, sy, _ = world.start
    ax.plot(sx, sy, marker="o", color="tab:green", markersize=8, linestyle="none", label="start")
    ax.plot(*world.goal, marker="*", color="tab:red", markersize=13, linestyle="none", label="goal")
    ax.set_aspect("equal")
    ax.set_xlabel("x (ft)")
    ax.set_ylabel("y (ft)")


def draw_path(ax: Axes, trace: Sequence[TraceStep], radius: float, *, label: str = "path") -> None:
    """Draw the robot's path and its disc at the last pose."""
    xs = [s.x for s in trace]
    ys = [s.y for s in trace]
    ax.plot(xs, ys, color="tab:blue", linewidth=1.6, label=label)
    ax.add_patch(CirclePatch((xs[-1], ys[-1]), radius, fill=False, edgecolor="tab:blue"))


def plot_run(world: World, trace: Sequence[TraceStep], result: Result) -> Figure:
    """A figure of one episode: world, path, final robot disc, and the outcome in the title."""
    fig, ax = plt.subplots(figsize=(8, 5), layout="constrained")
    draw_world(ax, world)
    draw_path(ax, trace, world.robot.radius, label=f"{result.planner} path")
    ax.autoscale_view()
    name = world.name or "world"
    ax.set_title(
        f"{result.planner} in {name}: {result.stop_reason} after {result.time_s:.1f} s, "
        f"path {result.path_length:.1f} ft"
    )
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small")
    return fig


def save_figure(fig: Figure, path: str | Path) -> None:
    """Write ``fig`` to ``path`` (format from the suffix) and close it."""
    fig.savefig(path, dpi=120)
    plt.close(fig)
