"""Progress on stderr for long runs: a bar on a terminal, a line now and then in a log.

Every long job of the package (a bench, a soak, the figures, an animation, a replay, a long
episode) reports its progress through :func:`progress_bar`. On a terminal that is a
``tqdm`` bar with an ETA. When stderr goes to a file or a pipe (CI, ``nohup``,
``2> log.txt``) a redrawn bar would fill the log with carriage returns, and none at all
leaves a reader guessing for minutes: there it writes one whole line every
:data:`LOG_INTERVAL` seconds, and a last one at the end, but only for a job that ran that
long, so a short one stays silent.
"""

from __future__ import annotations

import sys
import time
from typing import Any

from tqdm import tqdm

__all__ = ["LOG_INTERVAL", "progress_bar"]

#: Seconds between two progress lines in a log (stderr not a terminal).
LOG_INTERVAL = 10.0
#: The line written to a log: what, how far, how long so far and how long still.
LOG_FORMAT = (
    "{desc}: {n_fmt}/{total_fmt} {unit} ({percentage:.0f}%), {elapsed} so far, {remaining} left"
)


class _LogLines(tqdm):  # type: ignore[type-arg]
    """A ``tqdm`` that writes a whole line every :data:`LOG_INTERVAL` s, never a redrawn bar,
    and nothing for a job shorter than that."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        self._shown: float | None = None  # the count of the last line written
        self._written = time.time()  # when it was written (the start, before any)
        kwargs.update(mininterval=LOG_INTERVAL, bar_format=LOG_FORMAT, leave=False)
        super().__init__(*args, **kwargs)

    def display(self, msg: str | None = None, pos: int | None = None) -> None:
        if not hasattr(self, "start_t"):  # the first display, from tqdm's constructor
            return
        closing = msg == ""  # tqdm clears a bar it does not leave with an empty message
        if closing and self._shown in (None, self.n):
            return
        # tqdm's monitor thread may ask too: at most one line every LOG_INTERVAL s.
        if not closing and time.time() - self._written < LOG_INTERVAL:
            return
        self.fp.write(self.__str__() + "\n")
        self.fp.flush()
        self._shown, self._written = self.n, time.time()


def progress_bar(
    *, total: int, desc: str, unit: str, progress: bool | None, **options: Any
) -> tqdm:  # type: ignore[type-arg]
    """A progress bar over ``total`` ``unit`` labelled ``desc`` on stderr: ``progress=True``
    a ``tqdm`` bar, ``False`` none, ``None`` a bar on a terminal and a line now and then
    otherwise (module docstring). ``options`` go to a bar (``leave``, ``mininterval``...), not
    to the lines, whose pace and format are fixed.
    """
    if progress is None and not sys.stderr.isatty():
        return _LogLines(total=total, desc=desc, unit=unit, file=sys.stderr)
    return tqdm(total=total, desc=desc, unit=unit, disable=progress is False, **options)
