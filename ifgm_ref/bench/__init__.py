"""The benchmark: every planner on many worlds, against the shortest collision-free path.

:mod:`~ifgm_ref.bench.optimal` computes the physical limit, :mod:`~ifgm_ref.bench.tasks`
names and runs one world's episodes, :mod:`~ifgm_ref.bench.runner` spreads them over local
processes or a Dask cluster, :mod:`~ifgm_ref.bench.report` writes the table, the summary and
the plots. ``ifgm-ref bench`` is the command line (docs/benchmark.md).
"""
