"""A planner wrapper that records an episode: its reset and every observation and command.

The oracle's determinism check replays a recording into a fresh planner; the conformance
vectors store recordings as reference traces.
"""

from __future__ import annotations

from ifgm_ref.pose import Point, Pose
from ifgm_ref.protocol import Command, EpisodeParams, Observation, Planner


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
