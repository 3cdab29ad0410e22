"""Planners across a process boundary, and Python planners found by name.

=====================  ====================================================================
module                 what it is
=====================  ====================================================================
:mod:`.wire`           the JSON-lines codec of ``docs/oracle-protocol.md``: messages as lines
:mod:`.external`       :class:`~.external.ExternalPlanner`, a planner whose decisions come from
                       a program speaking the protocol (``--cmd`` of ``ifgm-ref simulate`` and
                       ``ifgm-ref oracle``)
:mod:`.pipes`          a program's stdin and stdout as lines, every wait bounded (polled
                       on POSIX, threaded elsewhere)
:mod:`.serve`          the program's end around any Python planner (``ifgm-ref serve``)
:mod:`.loading`        a Python planner from its name: built-in or ``module:attribute``
=====================  ====================================================================

Both ends see what a planner sees and nothing more: this package imports neither the map
(world, sensor, simulator) nor the oracle (``tests/test_layers.py``).
"""
