"""What a soak found: reached/N per planner and class, failures by stop reason, the Wilson
bound on the failure rate, and every failure with the command that replays it.

The failure rate of a planner in a class is a binomial proportion measured on ``N`` worlds.
Its upper bound is the upper end of the two-sided Wilson 95 % interval
(:func:`ifgm_ref.core.stats.wilson_interval` of the failures in ``N``): with no failure it is
``z**2 / (N + z**2)``, 0.19 % for ``N`` = 2,000 (issue 24's "below 0.2 % at 95 %") and
0.038 % for the 10,000 worlds of five such classes pooled.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from ifgm_ref.apps.bench.soak import SoakRow
from ifgm_ref.core.stats import wilson_interval

#: The confidence of the bound on the failure rate.
CONFIDENCE = 0.95
#: The class column of a planner's row over every class.
ALL = "all"


@dataclass(frozen=True)
class Tally:
    """One planner in one class (or :data:`ALL`): worlds, goals reached, failures by stop
    reason (most frequent first, then by name)."""

    planner: str
    world_class: str
    worlds: int
    reached: int
    failures: tuple[tuple[str, int], ...]

    @property
    def failed(self) -> int:
        """Episodes that did not reach the goal."""
        return self.worlds - self.reached

    @property
    def failure_rate_bound(self) -> float:
        """The upper end of the Wilson :data:`CONFIDENCE` interval of the failure rate.

        >>> round(Tally("p", "open", 2000, 2000, ()).failure_rate_bound, 6)
        0.001917
        """
        return wilson_interval(self.failed, self.worlds, CONFIDENCE).high


def _tally(planner: str, world_class: str, rows: Sequence[SoakRow]) -> Tally:
    reasons = Counter(row.stop_reason for row in rows if not row.reached)
    ordered = tuple(sorted(reasons.items(), key=lambda item: (-item[1], item[0])))
    reached = sum(row.reached for row in rows)
    return Tally(planner, world_class, len(rows), reached, ordered)


def _in_order(values: Sequence[str]) -> list[str]:
    return list(dict.fromkeys(values))


def summarise(rows: Sequence[SoakRow]) -> list[Tally]:
    """A tally per planner and class, in the order the rows name them, each planner's followed
    by its :data:`ALL` tally when it ran in more than one class."""
    classes = _in_order([row.world_class for row in rows])
    tallies = []
    for planner in _in_order([row.planner for row in rows]):
        own = [row for row in rows if row.planner == planner]
        for world_class in classes:
            chosen = [row for row in own if row.world_class == world_class]
            if chosen:
                tallies.append(_tally(planner, world_class, chosen))
        if len({row.world_class for row in own}) > 1:
            tallies.append(_tally(planner, ALL, own))
    return tallies


def _percent(value: float) -> str:
    return f"{100.0 * value:.3g} %"


def summary_table(tallies: Sequence[Tally]) -> str:
    """The tallies as a fixed-width table, one line per tally.

    >>> print(summary_table([Tally("ifgm", "open", 40, 38, (("time_limit", 2),))]))
    planner   class      reached      failures by stop reason         failure rate, 95 % upper bound
    ifgm      open       38/40        time_limit 2                    16.5 %
    """
    header = f"{'planner':<9} {'class':<10} {'reached':<12} {'failures by stop reason':<31} "
    lines = [header + f"failure rate, {CONFIDENCE * 100:g} % upper bound"]
    for t in tallies:
        reasons = ", ".join(f"{reason} {count}" for reason, count in t.failures) or "-"
        lines.append(
            f"{t.planner:<9} {t.world_class:<10} {f'{t.reached}/{t.worlds}':<12} {reasons:<31} "
            f"{_percent(t.failure_rate_bound)}"
        )
    return "\n".join(lines)


def _number(value: float | None, spec: str) -> str:
    return "-" if value is None else format(value, spec)


def describe(row: SoakRow) -> str:
    """One line on an episode: planner, class, seed, how and when it stopped.

    >>> from ifgm_ref.apps.bench.soak import SoakRow
    >>> describe(SoakRow("ifgm", "open", 5000, False, False, "time_limit", 155.3, 155.3, 204.1,
    ...                  1553))
    'ifgm open seed 5000: time_limit at 155.3 s of 155.3 s, path 204.1 ft, 1553 steps'
    """
    line = (
        f"{row.planner} {row.world_class} seed {row.seed}: {row.stop_reason} at "
        f"{_number(row.time_s, '.1f')} s of {row.time_bound:.1f} s, path "
        f"{_number(row.path_length, '.1f')} ft, {_number(row.steps, 'd')} steps"
    )
    return line + (f" ({row.detail})" if row.detail else "")


def replay_command(row: SoakRow, program: str) -> str:
    """The command that replays ``row`` with the soak's ``program`` (its ``--replay`` mode)."""
    return f"{program} --replay {row.world_class}:{row.seed} --planner {row.planner}"


def simulate_command(row: SoakRow, world_file: str | Path) -> str:
    """The ``ifgm-ref simulate`` command that replays ``row`` from its saved world file, to
    the same time limit (printed exactly: ``repr`` of a float reads back as the same float)."""
    return f"ifgm-ref simulate {world_file} --planner {row.planner} --max-time {row.time_bound!r}"


def failure_report(rows: Sequence[SoakRow], program: str, worlds: Path | None = None) -> str:
    """Every failure, planner by planner in the rows' order, with its replay command, and
    the ``ifgm-ref simulate`` one when its world was saved in the folder ``worlds``."""
    failed = [row for row in rows if not row.reached]
    planners = _in_order([row.planner for row in rows])
    failed.sort(key=lambda row: planners.index(row.planner))  # stable: class, seed kept
    lines = [f"failures: {len(failed)}"]
    for row in failed:
        lines += [describe(row), f"  replay: {replay_command(row, program)}"]
        if worlds is not None:
            lines.append(f"      or: {simulate_command(row, worlds / f'{row.world}.json')}")
    return "\n".join(lines)
