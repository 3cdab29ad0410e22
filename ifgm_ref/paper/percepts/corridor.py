"""Is the straight path towards a point free? The corridor test behind IBA's leaving rule.

Section 4.1: "the robot continuously monitors the obstacles in the path toward destination
during edge detection. The leaving point is selected based on free path". A path is free when
no obstacle point lies in the corridor as wide as the robot (plus a margin) along it, as far
as the robot has looked.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

#: Each point's offset from an origin: the arrays ``x - x0`` and ``y - y0``.
Offsets = tuple[NDArray[np.float64], NDArray[np.float64]]


def offsets(points: NDArray[np.float64], origin: tuple[float, float]) -> Offsets:
    """Each point's offset from ``origin``: ``(x - x0, y - y0)``, two arrays.

    >>> offsets(np.array([[3.0, 4.0]]), (1.0, 1.0))
    (array([2.]), array([3.]))
    """
    return points[:, 0] - origin[0], points[:, 1] - origin[1]


def _along_across(
    relative: Offsets, direction: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Each point's coordinates in the frame at its origin facing ``direction``: how far
    along that direction, and how far to its left."""
    c, s = math.cos(direction), math.sin(direction)
    dx, dy = relative
    return c * dx + s * dy, -s * dx + c * dy


def free_length(
    points: NDArray[np.float64],
    origin: tuple[float, float],
    direction: float,
    half_width: float,
    *,
    relative: Offsets | None = None,
) -> float:
    """How far the corridor of ``half_width`` from ``origin`` along ``direction`` is free.

    Returns the distance along the corridor's axis to the first point inside it (``inf`` if
    there is none). Points behind ``origin`` do not count; callers keep their own stand-off
    from the returned length.

    Parameters
    ----------
    points : (n, 2) array
        Obstacle points, same frame as ``origin`` and ``direction``.
    origin : (x, y)
        Where the corridor starts.
    direction : float
        Its direction, radians.
    half_width : float
        Half its width, ft (the robot radius plus a margin).
    relative : Offsets, optional
        ``offsets(points, origin)``, when the caller has them already (several corridors
        from one origin share them).

    Examples
    --------
    >>> pts = np.array([[5.0, 0.5], [3.0, 4.0], [-2.0, 0.0]])
    >>> free_length(pts, (0.0, 0.0), 0.0, 1.0)
    5.0
    >>> free_length(pts, (0.0, 0.0), math.pi / 2, 1.0)
    inf
    """
    if len(points) == 0:
        return math.inf
    along, across = _along_across(relative or offsets(points, origin), direction)
    inside = (along >= 0.0) & (np.abs(across) < half_width)
    return float(along[inside].min()) if inside.any() else math.inf


def disc_travel(
    points: NDArray[np.float64],
    origin: tuple[float, float],
    direction: float,
    radius: float,
    *,
    relative: Offsets | None = None,
) -> float:
    """How far a disc of ``radius`` centred at ``origin`` can move along ``direction`` before
    it touches one of ``points`` (``inf`` if never; 0 if one is inside it already).

    A point at ``along`` ahead and ``across`` to the side, ``|across| < radius``, is touched
    after ``along - sqrt(radius**2 - across**2)``; points behind the centre only recede.
    ``relative`` is ``offsets(points, origin)``, when the caller has them already.

    >>> pts = np.array([[5.0, 0.6], [3.0, 4.0], [-2.0, 0.0]])
    >>> disc_travel(pts, (0.0, 0.0), 0.0, 1.0)
    4.2
    >>> disc_travel(pts, (0.0, 0.0), math.pi, 1.0), disc_travel(pts, (4.5, 0.6), 0.0, 1.0)
    (1.0, 0.0)
    """
    if len(points) == 0:
        return math.inf
    along, across = _along_across(relative or offsets(points, origin), direction)
    ahead = (along >= 0.0) & (np.abs(across) < radius)
    if not ahead.any():
        return math.inf
    touch = along[ahead] - np.sqrt(radius * radius - across[ahead] ** 2)
    return max(0.0, float(touch.min()))
