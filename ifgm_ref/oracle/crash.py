"""An unexpected exception said in one line: what a verdict of ``error`` reports when a
planner, a program or the oracle's own machinery crashed."""

from __future__ import annotations

import traceback
from pathlib import Path
from types import TracebackType

__all__ = ["crash"]


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
