"""ROS bag I/O: a simulated run as a ROS 2 bag (MCAP or sqlite3) or a ROS 1 bag, and back.

Writing (``ifgm-ref simulate --record FILE``; ``docs/bags.md``):
:mod:`ifgm_ref.io.bags.record` keeps what a planner was handed and answered during a run,
:mod:`ifgm_ref.io.bags.messages` turns it into standard ROS messages (REP-103 units, REP-105
frames) and :mod:`ifgm_ref.io.bags.write` writes them. :mod:`ifgm_ref.io.bags.read` reads bags back.
"""
