"""The figure of a replay: the logged path, where the reference agrees, and the first
divergence with what the robot saw there.

The log holds no map, so the figure draws what the robot saw: every scan's returns, placed
from the pose of their step, sketch the obstacles. The path is green where the reference
agrees with the logged command, red where it differs and grey where nothing was logged; the
first divergence is starred, its scan's returns drawn in full, and arrows from it show the
headings the logged and the reference's turn rates lead to in one second. The axes frame the
returns, the path, the start and the goal with a small margin, as a run's plot does
(:func:`ifgm_ref.sim.plotting.show_frame`), never the sensor's reach; everything drawn has a
legend entry.
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from numpy.typing import NDArray

from ifgm_ref.apps.replay import ReplayReport, ReplayStep
from ifgm_ref.core.laserscan import LaserScan
from ifgm_ref.core.pose import Pose
from ifgm_ref.paper.percepts.points import scan_points, to_world
from ifgm_ref.sim.plotting import show_frame
from ifgm_ref.sim.world import Bounds

__all__ = ["plot_replay"]

#: Colours of a step by its verdict: agrees, differs, nothing logged.
VERDICT_COLOURS = {True: "tab:green", False: "tab:red", None: "0.6"}
#: At most this many scans' returns are drawn to sketch the obstacles (evenly spaced).
SKETCH_SCANS = 400
#: The arrows of the two commands at the first divergence, as a share of the path's extent.
ARROW_SHARE = 0.15
#: The figure's width, in; its height follows the frame's shape (between the two limits).
FIGURE_WIDTH = 9.0
HEIGHT_LIMITS = (4.0, 9.0)


def plot_replay(report: ReplayReport) -> Figure:
    """A figure of ``report`` (module docstring), lengths in the log's unit.

    Parameters
    ----------
    report : ReplayReport
        The replay drawn.

    Returns
    -------
    Figure
        Its axes frame the drawn returns, the path, the start and the goal (plus a margin),
        whatever the sensor's range; its height follows that frame's shape.
    """
    every = max(1, len(report.steps) // SKETCH_SCANS)
    sketched = list(zip(report.steps, report.scans, strict=True))[::every]
    returns = np.vstack([np.empty((0, 2)), *(_returns(s.pose, scan) for s, scan in sketched)])
    box = _frame(report, returns)
    shape = (box.ymax - box.ymin) / max(box.xmax - box.xmin, 1e-9)
    # the axes' width is the figure's but the y label's inch; title, x label and legend
    # below take some 2.2 in of height
    height = min(max((FIGURE_WIDTH - 1.0) * shape + 2.2, HEIGHT_LIMITS[0]), HEIGHT_LIMITS[1])
    fig, ax = plt.subplots(figsize=(FIGURE_WIDTH, height), layout="constrained")
    scans = f"{len(sketched)} scan{'s' if len(sketched) > 1 else ''}"
    label = f"scan returns ({scans}{'' if every == 1 else f', one in {every}'})"
    # dots small enough to draw a wall, dark enough to be seen
    ax.plot(*returns.T, ".", color="0.45", markersize=1.0, alpha=0.6, label=label)
    _draw_path(ax, report)
    goal, start = report.setting.goal, report.setting.start
    ax.plot(start.x, start.y, "o", color="tab:blue", label="start", zorder=4)  # over a star
    ax.plot(goal.x, goal.y, "*", color="gold", markersize=15, markeredgecolor="k", label="goal")
    first = report.first_divergence
    if first is not None:
        _draw_divergence(ax, report, first)
    unit = report.setting.unit
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    show_frame(ax, box)
    legend = fig.legend(loc="outside lower center", ncols=3, fontsize="small")
    for text, handle in zip(legend.get_texts(), legend.legend_handles, strict=True):
        if text.get_text() == label and isinstance(handle, Line2D):
            handle.set_markersize(6)  # a return's dot, large enough to be seen in the legend
    verdict = "agrees throughout" if first is None else f"first divergence at step {first.k}"
    ax.set_title(f"{report.planner} replayed on {Path(report.path).name}: {verdict}")
    return fig


def _frame(report: ReplayReport, returns: NDArray[np.float64]) -> Bounds:
    """The smallest rectangle that holds ``returns``, the path, the start, the goal and, at
    the first divergence, its scan's returns and the tips of its arrows."""
    points = [returns, np.array([(s.pose.x, s.pose.y) for s in report.steps])]
    points.append(np.array([report.setting.start[:2], tuple(report.setting.goal)]))
    if report.first_divergence is not None:
        first = report.first_divergence
        points.append(_returns(first.pose, report.scans[first.k]))
        points += [np.array([tip]) for _, _, tip in _arrows(report, first)]
    xy = np.vstack(points)
    return Bounds(*xy.min(axis=0), *xy.max(axis=0))


def _draw_path(ax: Axes, report: ReplayReport) -> None:
    """The logged path, a dot per step in its verdict's colour."""
    xy = np.array([(s.pose.x, s.pose.y) for s in report.steps])
    ax.plot(xy[:, 0], xy[:, 1], "-", color="0.4", linewidth=0.8, label="logged path")
    for verdict, colour in VERDICT_COLOURS.items():
        mask = np.array([s.agrees is verdict for s in report.steps])
        if mask.any():
            label = {True: "agrees", False: "differs", None: "no command logged"}[verdict]
            ax.plot(*xy[mask].T, ".", color=colour, markersize=3, label=f"{label} ({mask.sum()})")


def _draw_divergence(ax: Axes, report: ReplayReport, first: ReplayStep) -> None:
    """The first divergence: its star, its scan's returns and the two commands' arrows."""
    seen = _returns(first.pose, report.scans[first.k])
    if len(seen):
        ax.plot(*seen.T, ".", color="tab:purple", markersize=3, label="its scan's returns")
    label = f"first divergence (t={first.t:.2f} s)"
    ax.plot(*first.pose[:2], "*", color="tab:red", markersize=16, markeredgecolor="k", label=label)
    for name, colour, tip in _arrows(report, first):
        width = 4.0 if name == "logged" else 1.6  # the logged one shows under the other
        arrow = {"arrowstyle": "-|>", "color": colour, "linewidth": width}
        ax.annotate("", xy=tip, xytext=first.pose[:2], arrowprops=arrow, zorder=5)
        ax.plot(
            [], [], color=colour, linewidth=width, label=f"{name}: heading after 1 s of its turn"
        )


def _arrows(report: ReplayReport, first: ReplayStep) -> list[tuple[str, str, tuple[float, float]]]:
    """The arrows of the logged and the reference's commands at ``first`` (those there are):
    name, colour and tip, :data:`ARROW_SHARE` of the path's extent from the pose along the
    heading the command's turn leads to in one second."""
    pose = first.pose
    xy = np.array([(s.pose.x, s.pose.y) for s in report.steps])
    length = ARROW_SHARE * max(float(np.ptp(xy[:, 0])), float(np.ptp(xy[:, 1])), 1e-9)
    arrows = []
    for command, colour, name in (
        (first.logged, "tab:orange", "logged"),
        (first.reference, "tab:green", "reference"),
    ):
        if command is not None:
            heading = pose.theta + command[1]
            tip = (pose.x + length * math.cos(heading), pose.y + length * math.sin(heading))
            arrows.append((name, colour, tip))
    return arrows


def _returns(pose: Pose, scan: LaserScan) -> NDArray[np.float64]:
    """The world points of ``scan``'s returns seen from ``pose``, one ``(x, y)`` a row."""
    return np.asarray(to_world(scan_points(scan).xy, pose), dtype=np.float64)
