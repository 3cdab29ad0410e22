"""The benchmark's outputs: the table (CSV), summaries per planner and class, Markdown, plots.

Files written by :func:`write_report` into the output folder:

==========================  =================================================================
``results.csv``             one row per (planner, world): :class:`~ifgm_ref.apps.bench.tasks.Row`
``summary.csv``             one row per (planner, class): :class:`Summary`
``summary.md``              the run's settings and machine, the summary tables, the failures
``success_by_class.png``    success rate per class, one bar per planner
``path_ratio.png``          path length / optimal of the successful episodes, per class (only
                            when some episode has an optimal path: BARN's worlds have none)
``worlds/NAME.json``        every world some planner failed in, to replay with ``simulate``
``results.partial.csv``     the rows so far, as they arrive (removed when the run completes)
==========================  =================================================================
"""

from __future__ import annotations

import contextlib
import csv
import math
import os
import platform
from collections.abc import Sequence
from dataclasses import astuple, dataclass, fields
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ifgm_ref.apps.bench.tasks import Row, WorldSpec
from ifgm_ref.core.outputs import written
from ifgm_ref.io.worldfile import save_world
from ifgm_ref.sim.simulator import StopReason

#: The pseudo-class that pools every world.
ALL = "all"
#: The file that collects rows as they arrive, in completion order.
PARTIAL = "results.partial.csv"


@dataclass(frozen=True)
class Summary:
    """One planner on one class of worlds (or on all of them: ``world_class == "all"``).

    ``success_rate`` is the fraction of episodes that reached the goal; the path-ratio
    statistics are over those episodes (``None`` when there is none); ``collisions`` counts
    episodes that ended in a collision and ``errors`` those whose planner raised.
    ``collision_rate``, ``timeout_rate`` and ``stall_rate`` are the fractions of episodes
    that ended in a collision, at the time limit and stalled (no progress: the simulator's
    stall rule, :mod:`ifgm_ref.sim.simulator`); ``barn_score_mean`` is the mean BARN score over
    the episodes that have one (BARN worlds; ``None`` elsewhere), as BARN reports it.
    """

    planner: str
    world_class: str
    worlds: int
    success_rate: float
    collisions: int
    errors: int
    path_ratio_median: float | None
    path_ratio_p90: float | None
    time_median_s: float | None
    heading_change_median: float | None
    min_clearance_min: float | None
    decisions_per_cpu_s_median: float | None
    collision_rate: float | None = None
    timeout_rate: float | None = None
    stall_rate: float | None = None
    barn_score_mean: float | None = None

    @classmethod
    def columns(cls) -> tuple[str, ...]:
        """The column names, in order."""
        return tuple(f.name for f in fields(cls))


def _median(values: list[float]) -> float | None:
    return float(np.median(values)) if values else None


def summarize_rows(planner: str, world_class: str, rows: Sequence[Row]) -> Summary:
    """The :class:`Summary` of ``rows`` (all of one planner)."""
    reached = [r for r in rows if r.reached]
    ratios = [r.path_ratio for r in reached if r.path_ratio is not None]
    clearances = [r.min_clearance for r in rows if r.min_clearance is not None]
    speeds = [r.decisions_per_cpu_s for r in rows if r.decisions_per_cpu_s is not None]
    scores = [r.barn_score for r in rows if r.barn_score is not None]
    return Summary(
        planner=planner,
        world_class=world_class,
        worlds=len(rows),
        success_rate=len(reached) / len(rows),
        collisions=sum(r.collided for r in rows),
        errors=sum(r.stop_reason == "error" for r in rows),
        path_ratio_median=_median(ratios),
        path_ratio_p90=float(np.percentile(ratios, 90)) if ratios else None,
        time_median_s=_median([r.time_s for r in reached]),
        heading_change_median=_median([r.heading_change for r in reached]),
        min_clearance_min=min(clearances) if clearances else None,
        decisions_per_cpu_s_median=_median(speeds),
        collision_rate=sum(r.collided for r in rows) / len(rows),
        timeout_rate=sum(r.stop_reason == StopReason.TIME_LIMIT for r in rows) / len(rows),
        stall_rate=sum(r.stop_reason == StopReason.STALLED for r in rows) / len(rows),
        barn_score_mean=float(np.mean(scores)) if scores else None,
    )


def summarize(rows: Sequence[Row]) -> list[Summary]:
    """Per planner (in first-seen order): one summary per class (first-seen order), then all."""
    planners = list(dict.fromkeys(r.planner for r in rows))
    classes = list(dict.fromkeys(r.world_class for r in rows))
    out = []
    for planner in planners:
        mine = [r for r in rows if r.planner == planner]
        for world_class in classes:
            of_class = [r for r in mine if r.world_class == world_class]
            if of_class:
                out.append(summarize_rows(planner, world_class, of_class))
        if len(classes) > 1:
            out.append(summarize_rows(planner, ALL, mine))
    return out


def _cell(value: object) -> object:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return ""
    return value


def save_plot(fig: Figure, path: str | Path) -> None:
    """Save a report's plot as PNG, whole or not at all, with no software name in it."""
    with written(path) as partial:
        fig.savefig(partial, dpi=110, metadata={"Software": None})


def write_csv(
    path: Path, columns: Sequence[str], records: Sequence[object], *, append: bool = False
) -> None:
    """Write dataclass ``records`` as CSV (empty cells for missing values); with ``append``,
    add them to ``path``, writing the header only if the file is new."""
    if not append:  # a whole file: written whole or not at all
        with written(path) as partial:
            write_csv(partial, columns, records, append=True)
        return
    header = not path.exists()
    with path.open("a", newline="") as out:
        writer = csv.writer(out, lineterminator="\n")
        if header:
            writer.writerow(columns)
        writer.writerows([_cell(v) for v in astuple(r)] for r in records)  # type: ignore[call-overload]


def read_rows(path: str | Path) -> list[Row]:
    """Read ``results.csv`` back into rows (the inverse of :func:`write_csv` for rows)."""
    kinds = {f.name: f.type for f in fields(Row)}
    rows = []
    with Path(path).open(newline="") as source:
        for record in csv.DictReader(source):
            values: dict[str, object] = {}
            for name, text in record.items():
                kind = str(kinds[name])
                if text == "":
                    values[name] = math.nan if kind == "float" else None
                elif kind == "bool":
                    values[name] = text == "True"
                elif kind.startswith("int"):
                    values[name] = int(text)
                elif "float" in kind:
                    values[name] = float(text)
                else:
                    values[name] = text
            rows.append(Row(**values))  # type: ignore[arg-type]
    return rows


def _fmt(value: float | None, spec: str) -> str:
    return "-" if value is None else format(value, spec)


def length_unit(rows: Sequence[Row]) -> str:
    """The unit of the rows' lengths: ``m`` when every world is BARN's (metres), ``ft`` when
    none is (the paper's worlds and the generated ones), else "world units"."""
    barn = {r.barn_score is not None for r in rows}
    if barn == {True}:
        return "m"
    return "ft" if barn <= {False} else "world units"


def has_optimal(rows: Sequence[Row]) -> bool:
    """Whether any row has a path / optimal (BARN's worlds have no optimal path computed)."""
    return any(r.path_ratio is not None for r in rows)


def summary_markdown(summaries: Sequence[Summary], rows: Sequence[Row], header: str) -> str:
    """The Markdown summary: ``header`` (settings, machine), a table per class, failures.

    Clearances are labelled with :func:`length_unit`; the path / optimal columns are left out
    when no row has one (:func:`has_optimal`).
    """
    lines = [header.rstrip(), ""]
    ratios = has_optimal(rows)
    classes = list(dict.fromkeys(s.world_class for s in summaries))
    for world_class in classes:
        mine = [s for s in summaries if s.world_class == world_class]
        columns = ["planner", "success", "collisions", "errors"]
        columns += ["path/optimal median", "p90"] if ratios else []
        columns += ["time median s", "turning median rad"]
        columns += [f"min clearance {length_unit(rows)}", "decisions/CPU s"]
        lines += [
            f"## {world_class} ({mine[0].worlds} worlds)",
            "",
            "| " + " | ".join(columns) + " |",
            "|---|" + "---:|" * (len(columns) - 1),
        ]
        for s in mine:
            cells = [s.planner, f"{s.success_rate:.1%}", str(s.collisions), str(s.errors)]
            if ratios:
                cells += [_fmt(s.path_ratio_median, ".3f"), _fmt(s.path_ratio_p90, ".3f")]
            cells += [_fmt(s.time_median_s, ".1f"), _fmt(s.heading_change_median, ".2f")]
            cells += [_fmt(s.min_clearance_min, ".3f"), _fmt(s.decisions_per_cpu_s_median, ",.0f")]
            lines.append("| " + " | ".join(cells) + " |")
        lines.append("")
    barn = [s for s in summaries if s.barn_score_mean is not None and s.world_class != ALL]
    if barn:
        lines += [
            "## BARN worlds (BARN's score; its DWA baseline in Gazebo: 0.159 on 50 test worlds)",
            "",
            "| planner | class | worlds | mean BARN score | success | collisions | timeouts "
            "| stalls |",
            "|---|---|---:|---:|---:|---:|---:|---:|",
        ]
        lines += [
            f"| {s.planner} | {s.world_class} | {s.worlds} | {s.barn_score_mean:.3f} | "
            f"{s.success_rate:.1%} | {s.collision_rate or 0.0:.1%} | {s.timeout_rate or 0.0:.1%} "
            f"| {s.stall_rate or 0.0:.1%} |"
            for s in barn
        ]
        lines.append("")
    failed = [r for r in rows if not r.reached]
    lines += [f"## Episodes that did not reach the goal ({len(failed)})", ""]
    if failed:
        lines += ["| planner | world | stop reason | time s | detail |", "|---|---|---|---:|---|"]
        lines += [
            f"| {r.planner} | {r.world} | {r.stop_reason} | {_fmt(r.time_s, '.1f')} | "
            f"{r.detail or ''} |"
            for r in failed
        ]
    else:
        lines.append("None.")
    return "\n".join(lines) + "\n"


def plot_success(summaries: Sequence[Summary], path: Path) -> None:
    """Grouped bars: success rate per class, one bar per planner."""
    import matplotlib.pyplot as plt

    per_class = [s for s in summaries if s.world_class != ALL]
    classes = list(dict.fromkeys(s.world_class for s in per_class))
    planners = list(dict.fromkeys(s.planner for s in per_class))
    rate = {(s.planner, s.world_class): s.success_rate for s in per_class}
    width = 0.8 / len(planners)
    fig, ax = plt.subplots(figsize=(1.6 + 1.4 * len(classes), 4.2), layout="constrained")
    for k, planner in enumerate(planners):
        xs = np.arange(len(classes)) + (k - (len(planners) - 1) / 2) * width
        ys = [100.0 * rate.get((planner, c), math.nan) for c in classes]
        bars = ax.bar(xs, ys, width, label=planner)
        ax.bar_label(bars, fmt="%.0f", fontsize=6, padding=1)
    ax.set_xticks(np.arange(len(classes)), classes)
    ax.set_ylim(0, 110)
    ax.set_ylabel("reached the goal (%)")
    ax.set_title("Success rate by world class")
    fig.legend(loc="outside lower center", ncols=min(len(planners), 7), fontsize="small")
    save_plot(fig, path)
    plt.close(fig)


#: Width (in) below which the path ratio plot's title no longer fits (4.3 in at the default
#: title size): one or two planners would clip it.
MIN_PLOT_WIDTH = 5.0


def plot_path_ratio(rows: Sequence[Row], path: Path) -> None:
    """Box plots of path length / optimal over the successful episodes, a panel per class."""
    import matplotlib.pyplot as plt

    classes = list(dict.fromkeys(r.world_class for r in rows))
    planners = list(dict.fromkeys(r.planner for r in rows))
    columns = min(len(classes), 2)
    lines = math.ceil(len(classes) / columns)
    width = max(MIN_PLOT_WIDTH, 1.0 + 0.6 * len(planners) * columns)
    fig, axes = plt.subplots(
        lines, columns, figsize=(width, 0.5 + 3.3 * lines),
        sharey=True, squeeze=False, layout="constrained",
    )  # fmt: skip
    for ax in axes.flat[len(classes) :]:
        ax.set_visible(False)
    for ax, world_class in zip(axes.flat, classes, strict=False):
        data = [
            [r.path_ratio for r in rows if r.planner == p and r.world_class == world_class
             and r.path_ratio is not None]
            for p in planners
        ]  # fmt: skip
        ax.boxplot([d or [math.nan] for d in data], tick_labels=planners, whis=(0, 100))
        ax.axhline(1.0, color="0.5", linewidth=0.8, linestyle="--")
        ax.set_title(world_class)
        ax.tick_params(axis="x", labelrotation=60)
    for ax in axes[:, 0]:
        ax.set_ylabel("path / optimal (reached only)")
    fig.suptitle("Path length against the shortest collision-free path")
    save_plot(fig, path)
    plt.close(fig)


def save_failed_worlds(rows: Sequence[Row], specs: Sequence[WorldSpec], folder: Path) -> int:
    """Write every world in which some episode failed to ``folder/NAME.json``; the count."""
    failed = {r.world for r in rows if not r.reached}
    chosen = [spec for spec in specs if spec.name in failed]
    if chosen:
        folder.mkdir(parents=True, exist_ok=True)
    for spec in chosen:
        save_world(spec.build(), folder / f"{spec.name}.json")
    return len(chosen)


def machine() -> str:
    """One line on where a benchmark ran: CPU, CPU count, OS, Python and numpy versions, and
    the load average (other jobs on the machine slow a benchmark down)."""
    cpu = platform.processor() or platform.machine()
    with contextlib.suppress(OSError):
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.partition(":")[2].strip()
                break
    return (
        f"{cpu}, {os.cpu_count()} logical CPUs, {platform.system()} {platform.release()}, "
        f"Python {platform.python_version()}, numpy {np.__version__}, "
        f"load average {' '.join(f'{v:.2f}' for v in os.getloadavg())}"
    )


def write_report(
    rows: Sequence[Row], specs: Sequence[WorldSpec], out: str | Path, header: str
) -> list[Path]:
    """Write every output file (see the module docstring) into ``out``; return their paths."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    summaries = summarize(rows)
    files = {
        "results": out / "results.csv",
        "summary": out / "summary.csv",
        "markdown": out / "summary.md",
        "success": out / "success_by_class.png",
        "ratio": out / "path_ratio.png",
    }
    write_csv(files["results"], Row.columns(), rows)
    write_csv(files["summary"], Summary.columns(), summaries)
    with written(files["markdown"]) as partial:
        partial.write_text(summary_markdown(summaries, rows, header))
    plot_success(summaries, files["success"])
    if has_optimal(rows):
        plot_path_ratio(rows, files["ratio"])
    else:
        del files["ratio"]  # no axes to draw
    paths = list(files.values())
    if save_failed_worlds(rows, specs, out / "worlds"):
        paths.append(out / "worlds")
    return paths
