"""The dynamic window's trajectories and their costs, as base_local_planner scores them.

Reference
---------
D. Fox, W. Burgard, S. Thrun, "The dynamic window approach to collision avoidance", *IEEE
Robotics & Automation Magazine* 4(1):23-33, 1997; as ROS 1 ``base_local_planner``'s
``TrajectoryPlanner`` implements it (``dwa: true``): ``createTrajectories`` samples the
window, ``generateTrajectory`` rolls each sample out and scores it.

The window round the current velocity ``(vx, vth)`` over one control period ``T``::

    vx  in [max(min_vel_x, vx - acc_lim_x T),  max(min(max_vel_x, vx + acc_lim_x T), min_vel_x)]
    vth in [max(-max_vel_theta, vth - acc_lim_theta T), min(max_vel_theta, vth + acc_lim_theta T)]

sampled at ``vx_samples`` evenly spaced speeds, each with ``vth = 0`` first and then
``vtheta_samples - 1`` evenly spaced turn rates from the lowest; then ``vtheta_samples``
turns in place (``vx = 0``), each at least ``min_in_place_vel_theta``.

A sample is simulated for ``sim_time`` in ``n = int(max(|vx| sim_time / sim_granularity,
|vth| / angular_sim_granularity) + 0.5)`` steps (at least 1; ROS's formula, the angular term
without ``sim_time``), the velocity moving towards the sample at the acceleration limits,
the position advanced along the heading, then the heading turned. The ``n`` points before
each step are checked: a point outside the window, on a lethal or inscribed cell, or from
which MapGrid finds no way to the plan or the local goal makes the trajectory illegal. The
cost of a legal one, with ``meter_scoring`` (every scale multiplied by the cell size ``c``)::

    cost = c (pdist_scale path_dist + gdist_scale goal_dist + occdist_scale occ)

``path_dist`` and ``goal_dist`` are MapGrid's distances (cells) at the last point and ``occ``
the largest costmap cost along the trajectory.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ifgm_ref.planners.costmap import INSCRIBED

__all__ = ["Rollout", "Samples", "Window", "legal_costs", "rollout", "samples"]


@dataclass(frozen=True)
class Window:
    """The velocity limits and sampling of :func:`samples` (ROS's names)."""

    min_vel_x: float
    max_vel_x: float
    max_vel_theta: float
    min_in_place_vel_theta: float
    acc_lim_x: float
    acc_lim_theta: float
    vx_samples: int
    vtheta_samples: int


@dataclass(frozen=True, eq=False)
class Samples:
    """The sampled velocities, in TrajectoryPlanner's order: forward ones first."""

    vx: NDArray[np.float64]
    vth: NDArray[np.float64]
    forward: int  #: how many of them move forward (the rest turn in place)
    dvth: float  #: the spacing of the sampled turn rates
    raw_vth: NDArray[np.float64]  #: the turn rates before ``min_in_place_vel_theta``


def samples(
    window: Window, vx: float, vth: float, period: float, max_speed: float | None = None
) -> Samples:
    """The dynamic window's samples round the current ``(vx, vth)``; ``max_speed`` caps
    ``max_vel_x`` (ROS: the final goal's distance over ``sim_time``).

    Examples
    --------
    >>> w = Window(0.1, 0.5, 1.57, 0.314, 10.0, 20.0, 6, 20)
    >>> s = samples(w, 0.0, 0.0, 0.05)
    >>> s.vx[:6].round(2).tolist(), s.forward, len(s.vx), round(s.dvth, 4)
    ([0.1, 0.1, 0.1, 0.1, 0.1, 0.1], 120, 140, 0.1053)
    >>> sorted(set(s.vx.round(2).tolist()))
    [0.0, 0.1, 0.18, 0.26, 0.34, 0.42, 0.5]
    >>> float(s.vth[1]), float(abs(s.vth[120:]).min()) >= 0.314
    (-1.0, True)
    """
    top = window.max_vel_x if max_speed is None else min(window.max_vel_x, max_speed)
    hi_x = max(min(top, vx + window.acc_lim_x * period), window.min_vel_x)
    lo_x = max(window.min_vel_x, vx - window.acc_lim_x * period)
    hi_th = min(window.max_vel_theta, vth + window.acc_lim_theta * period)
    lo_th = max(-window.max_vel_theta, vth - window.acc_lim_theta * period)
    nx, nth = window.vx_samples, window.vtheta_samples
    dvx = (hi_x - lo_x) / (nx - 1) if nx > 1 else 0.0
    dvth = (hi_th - lo_th) / (nth - 1) if nth > 1 else 0.0
    turns = lo_th + dvth * np.arange(nth - 1)
    speeds = lo_x + dvx * np.arange(nx)
    fwd_vth = np.concatenate(([0.0], turns))
    fwd_x = np.repeat(speeds, len(fwd_vth))
    fwd_th = np.tile(fwd_vth, nx)
    raw = lo_th + dvth * np.arange(nth)
    least = window.min_in_place_vel_theta
    spin = np.where(raw > 0.0, np.maximum(raw, least), np.minimum(raw, -least))
    return Samples(
        np.concatenate((fwd_x, np.zeros(nth))),
        np.concatenate((fwd_th, spin)),
        len(fwd_x),
        dvth,
        np.concatenate((fwd_th, raw)),
    )


@dataclass(frozen=True, eq=False)
class Rollout:
    """Simulated trajectories: ``(samples, steps)`` poses, ``valid`` where a step exists."""

    x: NDArray[np.float64]
    y: NDArray[np.float64]
    theta: NDArray[np.float64]
    valid: NDArray[np.bool_]


def _approach(
    v0: float, target: NDArray[np.float64], change: NDArray[np.float64]
) -> NDArray[np.float64]:
    """base_local_planner's ``computeNewVelocity``: from ``v0`` towards ``target`` by at most
    ``change``."""
    return np.where(target >= v0, np.minimum(target, v0 + change), np.maximum(target, v0 - change))


def rollout(
    pose: tuple[float, float, float],
    velocity: tuple[float, float],
    chosen: Samples,
    window: Window,
    *,
    sim_time: float,
    granularity: float,
    angular_granularity: float,
) -> Rollout:
    """Simulate every sample of ``chosen`` from ``pose`` at the current ``velocity``.

    Examples
    --------
    Straight at 0.5 m/s for 2 s in steps of 0.02 m: 50 points, the last 0.98 m ahead.

    >>> w = Window(0.1, 0.5, 1.57, 0.314, 10.0, 20.0, 1, 1)
    >>> one = Samples(np.array([0.5]), np.array([0.0]), 1, 0.0, np.array([0.0]))
    >>> r = rollout((0.0, 0.0, 0.0), (0.5, 0.0), one, w, sim_time=2.0, granularity=0.02,
    ...             angular_granularity=0.02)
    >>> int(r.valid.sum()), round(float(r.x[0, 49]), 6)
    (50, 0.98)
    """
    vx, vth = chosen.vx, chosen.vth
    steps = np.maximum(
        (
            np.maximum(np.abs(vx) * sim_time / granularity, np.abs(vth) / angular_granularity) + 0.5
        ).astype(np.int64),
        1,
    )
    most = int(steps.max())
    dt = (sim_time / steps)[:, np.newaxis]
    k = np.arange(1, most + 1)[np.newaxis, :]
    vel_x = _approach(velocity[0], vx[:, np.newaxis], window.acc_lim_x * dt * k)
    vel_th = _approach(velocity[1], vth[:, np.newaxis], window.acc_lim_theta * dt * k)
    theta = np.empty((len(vx), most))
    theta[:, 0] = pose[2]
    theta[:, 1:] = pose[2] + np.cumsum(vel_th[:, :-1] * dt, axis=1)
    x = np.empty_like(theta)
    y = np.empty_like(theta)
    x[:, 0], y[:, 0] = pose[0], pose[1]
    x[:, 1:] = pose[0] + np.cumsum((vel_x * np.cos(theta) * dt)[:, :-1], axis=1)
    y[:, 1:] = pose[1] + np.cumsum((vel_x * np.sin(theta) * dt)[:, :-1], axis=1)
    valid = np.arange(most)[np.newaxis, :] < steps[:, np.newaxis]
    return Rollout(x, y, theta, valid)


def legal_costs(
    cells: tuple[NDArray[np.intp], NDArray[np.intp]],
    valid: NDArray[np.bool_],
    cost: NDArray[np.uint8],
    path_dist: NDArray[np.int32],
    goal_dist: NDArray[np.int32],
    scales: tuple[float, float, float],
) -> NDArray[np.float64]:
    """Each trajectory's cost (``scales`` = ``c pdist_scale, c gdist_scale,
    c occdist_scale``), ``nan`` where it is illegal (see the module docstring).

    ``cells`` are the window's rows and columns of every point (any value outside it).

    Examples
    --------
    Three trajectories of two points on a 1 x 3 window: the one ending nearer the goal costs
    less; the one through an inscribed cell is illegal.

    >>> cost = np.array([[0, 10, 253]], dtype=np.uint8)
    >>> to_goal = np.array([[2, 1, 0]], dtype=np.int32)
    >>> on_path = np.zeros((1, 3), dtype=np.int32)
    >>> rows = np.zeros((3, 2), dtype=np.intp)
    >>> cols = np.array([[0, 0], [0, 1], [1, 2]])
    >>> valid = np.ones((3, 2), dtype=bool)
    >>> legal_costs((rows, cols), valid, cost, on_path, to_goal, (1, 1, 0.01)).tolist()
    [2.0, 1.1, nan]
    """
    rows, cols = cells
    height, width = cost.shape
    inside = (rows >= 0) & (rows < height) & (cols >= 0) & (cols < width)
    r, c = np.where(inside, rows, 0), np.where(inside, cols, 0)
    point_cost = cost[r, c]
    impossible = path_dist.size
    pd, gd = path_dist[r, c], goal_dist[r, c]
    bad = ~inside | (point_cost >= INSCRIBED) | (pd >= impossible) | (gd >= impossible)
    illegal = (bad & valid).any(axis=1)
    occ = np.where(valid, point_cost, 0).max(axis=1)
    last = valid.sum(axis=1) - 1
    row = np.arange(len(last))
    pdist, gdist, occdist = scales
    total = pdist * pd[row, last] + gdist * gd[row, last] + occdist * occ
    return np.where(illegal, np.nan, total.astype(np.float64))
