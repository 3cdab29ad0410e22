"""The ``rospy`` a node imports under ifgm-ref: the stand-in (:mod:`ifgm_ref.io.ros.rospy_api`,
:mod:`ifgm_ref.io.ros.params_log`, :mod:`ifgm_ref.io.ros.services`)."""

from ifgm_ref.io.ros.params_log import *  # noqa: F403
from ifgm_ref.io.ros.rospy_api import *  # noqa: F403
from ifgm_ref.io.ros.rospy_api import ROSException
from ifgm_ref.io.ros.services import *  # noqa: F403

ROSInitException = ROSException
ROSSerializationException = ROSException
