"""The applications: the command line (:mod:`.cli`), the benchmark (:mod:`.bench`), the
paper's figures, the exploration of parameters, and the replay of a robot's log.

The top layer: it may import every folder below, and nothing imports it.
"""
