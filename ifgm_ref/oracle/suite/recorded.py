"""The reference's episode written into a suite case, and rebuilt with no reference running.

A reference-level case (``agrees_with_reference``) holds what the reference IFGM answered at
every step of its episode in the case's world, as the JSON-lines protocol writes a command
(:func:`~ifgm_ref.io.transport.wire.command_message`, without its ``type``), with the atoms it
held and its nearest finite decisions' margins (:mod:`ifgm_ref.oracle.agreement`). The
observations are not stored: driving the simulator with the recorded commands sees them
again, exactly, because the simulator is deterministic; :func:`rebuilt` checks that the
replay ended as recorded.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.params import SimParams
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import Command, EpisodeParams, Observation
from ifgm_ref.core.recording import RecordingPlanner
from ifgm_ref.io.transport.wire import command_message, parse_command
from ifgm_ref.oracle.agreement import ReferenceEpisode, reference_episode, tie_bound
from ifgm_ref.paper.flowchart import Atoms
from ifgm_ref.sim.simulator import simulate
from ifgm_ref.sim.world import World

__all__ = ["NEAREST", "rebuilt", "recorded"]

#: How many of a step's nearest decisions are kept besides the ties: those a divergence's
#: message shows (:func:`~ifgm_ref.oracle.agreement.divergence_message`).
NEAREST = 4


def recorded(world: World, sim: SimParams) -> dict[str, Any]:
    """Run the reference IFGM (our readings) in ``world`` and write down its episode."""
    episode = reference_episode(world, sim)
    margins = []
    for found in episode.margins:  # an infinite margin is no decision near its threshold
        nearest = sorted(((n, v) for n, v in found.items() if math.isfinite(v)), key=_second)
        kept = nearest[:NEAREST] + [(n, v) for n, v in nearest[NEAREST:] if v <= tie_bound(n)]
        margins.append(dict(kept))
    return {
        "commands": [_command(command) for _, command in episode.recording.steps],
        "atoms": [[n for n in Atoms.names() if getattr(a, n)] for a in episode.atoms],
        "margins": margins,
        "end": episode.run.result.stop_reason,
    }


def _second(item: tuple[str, float]) -> float:
    return item[1]


def _command(command: Command) -> dict[str, Any]:
    """``command`` as the protocol writes it, without the message's ``type``."""
    message = command_message(command)
    del message["type"]
    return message


class _Replay:
    """A planner that answers the recorded commands, one per step."""

    name = "reference (recorded)"

    def __init__(self, commands: list[Command]) -> None:
        self.commands = commands
        self.k = 0

    def reset(self, start: Pose, goal: Point, params: EpisodeParams) -> None:
        self.k = 0

    def step(self, observation: Observation) -> Command:
        if self.k >= len(self.commands):
            raise ImplementationError("the recorded episode has no more commands")
        self.k += 1
        return self.commands[self.k - 1]


def rebuilt(world: World, sim: SimParams, data: Mapping[str, Any]) -> ReferenceEpisode:
    """The reference's episode of :func:`recorded`, its observations seen again by driving
    the simulator with its commands; a replay that ends otherwise than recorded (another
    simulator than the one that recorded it) is an :class:`ImplementationError`."""
    commands = [parse_command({"type": "command", **message}) for message in data["commands"]]
    planner = RecordingPlanner(_Replay(commands))
    run = simulate(world, planner, sim)
    recording = planner.recording()
    if len(recording.steps) != len(commands) or run.result.stop_reason != data["end"]:
        raise ImplementationError(
            f"the recorded reference episode replays as {len(recording.steps)} steps ending "
            f"{run.result.stop_reason}, but was recorded as {len(commands)} ending {data['end']}"
        )
    atoms = tuple(Atoms(**{n: n in held for n in Atoms.names()}) for held in data["atoms"])
    margins = tuple(dict(found) for found in data["margins"])
    return ReferenceEpisode(recording, margins, atoms, run)
