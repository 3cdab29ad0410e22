"""The figure of a replay: the logged path, where the reference agrees, and the first
divergence with what the robot saw there.

The log holds no map, so the figure draws what the robot saw: every scan's returns, placed
from the pose of their step, sketch the obstacles. The path is green where the reference
agrees with the logged command, red where it differs and grey where nothing was logged; the
first divergence is starred, its scan's returns drawn in full, and arrows from it show the
headings the logged and the reference's turn rates lead to in one second.
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
from numpy.typing import NDArray

from ifgm_ref.bags.replay import ReplayReport, ReplayStep
from ifgm_ref.laserscan import LaserScan
from ifgm_ref.percepts.points import scan_points, to_world
from ifgm_ref.pose import Pose

__all__ = ["plot_replay"]

#: Colours of a step by its verdict: agrees, differs, nothing logged.
VERDICT_COLOURS = {True: "tab:green", False: "tab:red", None: "0.6"}
#: At most this many scans' returns are drawn to sketch the obstacles (evenly spaced).
SKETCH_SCANS = 400
#: The arrows of the two commands at the first divergence, as a share of the path's extent.
ARROW_SHARE = 0.15


def plot_replay(report: ReplayReport) -> Figure:
    """A figure of ``report`` (module docstring), lengths in the log's unit."""
    xy = np.array([(s.pose.x, s.pose.y) for s in report.steps])
    span = np.ptp(xy, axis=0) + 2.0 * report.setting.params.sensor.range_max
    height = min(max(9.0 * span[1] / span[0] + 1.5, 4.0), 9.0)  # the path's shape, legend below
    fig, ax = plt.subplots(figsize=(9.0, height), layout="constrained")
    every = max(1, len(report.steps) // SKETCH_SCANS)
    for step, scan in list(zip(report.steps, report.scans, strict=True))[::every]:
        xs, ys = _returns(step.pose, scan)
        ax.plot(xs, ys, ",", color="0.75")
    _draw_path(ax, report)
    goal, start = report.setting.goal, report.setting.start
    ax.plot(start.x, start.y, "o", color="tab:blue", label="start")
    ax.plot(goal.x, goal.y, "*", color="gold", markersize=15, markeredgecolor="k", label="goal")
    first = report.first_divergence
    if first is not None:
        _draw_divergence(ax, report, first)
    unit = report.setting.unit
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    ax.set_aspect("equal")
    fig.legend(loc="outside lower center", ncols=3, fontsize="small")
    verdict = "agrees throughout" if first is None else f"first divergence at step {first.k}"
    ax.set_title(f"{report.planner} replayed on {Path(report.path).name}: {verdict}")
    return fig


def _draw_path(ax: Axes, report: ReplayReport) -> None:
    xy = np.array([(s.pose.x, s.pose.y) for s in report.steps])
    ax.plot(xy[:, 0], xy[:, 1], "-", color="0.4", linewidth=0.8)
    for verdict, colour in VERDICT_COLOURS.items():
        mask = np.array([s.agrees is verdict for s in report.steps])
        if mask.any():
            label = {True: "agrees", False: "differs", None: "no command logged"}[verdict]
            ax.plot(*xy[mask].T, ".", color=colour, markersize=3, label=f"{label} ({mask.sum()})")


def _draw_divergence(ax: Axes, report: ReplayReport, first: ReplayStep) -> None:
    xs, ys = _returns(first.pose, report.scans[first.k])
    ax.plot(xs, ys, ".", color="tab:purple", markersize=3, label="its scan")
    label = f"first divergence (t={first.t:.2f} s)"
    ax.plot(*first.pose[:2], "*", color="tab:red", markersize=16, markeredgecolor="k", label=label)
    pose = first.pose
    xy = np.array([(s.pose.x, s.pose.y) for s in report.steps])
    length = ARROW_SHARE * max(float(np.ptp(xy[:, 0])), float(np.ptp(xy[:, 1])), 1e-9)
    for command, colour, name in (
        (first.logged, "tab:orange", "logged"),
        (first.reference, "tab:green", "reference"),
    ):
        if command is None:
            continue
        heading = pose.theta + command[1]  # where the turn leads in one second
        tip = (pose.x + length * math.cos(heading), pose.y + length * math.sin(heading))
        arrow = {"arrowstyle": "-|>", "color": colour, "linewidth": 2}
        ax.annotate("", xy=tip, xytext=(pose.x, pose.y), arrowprops=arrow, zorder=5)
        ax.plot([], [], color=colour, linewidth=2, label=f"{name}: heading after 1 s of its turn")


def _returns(pose: Pose, scan: LaserScan) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The world points of ``scan``'s returns seen from ``pose``, as x and y."""
    world = to_world(scan_points(scan).xy, pose)
    return world[:, 0], world[:, 1]
