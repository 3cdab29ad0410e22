"""The package's folders are its layers, and the imports keep to them.

Bottom up: ``core`` (foundations), ``paper`` (equations, Figure 3, percepts), ``planners`` and
``sim`` side by side, ``io``, ``oracle``, ``apps`` (docs/architecture.md). A module imports from
its own folder and the folders below only, function-level imports included; ``planners`` and
``sim`` never import each other.

That is the paper's "no prior map" rule made structural (section 3: "No priori information or
map of the environment is required since the decisions are based on current percepts"): the
planners, and the paper and the foundations below them, cannot reach the world, the sensor,
the simulator or anything above them.

Within the layers: the transport (the JSON-lines protocol, planners found by name) and the
ROS stand-in serve the oracle, the command line and the benchmark alike and import none of
them; the oracle and the benchmark import each other not at all. No module imports itself
through others (no import cycle), and the oracle is layered in its turn: what is checked and
how examples are drawn, then the checks, then what runs them.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "ifgm_ref"
#: The layers, bottom up: the folders of ``ifgm_ref`` and their floor. Folders on one floor
#: stand side by side and never import each other.
FLOORS = {"core": 0, "paper": 1, "planners": 2, "sim": 2, "io": 3, "oracle": 4, "apps": 5}
#: The package's own face (``__init__``, which installs the old names) and ``python -m``.
ROOT_MODULES = {"ifgm_ref", "ifgm_ref.__main__"}
#: What knows the map: a planner reaches none of it.
MAP_AWARE = (
    "ifgm_ref.sim",
    "ifgm_ref.io.worldfile",
    "ifgm_ref.io.gazebo",
    "ifgm_ref.io.barn",
    "ifgm_ref.io.scenarios",
    "ifgm_ref.io.bags",
    "ifgm_ref.oracle",
    "ifgm_ref.apps",
)
#: The map-free layers, whose whole import closure avoids MAP_AWARE: the planners and all
#: below them; the transport (both ends of the JSON-lines protocol see what a planner sees,
#: and planners are found by name) and the ROS stand-in and its broker (the same).
MAP_FREE_PREFIXES = (
    "ifgm_ref.core",
    "ifgm_ref.paper",
    "ifgm_ref.planners",
    "ifgm_ref.io.transport",
    "ifgm_ref.io.ros",
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
    return any(_within(module, aware) for aware in MAP_AWARE)


def _within(module: str, prefix: str) -> bool:
    return module == prefix or module.startswith(prefix + ".")


#: (layer, what it must never reach, why): each layer's whole import closure avoids the other.
#: Only what the floors allow and these forbid: a lower folder never reaches a higher one.
SEPARATE = [
    ("ifgm_ref.apps.bench", "ifgm_ref.oracle", "both take worlds and bounds from sim/"),
    ("ifgm_ref.apps.cli.simulate", "ifgm_ref.oracle", "a run, in process or through --cmd"),
    ("ifgm_ref.apps.cli.bench", "ifgm_ref.oracle", "the benchmark does without the oracle"),
    ("ifgm_ref.apps.cli.serve", "ifgm_ref.oracle", "a planner served needs no oracle"),
    ("ifgm_ref.apps.cli.common", "ifgm_ref.oracle", "what every subcommand shares"),
]


def test_the_validator_sits_below_everything_it_checks() -> None:
    """:mod:`ifgm_ref.core.validate`, which the equations, the parameters, the protocol and the
    command line all call, imports nothing of the project but its errors."""
    assert set(_closure("ifgm_ref.core.validate")) == {"ifgm_ref.core.errors"}


def test_map_free_layers_exist() -> None:
    assert "ifgm_ref.planners" in MAP_FREE
    assert "ifgm_ref.paper.flowchart" in MAP_FREE
    assert "ifgm_ref.planners.straight" in MAP_FREE
    assert "ifgm_ref.io.transport.wire" in MAP_FREE
    assert "ifgm_ref.io.transport.loading" in MAP_FREE
    for layer, other, _ in SEPARATE:
        assert any(_within(m, layer) for m in MODULES), layer
        assert any(_within(m, other) for m in MODULES), other


def _floor(module: str) -> tuple[str, int] | None:
    """The folder of ``module`` and its floor; ``None`` for the package's root modules."""
    if module in ROOT_MODULES:
        return None
    folder = module.split(".")[1]
    assert folder in FLOORS, f"{module} is in no layer's folder: place it in one of {FLOORS}"
    return folder, FLOORS[folder]


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m not in ROOT_MODULES))
def test_each_module_imports_its_own_folder_and_the_folders_below(module: str) -> None:
    here = _floor(module)
    assert here is not None
    for dep in GRAPH[module]:
        there = _floor(dep)
        if there is None or there[0] == here[0]:
            continue
        assert there[1] < here[1], (
            f"{module} ({here[0]}, floor {here[1]}) imports {dep} "
            f"({there[0]}, floor {there[1]}): a folder imports only the folders below it"
        )


def test_the_folder_check_has_teeth() -> None:
    GRAPH["ifgm_ref.sim.world"].add("ifgm_ref.planners.fgm")
    try:
        with pytest.raises(AssertionError, match="imports only the folders below"):
            test_each_module_imports_its_own_folder_and_the_folders_below("ifgm_ref.sim.world")
    finally:
        GRAPH["ifgm_ref.sim.world"].discard("ifgm_ref.planners.fgm")


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
    GRAPH["ifgm_ref.planners.straight"].add("ifgm_ref.sim.sensor")
    try:
        assert "ifgm_ref.sim.sensor" in _closure("ifgm_ref.planners")
    finally:
        GRAPH["ifgm_ref.planners.straight"].discard("ifgm_ref.sim.sensor")


def test_the_separation_has_teeth() -> None:
    GRAPH["ifgm_ref.apps.bench.runner"].add("ifgm_ref.oracle.checks")
    try:
        with pytest.raises(AssertionError, match=r"ifgm_ref\.oracle\.checks"):
            test_layers_stay_apart("ifgm_ref.apps.bench", "ifgm_ref.oracle", "test")
    finally:
        GRAPH["ifgm_ref.apps.bench.runner"].discard("ifgm_ref.oracle.checks")


#: The oracle's layers, bottom up: what is checked and how examples are drawn; the checks;
#: what runs them. A module imports oracle modules of its own layer or below only.
ORACLE_LAYERS = (
    (
        "ifgm_ref.oracle.suite",  # the suite's package (a docstring)
        "ifgm_ref.oracle.stable_draws",
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
        "ifgm_ref.oracle.agreement",
        "ifgm_ref.oracle.dead_end",
        "ifgm_ref.oracle.equation_checks",
        "ifgm_ref.oracle.invariance",
        "ifgm_ref.oracle.robust",
        "ifgm_ref.oracle.suite.recorded",
    ),
    (
        "ifgm_ref.oracle",  # the package's face: check() runs the runner
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
