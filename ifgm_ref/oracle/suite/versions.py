"""The suite's versions on disk: where they are, and one loaded with its cases.

Each version is a folder of ``ifgm_ref/oracle/suite/`` (``v1``, ``v2``, ...): a manifest
(``manifest.json``: the protocol version, the tolerances and the drawing it was built from),
one case file per property (:mod:`.cases`), the equation vectors and traces
(``vectors.json``) and a changelog. A version never changes once released; old ones stay
runnable (docs/oracle.md, "The conformance suite").
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.oracle.suite.cases import TIERS, Case, read_cases

__all__ = ["SUITES", "Suite", "load_suite", "manifest_path", "versions"]

#: The folder holding every version.
SUITES = Path(__file__).resolve().parent


def manifest_path(folder: Path) -> Path:
    """The manifest of the version in ``folder``."""
    return folder / "manifest.json"


def versions(root: Path = SUITES) -> list[str]:
    """The versions under ``root``, oldest first."""
    found = [p.parent.name for p in root.glob("v*/manifest.json")]
    return sorted(found, key=lambda name: int(name[1:]) if name[1:].isdigit() else 0)


@dataclass(frozen=True)
class Suite:
    """A loaded version: its manifest and every case, property by property in the
    manifest's order."""

    version: str
    folder: Path
    manifest: dict[str, Any]
    cases: tuple[Case, ...]

    def tier(self, tier: str) -> list[Case]:
        """The cases a run of ``tier`` runs: its own and those of the tiers before it."""
        if tier not in TIERS:
            raise ImplementationError(f"unknown tier {tier!r}; known: {', '.join(TIERS)}")
        wanted = TIERS[: TIERS.index(tier) + 1]
        return [case for case in self.cases if case.tier in wanted]


def load_suite(version: str, root: Path = SUITES) -> Suite:
    """Suite ``version`` (a name under ``root``, or a folder path holding a manifest)."""
    folder = Path(version) if manifest_path(Path(version)).is_file() else root / version
    if not manifest_path(folder).is_file():
        known = ", ".join(versions(root)) or "none"
        raise ImplementationError(f"no suite {version!r}; versions: {known}")
    manifest = json.loads(manifest_path(folder).read_text())
    cases: list[Case] = []
    for name in manifest["properties"]:
        header, found = read_cases(folder / f"{name}.jsonl")
        if header.get("suite") != manifest["suite"]:
            raise ImplementationError(f"{folder / name}.jsonl belongs to {header.get('suite')}")
        cases += found
    return Suite(manifest["suite"], folder, manifest, tuple(cases))
