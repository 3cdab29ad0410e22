"""The mutator of ``benchmarks/bench_mutation.py`` (issue 26): every site it lists is one change
of one node of the decision code, the changed source parses, and nothing else moves.

The benchmark is a script (``benchmarks/`` is not a package), loaded here from its path.
"""

from __future__ import annotations

import ast
import difflib
import importlib.util
import random
import sys
from collections import Counter
from pathlib import Path
from types import ModuleType

import pytest

BENCHMARKS = Path(__file__).resolve().parent.parent / "benchmarks"


@pytest.fixture(scope="module")
def bench() -> ModuleType:
    spec = importlib.util.spec_from_file_location(
        "bench_mutation", BENCHMARKS / "bench_mutation.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["bench_mutation"] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_every_operator_has_sites_in_the_decision_code(bench: ModuleType) -> None:
    every = [site for file in bench.FILES for site in bench.sites(file)]
    kinds = Counter(site.operator for site in every)
    assert set(kinds) == {"comparison", "arithmetic", "boolean", "negation", "constant"}
    assert len(every) == len(set(every)), "a site listed twice"


def test_a_mutant_changes_one_node_and_parses(bench: ModuleType) -> None:
    """Forty sites drawn with a fixed seed: the mutated source parses and differs from the
    original, unparsed the same way, in exactly one line, the site's."""
    every = [site for file in bench.FILES for site in bench.sites(file)]
    for site in random.Random(7).sample(every, 40):
        original = ast.unparse(ast.parse((bench.PACKAGE / site.file).read_text()))
        mutated = bench.mutated_source(site)
        ast.parse(mutated)
        changed = [
            line
            for line in difflib.unified_diff(original.splitlines(), mutated.splitlines(), n=0)
            if line.startswith(("+", "-")) and not line.startswith(("+++", "---"))
        ]
        assert len(changed) == 2, (site, changed)


def test_docstrings_and_annotations_are_left_alone(bench: ModuleType) -> None:
    """The flowchart's docstring examples (``>>> ...``) and its ``-> Branch`` are no sites."""
    tree = ast.parse((bench.PACKAGE / "paper" / "flowchart.py").read_text())
    nodes = list(ast.walk(tree))
    for site in bench.sites("paper/flowchart.py"):
        node = nodes[site.node]
        assert not (isinstance(node, ast.Constant) and isinstance(node.value, str))


def test_the_trace_filter_tells_rounding_from_change(bench: ModuleType) -> None:
    """Mutant #8 of seed 0 (``k == 0`` to ``k == 1`` in the clearance filter) wraps every
    heading once more: the traces differ in the 17th digit, which is rounding, not a change."""
    row = "15.3,20.2,0.018,0.157,-0.00045419758861878033,1.3,move_to_goal,path_regenerated"
    wrapped = row.replace("78033", "75437")
    assert bench.trace_change([row], [row]) == "same"
    assert bench.trace_change([row], [wrapped]) == "rounding"
    assert bench.trace_change([row], [row.replace("path_regenerated", "follow_edge")]) == "changed"
    assert bench.trace_change([row], [row.replace("20.2", "20.3")]) == "changed"
    assert bench.trace_change([row], [row, row]) == "changed"


def test_only_names_numbers_of_the_draw_and_refuses_others(bench: ModuleType) -> None:
    """``--only`` resumes a run cut short: ranges and single numbers, each a mutant drawn."""
    assert bench._numbers("78-80,5,79", 100) == [5, 78, 79, 80]
    for wrong in ("0", "99-101", "x", "3-"):
        with pytest.raises(SystemExit, match="--only"):
            bench._numbers(wrong, 100)
