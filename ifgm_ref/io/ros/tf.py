"""``tf.transformations``' quaternion and Euler-angle functions, for nodes under the stand-in.

Quaternions are ``[x, y, z, w]`` as ROS orders them, Euler angles are roll, pitch, yaw about
the static axes x, y, z (``axes="sxyz"``, ROS's default and the only one offered here):
the rotation is ``Rz(yaw) Ry(pitch) Rx(roll)``. Results are numpy arrays, as ROS's are.

>>> q = quaternion_from_euler(0.0, 0.0, 1.0)
>>> [round(float(v), 12) for v in euler_from_quaternion(q)]
[0.0, 0.0, 1.0]
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "euler_from_quaternion",
    "quaternion_conjugate",
    "quaternion_from_euler",
    "quaternion_inverse",
    "quaternion_multiply",
]


def _axes(axes: str) -> None:
    if axes != "sxyz":
        raise NotImplementedError(f"axes {axes!r}: the stand-in offers 'sxyz' (ROS's default) only")


def quaternion_from_euler(
    ai: float, aj: float, ak: float, axes: str = "sxyz"
) -> NDArray[np.float64]:
    """The quaternion ``[x, y, z, w]`` of roll ``ai``, pitch ``aj``, yaw ``ak`` (rad)."""
    _axes(axes)
    cr, sr = math.cos(ai / 2), math.sin(ai / 2)
    cp, sp = math.cos(aj / 2), math.sin(aj / 2)
    cy, sy = math.cos(ak / 2), math.sin(ak / 2)
    return np.array(
        [
            sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy,
        ]
    )


def euler_from_quaternion(
    quaternion: Sequence[float], axes: str = "sxyz"
) -> tuple[float, float, float]:
    """Roll, pitch and yaw (rad) of the quaternion ``[x, y, z, w]`` (normalised first)."""
    _axes(axes)
    x, y, z, w = (float(v) for v in quaternion)
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    if norm == 0.0:
        return 0.0, 0.0, 0.0
    x, y, z, w = x / norm, y / norm, z / norm, w / norm
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2.0 * (w * y - z * x))))
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return roll, pitch, yaw


def quaternion_multiply(q1: Sequence[float], q0: Sequence[float]) -> NDArray[np.float64]:
    """The product ``q1 * q0`` (rotate by ``q0``, then by ``q1``)."""
    x0, y0, z0, w0 = q0
    x1, y1, z1, w1 = q1
    return np.array(
        [
            w1 * x0 + x1 * w0 + y1 * z0 - z1 * y0,
            w1 * y0 - x1 * z0 + y1 * w0 + z1 * x0,
            w1 * z0 + x1 * y0 - y1 * x0 + z1 * w0,
            w1 * w0 - x1 * x0 - y1 * y0 - z1 * z0,
        ],
        dtype=np.float64,
    )


def quaternion_conjugate(quaternion: Sequence[float]) -> NDArray[np.float64]:
    """The conjugate ``[-x, -y, -z, w]``."""
    x, y, z, w = quaternion
    return np.array([-x, -y, -z, w], dtype=np.float64)


def quaternion_inverse(quaternion: Sequence[float]) -> NDArray[np.float64]:
    """The inverse rotation."""
    q = np.asarray(quaternion, dtype=np.float64)
    return quaternion_conjugate(q.tolist()) / float(np.dot(q, q))
