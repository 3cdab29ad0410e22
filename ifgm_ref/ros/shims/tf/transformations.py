"""``tf.transformations`` under ifgm-ref (:mod:`ifgm_ref.ros.tf`)."""

from ifgm_ref.ros.tf import *  # noqa: F403
from ifgm_ref.ros.tf import __all__ as __all__
