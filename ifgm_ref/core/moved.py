"""The modules' names before the package's folders showed its layers (issue 44), and a finder
that still imports them, with a :class:`DeprecationWarning` naming the new one.

A script that says ``from ifgm_ref.equations import gap_angle``, or an oracle command line
that says ``--ifgm-equations ifgm_ref.equations``, keeps working: the old name is the new
module itself, not a copy.

>>> import importlib, sys, warnings
>>> _ = sys.modules.pop("ifgm_ref.bags.read", None)  # imported once already, it warns no more
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     old = importlib.import_module("ifgm_ref.bags.read")
>>> old is importlib.import_module("ifgm_ref.io.bags.read")
True
>>> str(caught[-1].message)
'ifgm_ref.bags.read is now ifgm_ref.io.bags.read'
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import warnings
from collections.abc import Sequence
from types import ModuleType

#: Old module (or package) name -> its name now. (``ifgm_ref.paper``, the element index, is
#: now :mod:`ifgm_ref.core.elements`; its old name is the paper's folder.)
MOVED = {
    "ifgm_ref.bags": "ifgm_ref.io.bags",
    "ifgm_ref.bags.plot": "ifgm_ref.apps.replay_plot",
    "ifgm_ref.bags.replay": "ifgm_ref.apps.replay",
    "ifgm_ref.barn": "ifgm_ref.io.barn",
    "ifgm_ref.bench": "ifgm_ref.apps.bench",
    "ifgm_ref.bench.barn": "ifgm_ref.io.barn",
    "ifgm_ref.bench.noise": "ifgm_ref.apps.bench.noise_sweep",
    "ifgm_ref.cache": "ifgm_ref.core.cache",
    "ifgm_ref.cli": "ifgm_ref.apps.cli",
    "ifgm_ref.collision": "ifgm_ref.sim.collision",
    "ifgm_ref.convergence": "ifgm_ref.sim.convergence",
    "ifgm_ref.engine": "ifgm_ref.sim.engine",
    "ifgm_ref.equations": "ifgm_ref.paper.equations",
    "ifgm_ref.errors": "ifgm_ref.core.errors",
    "ifgm_ref.explore": "ifgm_ref.apps.explore",
    "ifgm_ref.figures": "ifgm_ref.apps.figures",
    "ifgm_ref.flowchart": "ifgm_ref.paper.flowchart",
    "ifgm_ref.formulas": "ifgm_ref.core.formulas",
    "ifgm_ref.gazebo": "ifgm_ref.io.gazebo",
    "ifgm_ref.intervals": "ifgm_ref.core.intervals",
    "ifgm_ref.laps": "ifgm_ref.sim.laps",
    "ifgm_ref.laserscan": "ifgm_ref.core.laserscan",
    "ifgm_ref.noise": "ifgm_ref.sim.noise",
    "ifgm_ref.oracle.conformance": "ifgm_ref.oracle.agreement",
    "ifgm_ref.oracle.crash": "ifgm_ref.oracle.counterexample",
    "ifgm_ref.outputs": "ifgm_ref.core.outputs",
    "ifgm_ref.params": "ifgm_ref.core.params",
    "ifgm_ref.percepts": "ifgm_ref.paper.percepts",
    "ifgm_ref.physics": "ifgm_ref.sim.physics",
    "ifgm_ref.physics.engine": "ifgm_ref.sim.physics.mujoco",
    "ifgm_ref.planners.ifgm_atoms": "ifgm_ref.planners.ifgm.atoms",
    "ifgm_ref.planners.ifgm_margins": "ifgm_ref.planners.ifgm.margins",
    "ifgm_ref.planners.ifgm_readings": "ifgm_ref.planners.ifgm.readings",
    "ifgm_ref.plotting": "ifgm_ref.sim.plotting",
    "ifgm_ref.pose": "ifgm_ref.core.pose",
    "ifgm_ref.progress": "ifgm_ref.core.progress",
    "ifgm_ref.protocol": "ifgm_ref.core.protocol",
    "ifgm_ref.raycast": "ifgm_ref.sim.raycast",
    "ifgm_ref.recording": "ifgm_ref.core.recording",
    "ifgm_ref.robot": "ifgm_ref.sim.robot",
    "ifgm_ref.ros": "ifgm_ref.io.ros",
    "ifgm_ref.scenarios": "ifgm_ref.io.scenarios",
    "ifgm_ref.sensor": "ifgm_ref.sim.sensor",
    "ifgm_ref.shapes": "ifgm_ref.sim.shapes",
    "ifgm_ref.simulator": "ifgm_ref.sim.simulator",
    "ifgm_ref.stats": "ifgm_ref.core.stats",
    "ifgm_ref.traceability": "ifgm_ref.paper.traceability",
    "ifgm_ref.transport": "ifgm_ref.io.transport",
    "ifgm_ref.validate": "ifgm_ref.core.validate",
    "ifgm_ref.velocity": "ifgm_ref.core.velocity",
    "ifgm_ref.world": "ifgm_ref.sim.world",
    "ifgm_ref.worldfile": "ifgm_ref.io.worldfile",
    "ifgm_ref.worldgen": "ifgm_ref.sim.worldgen",
}


def new_name(old: str) -> str | None:
    """The name now of module ``old``, or of a module in a package that moved; ``None`` for a
    name that did not move.

    >>> new_name("ifgm_ref.ros.bridge"), new_name("ifgm_ref.oracle.runner")
    ('ifgm_ref.io.ros.bridge', None)
    """
    if old in MOVED:
        return MOVED[old]
    package = old.rpartition(".")[0]
    while package:
        if package in MOVED:
            return f"{MOVED[package]}.{old[len(package) + 1 :]}"
        package = package.rpartition(".")[0]
    return None


class _MovedFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds an old name and loads it as the module of its new name."""

    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if not fullname.startswith("ifgm_ref.") or new_name(fullname) is None:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        new = new_name(spec.name)
        assert new is not None
        warnings.warn(f"{spec.name} is now {new}", DeprecationWarning, stacklevel=2)
        return importlib.import_module(new)

    def exec_module(self, module: ModuleType) -> None:
        """Nothing to run: the module is the new one, run already."""


def install_moved_names() -> None:
    """Let the old names be imported (once per process; the package does it on import).

    First on :data:`sys.meta_path`: a module of a package imported by its old name would
    otherwise be found again by the path finder, in the old package's ``__path__``, and run
    a second time as a copy.
    """
    if not any(isinstance(finder, _MovedFinder) for finder in sys.meta_path):
        sys.meta_path.insert(0, _MovedFinder())
