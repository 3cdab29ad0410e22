"""Planners that misbehave on purpose, for the tests of the bench and the soak; a test names
one by its factory path (:data:`CRASHES`)."""

from __future__ import annotations


class Crashes:
    """A planner whose every step raises: a run must record it as an error, not end."""

    name = "crashes"

    def reset(self, *args: object) -> None:
        """Nothing to set up."""

    def step(self, observation: object) -> None:
        """Raise ``RuntimeError("boom")``."""
        raise RuntimeError("boom")


#: The factory path of :class:`Crashes`, as planner lists take it.
CRASHES = f"{__name__}:Crashes"
