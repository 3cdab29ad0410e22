"""``tf.transformations`` under ifgm-ref (:mod:`ifgm_ref.io.ros.tf`)."""

from ifgm_ref.io.ros.tf import *  # noqa: F403
from ifgm_ref.io.ros.tf import __all__ as __all__
