"""The ``ifgm-ref`` command line.

Every error that bad input can cause is reported as one line on stderr
(``ifgm-ref: error: ...``) with exit status 2, never as a traceback. Output piped to a reader
that stops reading (``ifgm-ref planners | head -1``) ends the command quietly with status 141
(128 + SIGPIPE), as a shell reports it for any Unix tool the closed pipe stopped. Ctrl-C
and SIGTERM stop any command with one line, saying what it had finished and what it had not
written, and exit 130 or 143 (:mod:`.interrupt`); each file a command writes is written
whole or not at all, and said on stderr as it lands (:mod:`ifgm_ref.core.outputs`).

One module per subcommand or group of them, each adding its parser (``add_NAME``) and
running it (``run_NAME``): :mod:`.simulate`; :mod:`.listings` (``worlds``, ``planners``);
:mod:`.artefacts` (``figures``, ``vectors``, ``trace-matrix``); :mod:`.oracle`; :mod:`.suite`;
:mod:`.report`; :mod:`.bench`; :mod:`.serve`; :mod:`.replay`; :mod:`.docs`. What they share
is in :mod:`.common`.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable, Sequence
from importlib import import_module
from pathlib import Path
from typing import TYPE_CHECKING

from ifgm_ref.apps.cli.interrupt import as_interruption, exit_status, received, terminable
from ifgm_ref.core.errors import IfgmRefError
from ifgm_ref.core.outputs import LEDGER

if TYPE_CHECKING:
    from ifgm_ref.apps.cli.common import Subcommands

__all__ = ["EXIT_BROKEN_PIPE", "build_parser", "main"]

#: Exit status when the reader of the output went away: 128 + SIGPIPE (13).
EXIT_BROKEN_PIPE = 141


#: Every subcommand, in the order ``ifgm-ref --help`` lists them: its module in this package
#: and the module's function that adds its parser.
SUBCOMMANDS: dict[str, tuple[str, str]] = {
    "simulate": ("simulate", "add_simulate"),
    "worlds": ("listings", "add_worlds"),
    "figures": ("artefacts", "add_figures"),
    "planners": ("listings", "add_planners"),
    "vectors": ("artefacts", "add_vectors"),
    "oracle": ("oracle", "add_oracle"),
    "suite": ("suite", "add_suite"),
    "report": ("report", "add_report"),
    "bench": ("bench", "add_bench"),
    "trace-matrix": ("artefacts", "add_trace_matrix"),
    "serve": ("serve", "add_serve"),
    "replay": ("replay", "add_replay"),
    "docs": ("docs", "add_docs"),
}


def subcommands(names: Sequence[str] = tuple(SUBCOMMANDS)) -> list[Callable[[Subcommands], None]]:
    """The ``add_NAME`` functions of the subcommands ``names`` (default all), in that order
    (imported here, not with this package, so that Ctrl-C during the imports is met by
    :func:`main`)."""
    adds = (SUBCOMMANDS[name] for name in names)
    return [getattr(import_module(f"{__name__}.{module}"), add) for module, add in adds]


def build_parser(argv: Sequence[str] | None = None) -> argparse.ArgumentParser:
    """The argument parser of ``ifgm-ref``: when ``argv`` starts with a subcommand, with that
    subcommand alone (it parses the rest; the others' modules, and what they import, are
    not loaded), else with all of them (``ifgm-ref --help``, a misspelt subcommand)."""
    from ifgm_ref.apps.cli.common import Parser

    parser = Parser(
        prog="ifgm-ref",
        description="Reference implementation of IFGM and IBA (obstacle avoidance for "
        "mobile robots with U and H shaped obstacles).",
    )
    sub = parser.add_subparsers(
        dest="command", required=True, metavar="COMMAND", parser_class=Parser
    )
    named = [argv[0]] if argv and argv[0] in SUBCOMMANDS else list(SUBCOMMANDS)
    for add in subcommands(named):
        add(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status."""
    LEDGER.reset(announce=_say_written)
    try:
        try:
            with terminable():
                given = list(sys.argv[1:] if argv is None else argv)
                args = build_parser(given).parse_args(given)
                args.argv = given
                return int(args.func(args))
        except Exception as err:  # a library may turn Ctrl-C into an error of its own
            signum = received()
            if signum is None:
                raise
            raise as_interruption(signum) from err
    except KeyboardInterrupt as err:
        name, status = exit_status(err)
        print(f"ifgm-ref: interrupted by {name}: {LEDGER.summary()}", file=sys.stderr)
        return status
    except BrokenPipeError:
        # Only our own output can raise it here (the transport's pipes are written in threads
        # that take it as the program's end). Point stdout at nothing, so that the flush at
        # exit does not raise it again.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    except (IfgmRefError, OSError) as err:
        from ifgm_ref.apps.cli.common import EXIT_USAGE

        print(f"ifgm-ref: error: {err}", file=sys.stderr)
        return EXIT_USAGE
    finally:
        LEDGER.reset()  # the library, used after a command in the same process, says nothing


def _say_written(path: Path) -> None:
    print(f"wrote {path}", file=sys.stderr)
