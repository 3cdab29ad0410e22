"""A robot with mass: the ``mujoco`` engine (:mod:`ifgm_ref.sim.engine`) on the MuJoCo physics
engine.

:mod:`~ifgm_ref.sim.physics.bodies` gives the robot bodies (the paper's robot and a Jackal-like
one, each value with its source), :mod:`~ifgm_ref.sim.physics.mjcf` builds a world and a body
into a MuJoCo model, :mod:`~ifgm_ref.sim.physics.mujoco` runs it. Only the engine imports
``mujoco`` (the ``physics`` extra: ``pip install 'ifgm-ref[physics]'``); the bodies load
without it, so the command line can list them.
"""
