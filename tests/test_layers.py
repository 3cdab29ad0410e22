"""The paper's "no prior map" rule made structural: planners cannot reach what knows the map.

Section 3: "No priori information or map of the environment is required since the decisions
are based on current percepts." Planners (and the equations, percepts and flowchart layers
below them) must not import, directly or through other modules of ours, the world, the
sensor, the simulator or anything above them.
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
}
#: The map-free layers: their whole import closure must avoid MAP_AWARE.
MAP_FREE_PREFIXES = (
    "ifgm_ref.planners",
    "ifgm_ref.equations",
    "ifgm_ref.percepts",
    "ifgm_ref.flowchart",
    "ifgm_ref.protocol",
    "ifgm_ref.laserscan",
    # the protocol over JSON lines: both of its ends see what a planner sees, nothing more
    "ifgm_ref.wire",
    "ifgm_ref.serve",
    "ifgm_ref.oracle.external",
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


def test_map_free_layers_exist() -> None:
    assert "ifgm_ref.planners" in MAP_FREE
    assert "ifgm_ref.planners.straight" in MAP_FREE
    assert "ifgm_ref.wire" in MAP_FREE


@pytest.mark.paper("s3.no_map")
@pytest.mark.parametrize("module", MAP_FREE)
def test_planner_layers_never_import_the_map(module: str) -> None:
    reached = _closure(module)
    leaks = {dep: via for dep, via in reached.items() if dep in MAP_AWARE}
    assert not leaks, f"{module} reaches map-aware modules (module <- imported by): {leaks}"


def test_the_check_has_teeth() -> None:
    GRAPH["ifgm_ref.planners.straight"].add("ifgm_ref.sensor")
    try:
        assert "ifgm_ref.sensor" in _closure("ifgm_ref.planners")
    finally:
        GRAPH["ifgm_ref.planners.straight"].discard("ifgm_ref.sensor")
