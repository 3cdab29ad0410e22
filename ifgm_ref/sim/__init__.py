"""The simulated world: obstacles and shapes, ray casting, the sensors, collisions, the
engines that move the robot (kinematic, or MuJoCo in :mod:`.physics`), noise, the stall rules,
the simulation loop, the world classes (:mod:`.worldgen`) and plots of runs.

Imports :mod:`ifgm_ref.core` and :mod:`ifgm_ref.paper`; never a planner: the simulator runs
any object that speaks :class:`~ifgm_ref.core.protocol.Planner`.
"""
