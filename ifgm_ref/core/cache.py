"""The folder where ifgm-ref keeps what it can make again: the user's cache folder.

``$XDG_CACHE_HOME/ifgm-ref``, or ``~/.cache/ifgm-ref`` (the XDG base directory convention),
never the working folder. It holds the unpacked BARN worlds (:mod:`ifgm_ref.io.barn`) and
the oracle's Hypothesis files (``ifgm-ref oracle``); deleting it loses nothing.
"""

from __future__ import annotations

import os
from pathlib import Path


def user_cache() -> Path:
    """``$XDG_CACHE_HOME/ifgm-ref``, or ``~/.cache/ifgm-ref`` when that is unset or empty (not
    created here)."""
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "ifgm-ref"
