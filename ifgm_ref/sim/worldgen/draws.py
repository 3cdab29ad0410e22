"""Two sources of random choices for one world generator: Hypothesis, or a seeded numpy RNG.

The oracle's world classes (:mod:`ifgm_ref.sim.worldgen.classes`) are written once, against the
small :class:`Draw` interface. :class:`HypothesisDraw` turns every choice into a Hypothesis
draw, so the property tests shrink failing worlds; :class:`RandomDraw` takes every choice
from a ``numpy.random.Generator``, so the benchmark gets the same classes as plain uniform
samples reproducible from a seed (Hypothesis' own data is tuned to find bugs -- boundary
values, empty lists -- and cannot be seeded per task).

>>> import numpy as np
>>> d = RandomDraw(np.random.default_rng(7))
>>> 2.0 <= d.floats(2.0, 3.0, "length") <= 3.0
True
>>> len(d.repeat(lambda d: d.boolean("coin"), max_size=3, label="coins")) <= 3
True
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Protocol, TypeVar

import numpy as np
from hypothesis import strategies as st

T = TypeVar("T")


class Draw(Protocol):
    """The choices a world generator makes. ``label`` names the choice in failure reports."""

    def floats(self, low: float, high: float, label: str) -> float:
        """A float in ``[low, high]``."""
        ...

    def integers(self, low: int, high: int, label: str) -> int:
        """An integer in ``[low, high]``, both included."""
        ...

    def choice(self, options: Sequence[T], label: str) -> T:
        """One of ``options`` (Hypothesis shrinks towards the first)."""
        ...

    def boolean(self, label: str) -> bool:
        """``True`` or ``False``."""
        ...

    def repeat(
        self, build: Callable[[Draw], T], *, max_size: int, label: str, min_size: int = 0
    ) -> list[T]:
        """``min_size`` to ``max_size`` values, each made by ``build`` from this source."""
        ...


class HypothesisDraw:
    """Choices drawn by Hypothesis inside a ``@st.composite`` strategy (they shrink)."""

    def __init__(self, draw: st.DrawFn) -> None:
        self._draw = draw

    def floats(self, low: float, high: float, label: str) -> float:
        return self._draw(st.floats(low, high), label=label)

    def integers(self, low: int, high: int, label: str) -> int:
        return self._draw(st.integers(low, high), label=label)

    def choice(self, options: Sequence[T], label: str) -> T:
        return self._draw(st.sampled_from(options), label=label)

    def boolean(self, label: str) -> bool:
        return self._draw(st.booleans(), label=label)

    def repeat(
        self, build: Callable[[Draw], T], *, max_size: int, label: str, min_size: int = 0
    ) -> list[T]:
        element = strategy(build)
        return self._draw(st.lists(element, min_size=min_size, max_size=max_size), label=label)


class RandomDraw:
    """Choices drawn uniformly from a seeded ``numpy.random.Generator``."""

    def __init__(self, rng: np.random.Generator) -> None:
        self._rng = rng

    def floats(self, low: float, high: float, label: str) -> float:
        return float(self._rng.uniform(low, high))

    def integers(self, low: int, high: int, label: str) -> int:
        return int(self._rng.integers(low, high, endpoint=True))

    def choice(self, options: Sequence[T], label: str) -> T:
        return options[int(self._rng.integers(len(options)))]

    def boolean(self, label: str) -> bool:
        return bool(self._rng.integers(2))

    def repeat(
        self, build: Callable[[Draw], T], *, max_size: int, label: str, min_size: int = 0
    ) -> list[T]:
        return [build(self) for _ in range(self.integers(min_size, max_size, label))]


def strategy(build: Callable[[Draw], T]) -> st.SearchStrategy[T]:
    """The Hypothesis strategy of the values ``build`` makes from its draws."""

    @st.composite
    def values(draw: st.DrawFn) -> T:
        return build(HypothesisDraw(draw))

    return values()
