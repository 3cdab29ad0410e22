"""One ROS node's process, seen from the broker: started, talked to, killed.

The node runs its command unchanged (``python3 node.py``) in its own process group
(``start_new_session``), with the stand-in's shim packages first on its ``PYTHONPATH``
(:data:`SHIMS`) and one end of a socket pair open as the file descriptor that
:data:`~ifgm_ref.io.ros.client.FD_VARIABLE` names: the broker's link, apart from the node's
stdout and stderr, which are only its log (both go to one pipe, copied by a thread that keeps
the last lines for error messages). Every read of the link is bounded by a deadline.
"""

from __future__ import annotations

import collections
import contextlib
import json
import os
import select
import shlex
import signal
import socket
import subprocess
import threading
import time
import weakref
from pathlib import Path
from typing import IO, Any, TextIO

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.io.ros.client import FD_VARIABLE, INDEX_VARIABLE

__all__ = ["SHIMS", "SHIMS2", "NodeProcess"]

#: The folder of shim packages (``rospy``, ``tf``, ``sensor_msgs``, ...) put first on a
#: node's ``PYTHONPATH``.
SHIMS = Path(__file__).resolve().parent / "shims"
#: The same for ROS 2 nodes (``rclpy`` and ROS 2 Humble's message packages).
SHIMS2 = Path(__file__).resolve().parent / "shims2"
#: The folder that holds the ``ifgm_ref`` package, put after them (a node imports the
#: stand-in from the same tree as the broker's).
ROOT = Path(__file__).resolve().parents[3]
#: How many of the node's last log lines an error message quotes.
TAIL = 20
#: Longest wait for a killed node to be reaped, s.
REAP_WAIT = 5.0


class NodeProcess:
    """A node's process and its link to the broker (see the module docstring).

    Parameters
    ----------
    command : str
        The node's command line, split with :func:`shlex.split` (no shell).
    index : int
        The node's place among the nodes (0, 1, ...).
    log : text stream, optional
        Where the node's output is copied as it comes.
    shims : path, default :data:`SHIMS`
        The shim packages put first on its ``PYTHONPATH`` (:data:`SHIMS2` for ROS 2).
    """

    def __init__(
        self, command: str, index: int, log: TextIO | None = None, shims: Path = SHIMS
    ) -> None:
        self.command = command
        self.argv = shlex.split(command)
        if not self.argv:
            raise ImplementationError("a --ros-node command cannot be empty")
        self.index = index
        self.shims = shims
        self.name = f"node {index} ({command})"
        self._log = log
        self._process: subprocess.Popen[bytes] | None = None
        self._sock: socket.socket | None = None
        self._buffer = b""
        self._tail: collections.deque[str] = collections.deque(maxlen=TAIL)
        self._copier: threading.Thread | None = None
        self._finalizer: weakref.finalize[..., NodeProcess] | None = None

    @property
    def running(self) -> bool:
        """Whether the process was started and not killed."""
        return self._process is not None

    def start(self) -> None:
        """Start the node's process.

        Raises
        ------
        ImplementationError
            When it cannot be started.
        """
        ours, theirs = socket.socketpair()
        env = dict(os.environ)
        path = [str(self.shims), str(ROOT), env.get("PYTHONPATH", "")]
        env["PYTHONPATH"] = os.pathsep.join(p for p in path if p)
        env.update({FD_VARIABLE: str(theirs.fileno()), INDEX_VARIABLE: str(self.index)})
        env.setdefault("PYTHONHASHSEED", "0")  # the same set order on every run
        env.setdefault("PYTHONUNBUFFERED", "1")  # prints and tracebacks in the order made
        env.setdefault("OPENBLAS_NUM_THREADS", "1")  # a node forks: no BLAS threads
        try:
            self._process = subprocess.Popen(
                self.argv,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                env=env,
                pass_fds=(theirs.fileno(),),
                start_new_session=True,
            )
        except OSError as err:
            ours.close()
            raise ImplementationError(f"cannot start {self.name}: {err}") from None
        finally:
            theirs.close()
        self._sock = ours
        self._buffer = b""
        self._tail = collections.deque(maxlen=TAIL)
        assert self._process.stdout is not None
        self._copier = threading.Thread(
            target=_copy, args=(self._process.stdout, self._tail, self._log), daemon=True
        )
        self._copier.start()
        # a planner dropped without close() (a worker that ends) leaves no node behind
        self._finalizer = weakref.finalize(self, _kill_group, self._process)

    def send(self, line: dict[str, Any]) -> None:
        """Write one line to the node (the node reads it when it next waits)."""
        assert self._sock is not None
        try:
            self._sock.sendall((json.dumps(line, separators=(",", ":")) + "\n").encode())
        except OSError as err:
            raise self.failure(f"cannot write to it ({err})") from None

    def receive(self, deadline: float, waiting_for: str, timeout: str = "") -> dict[str, Any]:
        """The node's next line, awaited until ``deadline`` (``time.monotonic()``); ``timeout``
        names the timeout that set it, for the error message.

        Raises
        ------
        ImplementationError
            When the deadline passes, the link closes or the line is not a JSON object.
        """
        assert self._sock is not None
        while b"\n" not in self._buffer:
            left = deadline - time.monotonic()
            ready = select.select([self._sock], [], [], max(left, 0.0))[0] if left > 0 else []
            if not ready:
                raise self.failure(f"no answer while {waiting_for} ({timeout}; process killed)")
            chunk = self._sock.recv(1 << 16)
            if not chunk:
                raise self.failure(f"it {self._status()} while {waiting_for}")
            self._buffer += chunk
        line, _, self._buffer = self._buffer.partition(b"\n")
        try:
            message = json.loads(line)
        except ValueError:
            message = None
        if not isinstance(message, dict):
            raise self.failure(f"it wrote a line that is not a JSON object: {line[:80]!r}")
        return message

    def _status(self) -> str:
        process = self._process
        if process is None:
            return "was not running"
        with contextlib.suppress(subprocess.TimeoutExpired):
            process.wait(timeout=1.0)
        code = process.poll()
        if code is None:
            return "closed its link to the broker"
        if code < 0:
            return f"was killed by signal {signal.Signals(-code).name}"
        return f"exited with status {code}"

    def failure(self, text: str) -> ImplementationError:
        """An error about this node, quoting its last log lines, after killing it."""
        self.kill()
        if self._copier is not None:
            self._copier.join(timeout=1.0)
        tail = list(self._tail)
        quoted = "".join(f"\n    {line}" for line in tail) if tail else " (none)"
        return ImplementationError(f"ROS {self.name}: {text}; last output:{quoted}")

    def kill(self) -> None:
        """Kill the node's process group and reap it (nothing if it is not running)."""
        process, self._process = self._process, None
        if self._finalizer is not None:
            self._finalizer.detach()
            self._finalizer = None
        if process is not None:
            _kill_group(process)
        if self._sock is not None:
            self._sock.close()
            self._sock = None

    def wait_exit(self, timeout: float) -> int | None:
        """Wait up to ``timeout`` s for the process to exit; its status, or None."""
        if self._process is None:
            return None
        try:
            return self._process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            return None


def _kill_group(process: subprocess.Popen[bytes]) -> None:
    """Kill ``process``'s group if it still runs, and reap it."""
    if process.poll() is None:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(process.pid, signal.SIGKILL)
    with contextlib.suppress(subprocess.TimeoutExpired):
        process.wait(timeout=REAP_WAIT)


def _copy(stream: IO[bytes], tail: collections.deque[str], log: TextIO | None) -> None:
    """Keep the last lines of ``stream`` in ``tail``, copying each to ``log`` (a thread)."""
    with contextlib.suppress(OSError, ValueError):
        for raw in stream:
            line = raw.decode("utf-8", errors="replace")
            tail.append(line.rstrip("\r\n"))
            if log is not None:
                log.write(line)
                log.flush()
