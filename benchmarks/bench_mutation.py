"""Mutation testing of the oracle: how many small breaks of IFGM's decision code does each
level of conformance catch?

Run from the project root::

    python benchmarks/bench_mutation.py --count 100 --seed 0 [--out mutation-results]
    python benchmarks/bench_mutation.py --count 100 --seed 0 --only 78-100 --levels paper

Each mutant is one change at one site of the decision code (``--files``, default IFGM's
planner, its atoms, IBA, the edge follower, the sight, the flowchart and the percepts): a
comparison flipped (``<`` to ``<=``, ``<`` to ``>``, ``==`` to ``!=``), an arithmetic operator
swapped (``+``/``-``, ``*``/``/``), ``and``/``or`` swapped, a ``not`` or a unary minus
dropped, a number moved by one (``0`` to ``1``, ``x`` to ``x + 1``), ``True``/``False``
swapped. The sites are listed in a fixed order and ``--count`` of them drawn with ``--seed``
(``--count 0``: all), numbered from 1 in the order drawn; ``--only`` judges some of them
(a run cut short resumes with ``--only 78-100``). Each mutant lives in its own copy of the
package (``ast.unparse`` of the changed tree) and is served as a program (``ifgm-ref
serve``), so that the oracle, the simulator and the reference it compares with stay the
original. For each it reports:

* ``trace``: whether any IFGM trace in the built-in worlds changed (a mutant that changes
  none, or changes only the last digits, "rounding", is probably equivalent there, and is not
  counted in the kill rates);
* ``paper``: killed by the paper's properties (``ifgm-ref oracle``, quick profile, the
  first failure unshrunk: ``--stop-on-failure --no-shrink``);
* ``reference``: killed by reference agreement (``--check agrees_with_reference``);
* ``tests``: killed by the project's tests of the decision code (``--tests``);
* ``suite_quick`` and ``suite_full`` (only with ``--levels``): killed by the frozen suite's
  quick or full tier at both levels (``ifgm-ref oracle --suite v1 --level reference``), the
  measure of how much of the full tier's power the quick tier keeps; ``suite_cases``: the
  full tier with every case run, each mutant's verdicts written to
  ``OUT/suite-runs/NUMBER.jsonl`` (which cases kill it: ``ifgm-ref suite tiers --runs``);

each with the seconds it took. A mutant that cannot even be imported or served is ``broken``:
killed by anything, and counted apart. The kill rates are over the mutants that change a
trace. Results go to ``--out``: ``mutants.csv`` (one row per mutant, its number first) and the
summary on stdout.

Why not a mutation tool: mutmut and cosmic-ray run one test command per mutant and record one
verdict; here each mutant needs four (a trace filter and three levels), each run against the
original oracle with the mutant as a program. The mutator below is the part a tool would
give: about a hundred lines of :mod:`ast`.
"""

from __future__ import annotations

import argparse
import ast
import csv
import json
import os
import random
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "ifgm_ref"
#: The decision code of IFGM (issue 26's list).
FILES = (
    "planners/ifgm/planner.py",
    "planners/ifgm/atoms.py",
    "planners/iba.py",
    "planners/boundary.py",
    "planners/sight.py",
    "paper/flowchart.py",
    "paper/percepts/clusters.py",
    "paper/percepts/corridor.py",
    "paper/percepts/memory.py",
    "paper/percepts/points.py",
)
#: The tests that exercise the decision code.
TESTS = (
    "tests/test_ifgm.py tests/test_flowchart.py tests/test_flowchart_properties.py "
    "tests/test_iba.py tests/test_percepts.py"
)

_COMPARISONS: dict[type[ast.cmpop], tuple[type[ast.cmpop], ...]] = {
    ast.Lt: (ast.LtE, ast.Gt),
    ast.LtE: (ast.Lt, ast.GtE),
    ast.Gt: (ast.GtE, ast.Lt),
    ast.GtE: (ast.Gt, ast.LtE),
    ast.Eq: (ast.NotEq,),
    ast.NotEq: (ast.Eq,),
    ast.Is: (ast.IsNot,),
    ast.IsNot: (ast.Is,),
}
_ARITHMETIC: dict[type[ast.operator], type[ast.operator]] = {
    ast.Add: ast.Sub,
    ast.Sub: ast.Add,
    ast.Mult: ast.Div,
    ast.Div: ast.Mult,
}


@dataclass(frozen=True)
class Site:
    """One mutation: where (file, line, column, the node's index in a walk) and what."""

    file: str
    line: int
    column: int
    node: int
    operator: str
    change: str


def sites(file: str) -> Iterator[Site]:
    """Every mutation of ``file``'s code (docstrings and annotations left alone)."""
    tree = ast.parse((PACKAGE / file).read_text())
    skipped = _docstrings_and_annotations(tree)
    for index, node in enumerate(ast.walk(tree)):
        if id(node) in skipped:
            continue
        for operator, change in _changes(node):
            line, column = getattr(node, "lineno", 0), getattr(node, "col_offset", 0)
            yield Site(file, line, column, index, operator, change)


def _docstrings_and_annotations(tree: ast.AST) -> set[int]:
    skipped: set[int] = set()
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        first = body[0] if isinstance(body, list) and body else None
        if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
            skipped.add(id(first.value))
        for annotation in (getattr(node, "annotation", None), getattr(node, "returns", None)):
            if annotation is not None:
                skipped.update(id(sub) for sub in ast.walk(annotation))
    return skipped


def _changes(node: ast.AST) -> Iterator[tuple[str, str]]:
    """The mutations of one node, as (operator, change)."""
    if isinstance(node, ast.Compare) and len(node.ops) == 1:
        for new in _COMPARISONS.get(type(node.ops[0]), ()):
            yield "comparison", f"{type(node.ops[0]).__name__} -> {new.__name__}"
    elif isinstance(node, ast.BinOp) and type(node.op) in _ARITHMETIC:
        new = _ARITHMETIC[type(node.op)]
        yield "arithmetic", f"{type(node.op).__name__} -> {new.__name__}"
    elif isinstance(node, ast.BoolOp):
        yield "boolean", "and -> or" if isinstance(node.op, ast.And) else "or -> and"
    elif isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not | ast.USub):
        yield "negation", f"drop {type(node.op).__name__}"
    elif isinstance(node, ast.Constant) and type(node.value) in (int, float, bool):
        if isinstance(node.value, bool):
            yield "constant", f"{node.value} -> {not node.value}"
        else:
            yield "constant", f"{node.value!r} -> {node.value + 1!r}"


def mutated_source(site: Site) -> str:
    """``site.file`` with ``site``'s one change, as source."""
    tree = ast.parse((PACKAGE / site.file).read_text())
    node = list(ast.walk(tree))[site.node]
    _, _, after = site.change.partition(" -> ")
    if isinstance(node, ast.Compare):
        node.ops = [getattr(ast, after)()]
    elif isinstance(node, ast.BinOp):
        node.op = getattr(ast, after)()
    elif isinstance(node, ast.BoolOp):
        node.op = ast.Or() if isinstance(node.op, ast.And) else ast.And()
    elif isinstance(node, ast.UnaryOp):
        _replace(tree, node, node.operand)
    elif isinstance(node, ast.Constant):
        node.value = (not node.value) if isinstance(node.value, bool) else node.value + 1
    return ast.unparse(tree)


def _replace(tree: ast.AST, old: ast.AST, new: ast.AST) -> None:
    for parent in ast.walk(tree):
        for name, value in ast.iter_fields(parent):
            if value is old:
                setattr(parent, name, new)
            elif isinstance(value, list):
                for k, item in enumerate(value):
                    if item is old:
                        value[k] = new


# ---- the levels ----------------------------------------------------------------------------

#: The trace filter: every IFGM trace in the built-in worlds, as CSV (run in the copy).
_TRACES = """
from ifgm_ref.planners import make_planner
from ifgm_ref.io.scenarios import BUILTIN_WORLDS, resolve_world
from ifgm_ref.sim.simulator import simulate
for name in sorted(BUILTIN_WORLDS):
    print(simulate(resolve_world(name), make_planner("ifgm")).trace_csv(), end="")
"""
#: Trace numbers this near each other differ by rounding only (a heading wrapped once more).
ROUNDING = 1e-9


def _run(command: list[str], copy: Path | None, timeout: float) -> tuple[int, float]:
    """Run ``command`` with the mutant's ``copy`` of the package first on the path (run from
    the copy: ``python -m`` and ``-c`` put the working folder before ``PYTHONPATH``), or with
    the original (``None``)."""
    started = time.perf_counter()
    try:
        done = subprocess.run(
            command, cwd=copy or ROOT, env=_env(copy), capture_output=True, timeout=timeout
        )
        code = done.returncode
    except subprocess.TimeoutExpired:
        code = -1
    return code, time.perf_counter() - started


def _env(copy: Path | None) -> dict[str, str]:
    env = dict(os.environ)
    if copy is not None:
        env["PYTHONPATH"] = str(copy)
    return env


def traces(copy: Path | None) -> list[str] | None:
    """The built-in worlds' IFGM traces, their CSV lines; ``None`` if the package does not
    run (or runs for ever)."""
    try:
        done = subprocess.run(
            [sys.executable, "-c", _TRACES], cwd=copy or ROOT, env=_env(copy),
            capture_output=True, timeout=600,
        )  # fmt: skip
    except subprocess.TimeoutExpired:
        return None
    return done.stdout.decode().splitlines() if done.returncode == 0 else None


def trace_change(original: list[str], mutant: list[str]) -> str:
    """``"same"`` traces, traces that differ by ``"rounding"`` only (every number within
    :data:`ROUNDING`, every label the same), or ``"changed"`` ones."""
    if mutant == original:
        return "same"
    if len(mutant) != len(original):
        return "changed"
    for ours, theirs in zip(original, mutant, strict=True):
        for a, b in zip(ours.split(","), theirs.split(","), strict=False):
            try:
                if abs(float(a) - float(b)) > ROUNDING:
                    return "changed"
            except ValueError:
                if a != b:
                    return "changed"
    return "rounding"


def _serve(copy: Path) -> str:
    path = shlex.quote(str(copy))
    return f"env -C {path} PYTHONPATH={path} {sys.executable} -m ifgm_ref serve --planner ifgm"


def _oracle(copy: Path, *extra: str) -> list[str]:
    return [sys.executable, "-m", "ifgm_ref", "oracle", "--cmd", _serve(copy), "--jobs", "2",
            "--stop-on-failure", "--no-shrink", "--artifacts", str(copy / "oracle-failures"),
            *extra]  # fmt: skip


def _suite(copy: Path, tier: str, results: Path | None = None) -> list[str]:
    """The frozen suite's ``tier`` at both levels, the mutant served: stopping at the first
    failing case, or every case run and each verdict written to ``results``."""
    stop = ["--stop-on-failure"] if results is None else []
    return [sys.executable, "-m", "ifgm_ref", "oracle", "--suite", SUITE, "--tier", tier,
            "--level", "reference", "--cmd", _serve(copy), *stop,
            "--artifacts", str(copy / "suite-failures"),
            "--results", str(results or os.devnull)]  # fmt: skip


#: The suite version the ``suite_quick`` and ``suite_full`` levels run.
SUITE = "v1"
#: The levels, in the order they run (the suite's only when asked: ``--levels``).
LEVELS = ("paper", "reference", "tests", "suite_quick", "suite_full", "suite_cases")


@dataclass
class Outcome:
    """One mutant's trace filter ("changed", "same" or "broken"), and per level its verdict
    ("killed", "survived", or "error": the command could not judge, exit status 2 and up)
    and seconds."""

    number: int
    site: Site
    trace: str
    verdicts: dict[str, str] = field(default_factory=dict)
    seconds: dict[str, float] = field(default_factory=dict)


def judge(
    number: int, site: Site, original: list[str], levels: list[str], tests: str, out: Path
) -> Outcome:
    """Build ``site``'s mutant (``number`` of the draw) in a copy of the package and run
    every level on it."""
    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="mutant-") as folder:
        copy = Path(folder)
        shutil.copytree(PACKAGE, copy / "ifgm_ref", ignore=shutil.ignore_patterns("__pycache__"))
        (copy / "ifgm_ref" / site.file).write_text(mutated_source(site))
        found = traces(copy)
        if found is None:
            seconds = {"trace": time.perf_counter() - started}
            return Outcome(number, site, "broken", seconds=seconds)
        outcome = Outcome(number, site, trace_change(original, found))
        outcome.seconds["trace"] = time.perf_counter() - started
        if outcome.trace != "changed":
            return outcome
        commands = {
            "paper": (_oracle(copy), None),
            "reference": (_oracle(copy, "--level", "reference", "--check",
                                  "agrees_with_reference"), None),
            # the project's ini puts its root first on the path: the copy goes before it
            "suite_quick": (_suite(copy, "quick"), None),
            "suite_full": (_suite(copy, "full"), None),
            "suite_cases": (_suite(copy, "full", out / "suite-runs" / f"{number}.jsonl"), None),
            "tests": ([sys.executable, "-m", "pytest", "-x", "-q", "-n", "0", "-p",
                       "no:cacheprovider", "-o", f"pythonpath={copy} {ROOT}",
                       *(str(ROOT / t) for t in tests.split())], copy),
        }  # fmt: skip
        for level in (level for level in LEVELS if level in levels):
            command, path = commands[level]
            code, outcome.seconds[level] = _run(command, path, 1800)
            outcome.verdicts[level] = {0: "survived", 1: "killed"}.get(code, "error")
    return outcome


# ---- the run --------------------------------------------------------------------------------


def main() -> None:
    """Draw the mutants, judge each, write the table and print the kill rates."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--count", type=int, default=100, help="mutants to draw (0: all)")
    parser.add_argument("--seed", type=int, default=0, help="the draw's seed (default 0)")
    parser.add_argument("--files", default=",".join(FILES), help="files under ifgm_ref/")
    parser.add_argument("--levels", default="paper,reference,tests", help="levels to run")
    parser.add_argument("--tests", default=TESTS, help="the test files of the tests level")
    parser.add_argument("--out", type=Path, default=Path("mutation-results"), help="folder")
    parser.add_argument("--only", help="judge only these numbers of the draw: 78-100,5")
    parser.add_argument("--list", action="store_true", help="list the sites and stop")
    args = parser.parse_args()
    every = [site for file in args.files.split(",") for site in sites(file)]
    if args.list:
        for site in every:
            print(json.dumps(asdict(site)))
        return
    drawn = every if args.count == 0 else random.Random(args.seed).sample(every, args.count)
    numbers = _numbers(args.only, len(drawn)) if args.only else range(1, len(drawn) + 1)
    print(f"{len(every)} sites in {args.files}; judging {len(numbers)} of {len(drawn)} drawn "
          f"(seed {args.seed})")  # fmt: skip
    original = traces(None)
    if original is None:
        raise SystemExit("the unmutated package does not run")
    (args.out / "suite-runs").mkdir(parents=True, exist_ok=True)
    outcomes = []
    for k in numbers:
        outcome = judge(k, drawn[k - 1], original, args.levels.split(","), args.tests, args.out)
        outcomes.append(outcome)
        print(f"[{k}/{len(drawn)}] {_row(outcome)}", flush=True)
        _write(args.out / "mutants.csv", outcomes)
    print(_summary(outcomes))


def _numbers(only: str, drawn: int) -> list[int]:
    """``--only``'s numbers ("78-100,5"), each checked to be one of the ``drawn``."""
    numbers: list[int] = []
    for part in only.split(","):
        found = re.fullmatch(r"(\d+)(?:-(\d+))?", part.strip())
        if found is None:
            raise SystemExit(f"--only: {part!r} is not a number or a range like 78-100")
        first, last = found.groups()
        numbers.extend(range(int(first), int(last or first) + 1))
    if not numbers or min(numbers) < 1 or max(numbers) > drawn:
        raise SystemExit(f"--only: numbers must lie in 1-{drawn}, the mutants drawn")
    return sorted(set(numbers))


def _row(outcome: Outcome) -> str:
    site = outcome.site
    verdicts = "; ".join(
        f"{level} {outcome.verdicts[level]} ({outcome.seconds[level]:.0f} s)"
        for level in LEVELS
        if level in outcome.verdicts
    )
    return (
        f"{site.file}:{site.line}:{site.column} {site.change}: trace {outcome.trace} "
        f"({outcome.seconds['trace']:.0f} s){'; ' + verdicts if verdicts else ''}"
    )


def _write(path: Path, outcomes: list[Outcome]) -> None:
    with path.open("w", newline="") as out:
        writer = csv.writer(out)
        per_level = [f"{level}{suffix}" for level in LEVELS for suffix in ("", "_s")]
        writer.writerow(
            ["number", "file", "line", "column", "operator", "change", "trace", "trace_s",
             *per_level]
        )  # fmt: skip
        for o in outcomes:
            s = o.site
            levels = [item for level in LEVELS for item in
                      (o.verdicts.get(level, ""), f"{o.seconds.get(level, 0.0):.1f}")]  # fmt: skip
            writer.writerow([o.number, s.file, s.line, s.column, s.operator, s.change, o.trace,
                             f"{o.seconds['trace']:.1f}", *levels])  # fmt: skip


def _summary(outcomes: list[Outcome]) -> str:
    changed = [o for o in outcomes if o.trace == "changed"]
    lines = [
        f"{len(outcomes)} mutants: {len(changed)} change a trace in the built-in worlds, "
        f"{sum(o.trace == 'same' for o in outcomes)} change none, "
        f"{sum(o.trace == 'rounding' for o in outcomes)} only by rounding, "
        f"{sum(o.trace == 'broken' for o in outcomes)} do not run"
    ]
    for level in LEVELS:
        judged = [o.verdicts[level] for o in changed if level in o.verdicts]
        if judged:
            killed, errors = judged.count("killed"), judged.count("error")
            seconds = statistics.median(o.seconds[level] for o in changed if level in o.seconds)
            share = 100.0 * killed / len(judged)
            lines.append(
                f"  {level}: killed {killed} of {len(judged)} ({share:.0f} %), {errors} could "
                f"not judge; median {seconds:.0f} s a mutant"
            )
    return "\n".join(lines)


if __name__ == "__main__":
    main()
