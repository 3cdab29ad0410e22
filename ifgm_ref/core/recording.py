"""Record an episode as the planner saw it, and replay it into another planner.

:class:`RecordingPlanner` wraps a planner and keeps its reset and every observation and
command; :meth:`RecordingPlanner.recording` freezes them into a :class:`Recording`.
:func:`replay` hands a recording's observations, in order, to a fresh planner (open loop:
its commands move nothing) and yields each recorded command beside the new one. Three users
compare the two their own way: the oracle's ``deterministic`` check (bit for bit), the
test vectors' reference traces (within the file's tolerances:
:func:`ifgm_ref.oracle.vectors.replay_traces`), and ``benchmarks/bench_decision.py``, which
times and counts the replayed decisions. ``ifgm-ref simulate --record`` writes a recording
as a ROS bag (:mod:`ifgm_ref.io.bags.write`). The module knows no map: it sits below the
simulator's users (the oracle, the bags, the command line), which all record through it.

Examples
--------
>>> from ifgm_ref.planners import make_planner
>>> from ifgm_ref.io.scenarios import resolve_world
>>> from ifgm_ref.core.params import SimParams
>>> from ifgm_ref.sim.simulator import simulate
>>> recorder = RecordingPlanner(make_planner("iba"))
>>> _ = simulate(resolve_world("post"), recorder, SimParams(max_time=1.0))
>>> recording = recorder.recording()
>>> len(recording.steps)
10
>>> all(again == recorded for _, recorded, again in replay(recording, make_planner("iba")))
True
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import NamedTuple

from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation, Planner

__all__ = ["Recording", "RecordingPlanner", "Replayed", "replay"]


@dataclass(frozen=True)
class Recording:
    """An episode as a planner saw it: how it was reset, then every (observation, command)."""

    start: Pose
    goal: Point
    params: EpisodeParams
    steps: tuple[tuple[Observation, Command], ...]


class Replayed(NamedTuple):
    """One replayed step: the observation, the command recorded for it, and the new one."""

    observation: Observation
    recorded: Command
    command: Command


class RecordingPlanner:
    """Pass every call on to ``planner`` and keep what went through.

    Attributes
    ----------
    reset_args : tuple or None
        ``(start, goal, params)`` of the last reset.
    steps : list of (Observation, Command)
        Every step since construction, in order.
    """

    def __init__(self, planner: Planner) -> None:
        self.planner = planner
        self.name = planner.name
        self.reset_args: tuple[Pose, Point, EpisodeParams] | None = None
        self.steps: list[tuple[Observation, Command]] = []

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        """Record the episode's start, then reset the wrapped planner."""
        self.reset_args = (start, goal, params)
        self.planner.reset(start, goal, params)

    def step(self, observation: Observation) -> Command:
        """Decide with the wrapped planner and record the exchange."""
        command = self.planner.step(observation)
        self.steps.append((observation, command))
        return command

    def recording(self) -> Recording:
        """What has been recorded: the last reset and every step since construction.

        Raises
        ------
        ValueError
            If the planner was never reset.
        """
        if self.reset_args is None:
            raise ValueError("nothing recorded: the planner was never reset")
        return Recording(*self.reset_args, steps=tuple(self.steps))


def replay(
    recording: Recording,
    planner: Planner,
    *,
    step: Callable[[Planner, Observation], Command] | None = None,
    observations: Sequence[Observation] | None = None,
) -> Iterator[Replayed]:
    """Reset ``planner`` as recorded, then step it through the recorded observations.

    The reset happens at once (an exception from it propagates from this call); the steps
    happen one per item taken from the returned iterator, so a caller may stop at the first
    mismatch, and an exception from ``step`` propagates from that item.

    Parameters
    ----------
    recording : Recording
        The episode to replay.
    planner : Planner
        A fresh planner; its commands are returned, not executed (open loop).
    step : callable, optional
        Decides one step: ``step(planner, observation)``; default ``planner.step(observation)``
        (a benchmark times or traces it here).
    observations : sequence of Observation, optional
        Handed to the planner in place of the recorded ones, one per step (the recorded ones
        are still yielded).

    Returns
    -------
    iterator of Replayed
        ``(observation, recorded, command)`` per step, in order.
    """
    handed = [obs for obs, _ in recording.steps] if observations is None else list(observations)
    if len(handed) != len(recording.steps):
        raise ValueError(
            f"{len(handed)} observations, but the recording has {len(recording.steps)} steps"
        )
    planner.reset(recording.start, recording.goal, recording.params)
    return _steps(recording, planner, step, handed)


def _steps(
    recording: Recording,
    planner: Planner,
    step: Callable[[Planner, Observation], Command] | None,
    handed: Sequence[Observation],
) -> Iterator[Replayed]:
    for (observation, recorded), given in zip(recording.steps, handed, strict=True):
        command = planner.step(given) if step is None else step(planner, given)
        yield Replayed(observation, recorded, command)
