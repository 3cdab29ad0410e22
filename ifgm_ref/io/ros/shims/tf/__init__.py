"""The ``tf`` a node imports under ifgm-ref: ``tf.transformations`` only."""

from ifgm_ref.io.ros import tf as transformations

__all__ = ["transformations"]
