"""What a verdict other than a pass says and leaves: a crash in one line, and a failing
check's counterexample on disk (world files, traces, plots and ``report.md``).

:func:`crash` names an unexpected exception and where it was raised (an ``error`` verdict's
message); :func:`write_evidence` writes what a failing example left behind
(:class:`~ifgm_ref.oracle.check_types.Evidence`) into one folder per check, with the commands
that replay it on the same engine, body, time step and goal tolerance (``ifgm-ref simulate``).
"""

from __future__ import annotations

import re
import traceback
from pathlib import Path
from types import TracebackType
from typing import Any

from ifgm_ref.core.outputs import written
from ifgm_ref.core.params import DT, GOAL_TOLERANCE, SimParams
from ifgm_ref.io.worldfile import save_world
from ifgm_ref.oracle.check_types import Check, Evidence
from ifgm_ref.oracle.implementation import Implementation

__all__ = ["crash", "slug", "write_evidence"]


def slug(text: str) -> str:
    """``text`` as a folder name of a counterexample (an implementation's label).

    >>> slug("cmd: ./my planner --fast")
    'cmd_._my_planner_--fast'
    """
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text).strip("_")[:60] or "implementation"


def write_evidence(
    folder: Path, evidence: Evidence, check: Check, impl: Implementation, message: str,
    *, sim: SimParams | None = None,
) -> None:  # fmt: skip
    """Write a failure's counterexample: world files, traces, plots and ``report.md``, whose
    replay commands run on ``sim``'s engine and body (default: kinematic)."""
    folder.mkdir(parents=True, exist_ok=True)
    lines = [f"# {check.name}: failed", "", f"Property: {check.sentence}.", "", message, ""]
    if evidence.inputs is not None:
        lines += ["Inputs:", "", f"    {evidence.inputs!r}", ""]
    names = ["world", "world_moved"][: len(evidence.worlds)]
    for k, world in enumerate(evidence.worlds):
        save_world(world, folder / f"{names[k]}.json")
    for k, run in enumerate(evidence.runs):
        stem = names[min(k, len(names) - 1)] + ("_rerun" if k >= len(names) else "")
        with written(folder / f"{stem}_trace.csv", announce=False) as partial:
            partial.write_text(run.trace_csv())
        mark = evidence.step if k == 0 else None
        engine = (sim or SimParams()).engine
        _plot(evidence.worlds[min(k, len(names) - 1)], run, folder / f"{stem}.png", mark, engine)
    if evidence.worlds:
        how = impl.simulate_options()
        limit = f" --max-time {evidence.max_time:.6g}" if evidence.max_time else ""
        if sim is not None and sim.engine != SimParams().engine:  # replay on the same engine
            limit += f" --engine {sim.engine}" + (f" --body {sim.body}" if sim.body else "")
        if sim is not None and (sim.dt, sim.goal_tolerance) != (DT, GOAL_TOLERANCE):
            limit += f" --dt {sim.dt:.6g} --goal-tolerance {sim.goal_tolerance:.6g}"
        lines += ["Replay:", ""]
        for name in names:
            lines.append(
                f"    ifgm-ref simulate {folder / name}.json {how}{limit} "
                f"--plot {folder / name}_replay.png --trace {folder / name}_replay_trace.csv "
                f"--record {folder / name}_replay.mcap"
            )
        lines.append("")
    with written(folder / "report.md", announce=False) as partial:
        partial.write_text("\n".join(lines))


def _plot(world: Any, run: Any, path: Path, mark: int | None, engine: str) -> None:
    from ifgm_ref.sim.plotting import finest_colouring, plot_run, save_figure

    colour_by = finest_colouring(run.trace)
    figure = plot_run(world, run.trace, run.result, colour_by=colour_by, mark=mark, engine=engine)
    with written(path, announce=False) as partial:
        save_figure(figure, partial)


def crash(err: BaseException, *, outer: TracebackType | None = None) -> str:
    """Name an unexpected exception and where it was raised, in one line.

    ``Type: message at file:line``: the innermost frame of its traceback (or of ``outer``, for
    an exception never raised itself, such as a member of a group built in place), the path
    relative to the folder that holds ``ifgm_ref``, or to the working folder. A group lists
    its exceptions.

    >>> try:
    ...     [][0]
    ... except IndexError as err:
    ...     print(crash(err))  # doctest: +ELLIPSIS
    IndexError: list index out of range at <doctest ...>:2
    """
    where = err.__traceback__ or outer
    if isinstance(err, BaseExceptionGroup):
        inner = "; ".join(crash(e, outer=where) for e in err.exceptions)
        return f"{type(err).__name__} of {len(err.exceptions)}: {inner}"
    first_line = next(iter(str(err).splitlines()), "")
    text = f"{type(err).__name__}: {first_line}"
    frames = traceback.extract_tb(where)
    if frames:
        text += f" at {_short_path(frames[-1].filename)}:{frames[-1].lineno}"
    return text


def _short_path(filename: str) -> str:
    """``filename`` relative to the folder holding this package, or to the working folder."""
    path = Path(filename)
    for root in (Path(__file__).resolve().parents[2], Path.cwd()):
        if path.is_relative_to(root):
            return path.relative_to(root).as_posix()
    return filename
