"""The benchmark: every planner on many worlds, against the shortest collision-free path.

:mod:`~ifgm_ref.apps.bench.optimal` computes the physical limit, :mod:`~ifgm_ref.apps.bench.tasks`
names and runs one world's episodes, :mod:`~ifgm_ref.apps.bench.runner` spreads them over local
processes or a Dask cluster, :mod:`~ifgm_ref.apps.bench.report` writes the table, the summary and
the plots. ``ifgm-ref bench`` is the command line (docs/benchmark.md).

:mod:`~ifgm_ref.apps.bench.soak` runs the soak, thousands of drawn worlds per class to bound each
planner's failure rate, and :mod:`~ifgm_ref.apps.bench.soak_report` tallies it;
``benchmarks/bench_soak.py`` is its command line (benchmarks/README.md).
"""
