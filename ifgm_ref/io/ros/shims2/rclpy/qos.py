"""``rclpy.qos`` under ifgm-ref: profiles are accepted, not acted on."""

import enum

from ifgm_ref.io.ros.rclpy_api import QoSProfile as QoSProfile

qos_profile_sensor_data = QoSProfile(depth=5)
qos_profile_system_default = QoSProfile(depth=10)
qos_profile_services_default = QoSProfile(depth=10)


class ReliabilityPolicy(enum.Enum):
    """Accepted, not acted on."""

    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2


class HistoryPolicy(enum.Enum):
    """Accepted, not acted on."""

    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2


class DurabilityPolicy(enum.Enum):
    """Accepted, not acted on."""

    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2
