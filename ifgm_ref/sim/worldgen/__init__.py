"""World generation: the navigation problems of the world classes, solvable by construction.

=====================  ====================================================================
module                 what it is
=====================  ====================================================================
:mod:`.classes`        the classes (open, U, H, symmetric, mixed, enclosed, gap wall), each a
                       function of a :class:`~.draws.Draw`; :func:`~.classes.random_world`,
                       a world of a class from a seed; :func:`~.classes.solvable`
:mod:`.draws`          the two sources of a generator's choices: Hypothesis (for the oracle's
                       strategies, :mod:`ifgm_ref.oracle.strategies`; failing worlds shrink)
                       or a seeded numpy generator (for the benchmark, :mod:`ifgm_ref.apps.bench`)
=====================  ====================================================================

The oracle and the benchmark both build on this package and it imports neither
(``tests/test_layers.py``).
"""
