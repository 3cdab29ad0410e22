"""Writing a suite version: drawing its cases once, judging them by the reference, freezing them.

``ifgm-ref suite build --version v1`` draws each simulation check's examples from the check's
own strategy (derandomized, ``examples`` per check, the explicit ones first), runs the
reference on each -- IFGM, or IBA for the checks only IBA's promises reach -- and keeps the
cases it passes having met something to check; a reference-level case also records the
reference's answers (:mod:`.recorded`). It writes one file of cases per property, the
equation vectors and traces (``vectors.json``, the file ``ifgm-ref vectors`` writes) and a
manifest. The quick tier is chosen by measurement (:mod:`.tiers`), and its kill matrix
written beside the cases (``kill-matrix.json``).
"""

from __future__ import annotations

import json
import shutil
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

import hypothesis
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import seed as hypothesis_seed

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.params import SimParams
from ifgm_ref.io.transport.wire import PROTOCOL_VERSION
from ifgm_ref.io.worldfile import load_world
from ifgm_ref.oracle.agreement import HEADING_TOL, POINT_TIE, SPEED_TOL, TIE
from ifgm_ref.oracle.check_types import Check, CheckFailed, Kind, Recorder
from ifgm_ref.oracle.checks import CHECKS
from ifgm_ref.oracle.implementation import Implementation
from ifgm_ref.oracle.stable_draws import global_constants_only
from ifgm_ref.oracle.suite.cases import Case, read_cases, write_cases
from ifgm_ref.oracle.suite.recorded import recorded
from ifgm_ref.oracle.suite.tiers import broken_implementations, kill_matrix, quick_tier, with_tiers
from ifgm_ref.oracle.suite.versions import SUITES, manifest_path, versions
from ifgm_ref.oracle.vectors import write_vectors
from ifgm_ref.sim.world import World

__all__ = ["CLASS_FLAGGED", "REFERENCES", "build_suite", "drawn_examples", "promote"]

#: The reference planners that judge the cases, in order: a check's cases are drawn for, and
#: judged by, the first whose promises it applies to.
REFERENCES = ("ifgm", "iba")
#: The checks whose worlds are drawn from the classes the implementation converges in: their
#: cases carry their world's class as a flag (``class:u``).
CLASS_FLAGGED = frozenset(
    {"rigid_motion_invariant", "scale_invariant", "ignores_unseen_obstacles", "deterministic"}
)

#: The checks whose example holds more than a world (a gap, a scale, a disc, dynamics).
_NOT_A_WORLD = frozenset({"passes_wide_gaps", "stops_in_time"})


def drawn_examples(check: Check, impl: Implementation, count: int, seed: int) -> list[Any]:
    """``check``'s explicit examples, then ``count`` drawn from its strategy for ``impl``
    (derandomized by ``seed``), duplicates left out, in the order drawn."""
    examples: list[Any] = list(check.explicit()) if check.explicit is not None else []

    @settings(
        max_examples=count,
        phases=[Phase.generate],
        database=None,
        deadline=None,
        suppress_health_check=list(HealthCheck),
    )
    @hypothesis_seed(seed)
    @given(check.strategy(impl))
    def collect(example: Any) -> None:
        if example not in examples:
            examples.append(example)

    with global_constants_only():  # the same examples whatever is installed or imported
        collect()
    return examples


def _world_of(example: Any) -> World:
    return example if isinstance(example, World) else example[0]


def _judged(check: Check, impl: Implementation, example: Any, sim: SimParams) -> tuple[str, float]:
    """The reference's verdict on ``example`` (``pass``, ``fail`` or ``skip``: it met
    nothing to check) and its seconds."""
    recorder = Recorder(sim=sim)
    started = time.perf_counter()
    try:
        check.test(impl, example, recorder)
    except CheckFailed:
        return "fail", time.perf_counter() - started
    missed = None if check.meets is None else check.meets.missed(recorder)
    return "skip" if missed is not None else "pass", time.perf_counter() - started


def _check_cases(
    check: Check, count: int, seed: int, progress: Callable[[str], None], seconds: dict[str, float]
) -> list[Case]:
    impl = _reference_for(check)
    sim = SimParams()
    cases: list[Case] = []
    for example in drawn_examples(check, impl, count, seed):
        verdict, spent = _judged(check, impl, example, sim)
        if verdict == "skip":
            continue
        if verdict == "fail":  # the reference must pass its own oracle: a bug to fix, not a case
            raise ImplementationError(f"the reference {impl.label} fails {check.name} on {example}")
        world = _world_of(example)
        flags = (f"class:{world.name}",) if check.name in CLASS_FLAGGED else ()
        case = Case(f"{check.name}/{len(cases) + 1:04d}", check.name, example, flags=flags, sim=sim)
        if check.name == "agrees_with_reference":
            case = replace(case, recorded=recorded(world, Recorder(sim=sim).sim_for(world)))
        cases.append(case)
        seconds[case.id] = spent
    progress(f"{check.name}: {len(cases)} cases")
    return cases


def _reference_for(check: Check) -> Implementation:
    """The first of :data:`REFERENCES` whose promises ``check`` applies to."""
    for name in REFERENCES:
        impl = Implementation.from_spec(name)
        if check.applies(impl) is None:
            return impl
    raise ImplementationError(f"no reference planner promises {check.name}")


def build_suite(
    version: str,
    *,
    examples: int = 50,
    seed: int = 0,
    root: Path = SUITES,
    checks: list[str] | None = None,
    progress: Callable[[str], None] = lambda line: None,
    jobs: int = 1,
) -> Path:
    """Write suite ``version`` under ``root`` (refused if it exists: a version is frozen),
    its kill matrix run in ``jobs`` processes, and return its folder."""
    folder = root / version
    if manifest_path(folder).exists():
        raise ImplementationError(f"suite {version} exists in {root}; versions are frozen")
    folder.mkdir(parents=True, exist_ok=True)
    names = checks or [n for n, c in CHECKS.items() if c.kind is Kind.SIMULATION]
    seconds: dict[str, float] = {}
    cases = [c for n in names for c in _check_cases(CHECKS[n], examples, seed, progress, seconds)]
    matrix = kill_matrix(cases, broken_implementations(), progress, jobs=jobs)
    quick, times, held_out = quick_tier(cases, matrix, seconds)
    cases = with_tiers(cases, quick)
    for name in names:
        header = {"suite": version, "protocol": PROTOCOL_VERSION, "property": name}
        write_cases(folder / f"{name}.jsonl", header, [c for c in cases if c.check == name])
    kills = {"quick": quick, "times": times, "held_out": held_out, "killed": matrix}
    kills["reference_seconds"] = seconds
    (folder / "kill-matrix.json").write_text(json.dumps(kills, indent=1) + "\n")
    write_vectors(folder / "vectors.json")
    manifest = {
        "suite": version,
        "protocol": PROTOCOL_VERSION,
        "generator": f"ifgm-ref suite build (hypothesis {hypothesis.__version__})",
        "examples_per_check": examples,
        "seed": seed,
        "sim": {"engine": "kinematic", "dt": SimParams().dt},
        "tolerances": {
            "heading": HEADING_TOL,
            "speed": SPEED_TOL,
            "tie": TIE,
            "point_tie": POINT_TIE,
        },
        "properties": {name: CHECKS[name].sentence for name in names},
    }
    manifest_path(folder).write_text(json.dumps(manifest, indent=2) + "\n")
    counts = ", ".join(f"{sum(c.check == n for c in cases)} {n}" for n in names)
    (folder / "CHANGELOG.md").write_text(
        f"# Suite {version}\n\n- {len(cases)} cases, {len(quick)} of them quick: {counts}\n"
    )
    return folder


def promote(counterexample: Path, version: str, *, root: Path = SUITES) -> Case:
    """Add the world of a drawn profile's ``counterexample`` folder (``world.json`` and the
    check named in its ``report.md``) to suite ``version`` as a new full-tier case, judged by
    the reference. ``version`` is made from the latest version if it does not exist yet (a
    released version is never changed: promote into the next one)."""
    report = counterexample / "report.md"
    if not report.is_file() or not (counterexample / "world.json").is_file():
        raise ImplementationError(f"{counterexample}: no counterexample (report.md, world.json)")
    name = report.read_text().split("\n", 1)[0].removeprefix("# ").split(":")[0]
    check = CHECKS.get(name)
    if check is None or name in CLASS_FLAGGED or name in _NOT_A_WORLD:
        raise ImplementationError(f"{name}: only a check whose example is a world is promoted")
    folder = root / version
    if not manifest_path(folder).exists():
        latest = versions(root)
        if not latest:
            raise ImplementationError(f"no suite under {root} to start {version} from")
        shutil.copytree(root / latest[-1], folder)
        manifest = json.loads(manifest_path(folder).read_text())
        for property_name in manifest["properties"]:  # every file now says which version
            path = folder / f"{property_name}.jsonl"
            header, cases = read_cases(path)
            write_cases(path, {**header, "suite": version}, cases)
        manifest_path(folder).write_text(json.dumps({**manifest, "suite": version}, indent=2))
    header, cases = read_cases(folder / f"{name}.jsonl")
    world = load_world(counterexample / "world.json")
    verdict, _ = _judged(check, _reference_for(check), world, SimParams())
    if verdict != "pass":
        raise ImplementationError(f"the reference does not pass {name} on it ({verdict})")
    number = max(int(c.id.split("/")[1]) for c in cases) + 1
    case = Case(f"{name}/{number:04d}", name, world)
    if name == "agrees_with_reference":
        case = replace(case, recorded=recorded(world, Recorder().sim_for(world)))
    write_cases(folder / f"{name}.jsonl", {**header, "suite": version}, [*cases, case])
    with (folder / "CHANGELOG.md").open("a") as log:
        log.write(f"- {case.id}: added, the counterexample of {counterexample}\n")
    return case
