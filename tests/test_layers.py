"""The paper's "no prior map" rule made structural: planners cannot reach what knows the map.

Section 3: "No priori information or map of the environment is required since the decisions
are based on current percepts." Planners (and the equations, percepts and flowchart layers
below them) must not import, directly or through other modules of ours, the world, the
sensor, the simulator or anything above them.

The same import graph keeps the layers above apart: the transport (the JSON-lines protocol,
planners found by name) serves the oracle, the command line and the benchmark alike and
imports none of them; the world classes and the time bound serve the oracle and the
benchmark, which import each other not at all. No module imports itself through others (no
import cycle, function-level imports included), and the oracle is layered: what is checked
and how examples are drawn, then the checks, then what runs them.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "ifgm_ref"
#: Modules that know the map or sit above the planners.
MAP_AWARE = {
    "ifgm_ref.world",
    "ifgm_ref.worldfile",
    "ifgm_ref.shapes",
    "ifgm_ref.scenarios",
    "ifgm_ref.raycast",
    "ifgm_ref.sensor",
    "ifgm_ref.collision",
    "ifgm_ref.simulator",
    "ifgm_ref.plotting",
    "ifgm_ref.cli",
    "ifgm_ref.convergence",
}
#: Packages that know the map or sit above the planners, every module in them.
MAP_AWARE_PACKAGES = ("ifgm_ref.cli.", "ifgm_ref.worldgen", "ifgm_ref.oracle", "ifgm_ref.bench")
#: The map-free layers: their whole import closure must avoid MAP_AWARE.
MAP_FREE_PREFIXES = (
    "ifgm_ref.planners",
    "ifgm_ref.equations",
    "ifgm_ref.percepts",
    "ifgm_ref.flowchart",
    "ifgm_ref.protocol",
    "ifgm_ref.laserscan",
    # the protocol over JSON lines: both of its ends see what a planner sees, nothing more;
    # and planners found by name
    "ifgm_ref.transport",
    # unchanged ROS nodes as a planner: the stand-in and its broker see what a planner sees
    "ifgm_ref.ros",
)


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _imports(path: Path) -> set[str]:
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            found.add(node.module)
            found.update(f"{node.module}.{alias.name}" for alias in node.names)
    return {name for name in found if name.startswith("ifgm_ref")}


MODULES = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
GRAPH = {name: {i for i in _imports(path) if i in MODULES} for name, path in MODULES.items()}


def _closure(start: str) -> dict[str, str]:
    """Every module reachable from ``start``, with the module that imports it."""
    seen: dict[str, str] = {}
    todo = [start]
    while todo:
        here = todo.pop()
        for dep in GRAPH.get(here, set()):
            if dep not in seen and dep != start:
                seen[dep] = here
                todo.append(dep)
    return seen


MAP_FREE = sorted(m for m in MODULES if m.startswith(MAP_FREE_PREFIXES))


def _map_aware(module: str) -> bool:
    return module in MAP_AWARE or module.startswith(MAP_AWARE_PACKAGES)


def _within(module: str, prefix: str) -> bool:
    return module == prefix or module.startswith(prefix + ".")


#: (layer, what it must never reach, why): each layer's whole import closure avoids the other.
SEPARATE = [
    ("ifgm_ref.transport", "ifgm_ref.oracle", "the oracle uses the transport, not the reverse"),
    ("ifgm_ref.transport", "ifgm_ref.bench", "the benchmark uses the transport"),
    ("ifgm_ref.transport", "ifgm_ref.cli", "the command line uses the transport"),
    ("ifgm_ref.ros", "ifgm_ref.oracle", "the oracle runs ROS nodes, not the reverse"),
    ("ifgm_ref.ros", "ifgm_ref.cli", "the command line runs ROS nodes"),
    ("ifgm_ref.ros", "ifgm_ref.bench", "the benchmark does without ROS nodes"),
    ("ifgm_ref.bench", "ifgm_ref.oracle", "both take worlds and bounds from worldgen, convergence"),
    ("ifgm_ref.oracle", "ifgm_ref.bench", "both take worlds and bounds from worldgen, convergence"),
    ("ifgm_ref.worldgen", "ifgm_ref.oracle", "the oracle's strategies wrap the generators"),
    ("ifgm_ref.worldgen", "ifgm_ref.bench", "the benchmark samples the generators"),
    ("ifgm_ref.convergence", "ifgm_ref.oracle", "the oracle and the benchmark use the bound"),
    ("ifgm_ref.convergence", "ifgm_ref.bench", "the oracle and the benchmark use the bound"),
    ("ifgm_ref.cli.simulate", "ifgm_ref.oracle", "a run, in process or through --cmd"),
    ("ifgm_ref.cli.bench", "ifgm_ref.oracle", "the benchmark does without the oracle"),
    ("ifgm_ref.cli.serve", "ifgm_ref.oracle", "a planner served needs no oracle"),
    ("ifgm_ref.cli.common", "ifgm_ref.oracle", "what every subcommand shares"),
    ("ifgm_ref.simulator", "ifgm_ref.planners", "it runs any planner; formulas: ifgm_ref.formulas"),
    ("ifgm_ref.laps", "ifgm_ref.planners", "the lap rule's thresholds are formulas too"),
    ("ifgm_ref.formulas", "ifgm_ref.planners", "below the planners and the simulator"),
]


def test_the_validator_sits_below_everything_it_checks() -> None:
    """:mod:`ifgm_ref.validate`, which the equations, the parameters, the protocol and the
    command line all call, imports nothing of the project but its errors."""
    assert set(_closure("ifgm_ref.validate")) == {"ifgm_ref.errors"}


def test_map_free_layers_exist() -> None:
    assert "ifgm_ref.planners" in MAP_FREE
    assert "ifgm_ref.planners.straight" in MAP_FREE
    assert "ifgm_ref.transport.wire" in MAP_FREE
    assert "ifgm_ref.transport.loading" in MAP_FREE
    for layer, other, _ in SEPARATE:
        assert any(_within(m, layer) for m in MODULES), layer
        assert any(_within(m, other) for m in MODULES), other


@pytest.mark.paper("s3.no_map")
@pytest.mark.parametrize("module", MAP_FREE)
def test_planner_layers_never_import_the_map(module: str) -> None:
    reached = _closure(module)
    leaks = {dep: via for dep, via in reached.items() if _map_aware(dep)}
    assert not leaks, f"{module} reaches map-aware modules (module <- imported by): {leaks}"


@pytest.mark.parametrize(("layer", "other", "why"), SEPARATE)
def test_layers_stay_apart(layer: str, other: str, why: str) -> None:
    for module in (m for m in MODULES if _within(m, layer)):
        reached = _closure(module)
        leaks = {dep: via for dep, via in reached.items() if _within(dep, other)}
        assert not leaks, f"{module} reaches {other} ({why}; module <- imported by): {leaks}"


def test_the_check_has_teeth() -> None:
    GRAPH["ifgm_ref.planners.straight"].add("ifgm_ref.sensor")
    try:
        assert "ifgm_ref.sensor" in _closure("ifgm_ref.planners")
    finally:
        GRAPH["ifgm_ref.planners.straight"].discard("ifgm_ref.sensor")


def test_the_separation_has_teeth() -> None:
    GRAPH["ifgm_ref.transport.wire"].add("ifgm_ref.oracle.checks")
    try:
        with pytest.raises(AssertionError, match=r"ifgm_ref\.oracle\.checks"):
            test_layers_stay_apart("ifgm_ref.transport", "ifgm_ref.oracle", "test")
    finally:
        GRAPH["ifgm_ref.transport.wire"].discard("ifgm_ref.oracle.checks")


#: The oracle's layers, bottom up: what is checked and how examples are drawn; the checks;
#: what runs them. A module imports oracle modules of its own layer or below only.
ORACLE_LAYERS = (
    (
        "ifgm_ref.oracle",  # the package itself (an empty __init__)
        "ifgm_ref.oracle.suite",  # the suite's package (a docstring)
        "ifgm_ref.oracle.stable_draws",
        "ifgm_ref.oracle.crash",
        "ifgm_ref.oracle.workers",
        "ifgm_ref.oracle.implementation",
        "ifgm_ref.oracle.check_types",
        "ifgm_ref.oracle.profiles",
        "ifgm_ref.oracle.specification",
        "ifgm_ref.oracle.domains",
        "ifgm_ref.oracle.strategies",
        "ifgm_ref.oracle.percept_strategies",
        "ifgm_ref.oracle.metamorphic",
        "ifgm_ref.oracle.mutants",
        "ifgm_ref.oracle.variants",
        "ifgm_ref.oracle.vectors",
        "ifgm_ref.oracle.suite.cases",
        "ifgm_ref.oracle.suite.versions",
        "ifgm_ref.oracle.suite.report",
        "ifgm_ref.oracle.suite.runfile",
    ),
    (
        "ifgm_ref.oracle.episodes",
        "ifgm_ref.oracle.braking",
        "ifgm_ref.oracle.checks",
        "ifgm_ref.oracle.conformance",
        "ifgm_ref.oracle.dead_end",
        "ifgm_ref.oracle.equation_checks",
        "ifgm_ref.oracle.invariance",
        "ifgm_ref.oracle.robust",
        "ifgm_ref.oracle.suite.recorded",
    ),
    (
        "ifgm_ref.oracle.runner",
        "ifgm_ref.oracle.counterexample",
        "ifgm_ref.oracle.pytest_plugin",
        "ifgm_ref.oracle.test_conformance",
        "ifgm_ref.oracle.suite.run",
        "ifgm_ref.oracle.suite.tiers",
        "ifgm_ref.oracle.suite.build",
    ),
)


#: The oracle's packages, whose modules have layers of their own.
_PACKAGES = ("ifgm_ref.oracle", "ifgm_ref.oracle.suite")


def _oracle_layer(module: str) -> int:
    for level, members in enumerate(ORACLE_LAYERS):
        if any(module == m or (m not in _PACKAGES and _within(module, m)) for m in members):
            return level
    raise AssertionError(f"{module} is in no layer of ORACLE_LAYERS: place it there")


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """An import cycle of ``graph`` (its modules in order, the first repeated), or ``None``."""
    done: set[str] = set()
    path: list[str] = []

    def visit(module: str) -> list[str] | None:
        if module in path:
            return [*path[path.index(module) :], module]
        if module in done:
            return None
        path.append(module)
        for dep in sorted(graph.get(module, ())):
            if (found := visit(dep)) is not None:
                return found
        path.pop()
        done.add(module)
        return None

    for module in sorted(graph):
        if (found := visit(module)) is not None:
            return found
    return None


def test_the_package_has_no_import_cycle() -> None:
    """Function-level imports count: a cycle hidden in one is a cycle all the same."""
    cycle = _cycle(GRAPH)
    assert cycle is None, f"import cycle: {' -> '.join(cycle or [])}"


@pytest.mark.parametrize("module", sorted(m for m in MODULES if _within(m, "ifgm_ref.oracle")))
def test_oracle_modules_import_only_their_layer_or_below(module: str) -> None:
    level = _oracle_layer(module)
    above = sorted(
        dep
        for dep in GRAPH[module]
        if _within(dep, "ifgm_ref.oracle") and _oracle_layer(dep) > level
    )
    assert not above, f"{module} (layer {level}) imports a higher layer: {above}"


def test_the_cycle_check_has_teeth() -> None:
    GRAPH["ifgm_ref.oracle.implementation"].add("ifgm_ref.oracle.checks")
    try:
        assert _cycle(GRAPH) is not None
        with pytest.raises(AssertionError, match="imports a higher layer"):
            test_oracle_modules_import_only_their_layer_or_below("ifgm_ref.oracle.implementation")
    finally:
        GRAPH["ifgm_ref.oracle.implementation"].discard("ifgm_ref.oracle.checks")
