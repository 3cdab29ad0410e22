"""Output files written whole or not at all, and the ledger of what a command wrote.

:func:`written` hands a writer a temporary name beside the file (hidden, with the file's own
suffix, so that a writer choosing its format by suffix still does) and renames it over the
file once the writer is done (:func:`os.replace`, atomic on one file system). A reader never
sees half a file, and a writer stopped by an exception, Ctrl-C included, leaves no temporary
and the previous file, if there was one, untouched. A path that is there and is not a
regular file (``/dev/stdout``, a named pipe) is written in place, and a symbolic link's
target is replaced, not the link.

:data:`LEDGER` keeps, for the command running in this process, the files it means to write
(:meth:`Ledger.plan`), those it wrote and what it is doing (:meth:`Ledger.doing`); the
command line says each file as it lands (:attr:`Ledger.announce`) and, when a command is
interrupted, what was finished and what is missing (:meth:`Ledger.summary`).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

__all__ = ["LEDGER", "Ledger", "written"]


class Ledger:
    """The files one command planned and wrote, and what it is doing now."""

    def __init__(self) -> None:
        self.planned: list[Path] = []
        self.written: list[Path] = []
        self.now = ""
        #: Called with each file as it lands (the command line prints ``wrote PATH``).
        self.announce: Callable[[Path], None] | None = None

    def reset(self, announce: Callable[[Path], None] | None = None) -> None:
        """Forget the last command's files; announce the next one's with ``announce``."""
        self.planned, self.written, self.now = [], [], ""
        self.announce = announce

    def plan(self, *paths: str | os.PathLike[str]) -> None:
        """Say that the command means to write ``paths`` (what :meth:`summary` calls missing
        until they are written)."""
        self.planned += [Path(p) for p in paths if Path(p) not in self.planned]

    def doing(self, what: str) -> None:
        """Say what the command is doing now (``"simulating"``, ``"check 3 of 12"``)."""
        self.now = what

    def landed(self, path: Path, *, announce: bool = True) -> None:
        """Record ``path`` as written whole and announce it; a file not announced (one of many
        in a folder the command names: world files, a counterexample's) is recorded only if
        planned, so that an interruption's line stays one line."""
        if announce or path in self.planned:
            self.written.append(path)
        if announce and self.announce is not None:
            self.announce(path)

    def missing(self) -> list[Path]:
        """The planned files not written (yet)."""
        return [p for p in self.planned if p not in self.written]

    def summary(self) -> str:
        """What was finished and what is missing, in one line.

        >>> ledger = Ledger()
        >>> ledger.plan("a.png", "b.gif")
        >>> ledger.landed(Path("a.png"))
        >>> ledger.doing("writing b.gif")
        >>> ledger.summary()
        'while writing b.gif; wrote a.png; not written: b.gif'
        """
        parts = [f"while {self.now}"] if self.now else []
        done = ", ".join(map(str, self.written))
        parts.append(f"wrote {done}" if done else "nothing written")
        missing = self.missing()
        if missing:
            parts.append("not written: " + ", ".join(map(str, missing)))
        return "; ".join(parts)


#: The ledger of the command running in this process.
LEDGER = Ledger()


@contextmanager
def written(path: str | os.PathLike[str], *, announce: bool = True) -> Iterator[Path]:
    """Yield a temporary path for the writer of ``path``; when the block ends normally, move
    it over ``path`` and record it in :data:`LEDGER` (said as it lands unless not
    ``announce``: one of many files whose folder the command names); when it raises, remove
    it.

    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> with written(folder / "a.txt") as partial:
    ...     _ = partial.write_text("whole")
    >>> (folder / "a.txt").read_text(), sorted(p.name for p in folder.iterdir())
    ('whole', ['a.txt'])
    """
    final = Path(path)
    if final.exists() and not final.resolve().is_file():  # /dev/stdout, a FIFO: no rename
        yield final
        LEDGER.landed(final, announce=announce)
        return
    target = final.resolve()  # a symbolic link keeps pointing at the new file
    partial = target.with_name(f".{target.stem}.partial-{os.getpid()}{target.suffix}")
    try:
        yield partial
        os.replace(partial, target)
    except BaseException:
        partial.unlink(missing_ok=True)
        raise
    LEDGER.landed(final, announce=announce)
