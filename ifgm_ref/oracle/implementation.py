"""The implementation under test: how to make its planners, what it promises, its equations.

Like scikit-learn's estimator tags, a planner declares what it promises, and the oracle
generates only the checks that apply (:class:`Promises`). The paper's Table 1 and section 5
say what each planner promises: the Bug family, IBA and IFGM converge in every solvable world
class; FGM and APF do not promise convergence where U, H (and, for APF, symmetric) obstacles
are (Table 1: "trapped"). A user's implementation promises what the planner it implements
promises (``promises="ifgm"`` by default), the noise levels it tolerates included
(:attr:`Promises.noise`, which the robust profile checks: :mod:`ifgm_ref.oracle.robust`).
"""

from __future__ import annotations

import shlex
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace

from ifgm_ref.core.errors import ImplementationError, PlannerError
from ifgm_ref.core.pose import Point, Pose
from ifgm_ref.core.protocol import EpisodeParams, Planner
from ifgm_ref.io.transport.external import TIMEOUT
from ifgm_ref.io.transport.loading import load_planner_factory
from ifgm_ref.planners import PLANNERS, declared_promises
from ifgm_ref.planners.promises import ALL_CLASSES, REFERENCE_NOISE_LEVELS
from ifgm_ref.planners.promises import Promises as Promises
from ifgm_ref.sim.noise import NoiseLevels

__all__ = [
    "ALL_CLASSES",
    "PROMISES",
    "REFERENCE_NOISE",
    "Implementation",
    "promises_of",
]

#: The noise levels the reference planners promise
#: (:data:`~ifgm_ref.planners.promises.REFERENCE_NOISE_LEVELS`; :mod:`ifgm_ref.sim.noise`).
REFERENCE_NOISE = NoiseLevels.parse(REFERENCE_NOISE_LEVELS)
#: How to say what an implementation the oracle cannot find promises of promises.
HOW_TO_PROMISE = (
    "say what it promises: --promises ifgm (ifgm-ref oracle), --ifgm-promises ifgm (pytest), "
    'promises="ifgm" (check_planner), a --spec file, or a promises attribute on its factory'
)


def promised_noise(promises: Promises) -> NoiseLevels | None:
    """The noise levels ``promises`` promise (:attr:`Promises.noise`), parsed; ``None``: no
    robustness promised.

    >>> promised_noise(Promises(noise="range=0.02")).range, promised_noise(Promises())
    (0.02, None)
    """
    return None if promises.noise is None else NoiseLevels.parse(promises.noise, "noise")


#: What each built-in planner promises, as it declares it (:data:`ifgm_ref.planners.PLANNERS`).
PROMISES: dict[str, Promises] = {name: info.promises for name, info in PLANNERS.items()}


#: The equations a built-in planner is checked with when none are given: the reference's.
REFERENCE_EQUATIONS = "ifgm_ref.paper.equations"


def default_equations(spec: str) -> str | None:
    """The equations checked for the Python planner ``spec`` when none are given (``ifgm-ref
    oracle --planner`` without ``--equations``, the pytest plugin's ``--ifgm-impl`` without
    ``--ifgm-equations``): :data:`REFERENCE_EQUATIONS` for a built-in planner (a name of
    :data:`ifgm_ref.planners.PLANNERS`), whose equations are the reference's; ``None`` for
    anything else, whose equation checks are then not applicable, saying how to give them.

    >>> default_equations("fgm"), default_equations("mypkg.module:make_planner")
    ('ifgm_ref.paper.equations', None)
    """
    return REFERENCE_EQUATIONS if spec in PLANNERS else None


def promises_of(name: str) -> Promises:
    """The promises of the built-in planner ``name``.

    >>> promises_of("dwa").converges_in
    frozenset()
    >>> promises_of("mypkg")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: no promises known for 'mypkg'; known: apf, bug1, \
bug2, distbug, dwa, fgm, iba, ifgm, straight
    """
    try:
        return PROMISES[name]
    except KeyError:
        known = ", ".join(sorted(PROMISES))
        raise ImplementationError(f"no promises known for {name!r}; known: {known}") from None


def promises_for(factory: object, label: str, promises: Promises | str | None) -> Promises:
    """What the implementation ``factory`` (named ``label``) is held to: ``promises`` if given
    (:class:`Promises` or a built-in planner's name), else what it declares
    (:func:`ifgm_ref.planners.declared_promises`); neither is one line saying how.

    >>> promises_for(lambda: None, "mypkg.mod:make", None)
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: mypkg.mod:make declares no promises; say what it \
promises: --promises ifgm (ifgm-ref oracle), --ifgm-promises ifgm (pytest), promises="ifgm" \
(check_planner), a --spec file, or a promises attribute on its factory
    """
    if isinstance(promises, Promises):
        return promises
    if promises is not None:
        return promises_of(promises)
    try:
        declared = declared_promises(factory)
    except PlannerError as err:
        raise ImplementationError(str(err)) from None
    if declared is None:
        raise ImplementationError(f"{label} declares no promises; {HOW_TO_PROMISE}")
    return declared


@dataclass
class Implementation:
    """A planner implementation to check.

    Parameters
    ----------
    factory : callable
        Returns a planner (``name``, ``reset``, ``step``) ready for a new episode; called
        once per episode. An out-of-process planner's factory returns the same adapter every
        time (its program runs once and plays every episode).
    label : str
        How reports name it (``ifgm``, ``mypkg.module:make_planner``, ``cmd: ./my_planner``).
    promises : Promises
        What it promises; decides which checks apply.
    equations : object or None
        Anything with the reference's equation functions as attributes (a module, say), to
        check eqs. (1)-(4); ``None`` skips the equation checks.
    runs_as : tuple of str
        The ``ifgm-ref simulate`` options that run it, as a counterexample's replay command
        gives them (:meth:`simulate_options`); empty: derived from ``label``.
    """

    factory: Callable[[], Planner]
    label: str
    promises: Promises = field(default_factory=Promises)
    equations: object | None = None
    runs_as: tuple[str, ...] = ()

    def simulate_options(self) -> str:
        """The ``ifgm-ref simulate`` options that run it: :attr:`runs_as`, quoted, or
        ``--planner LABEL``, or ``--cmd "COMMAND"`` for a program labelled ``cmd: COMMAND``.

        >>> Implementation(lambda: None, "cmd: ./port --fast").simulate_options()
        '--cmd "./port --fast"'
        >>> nodes = Implementation(lambda: None, "ros", runs_as=("--ros-node", "python3 a.py"))
        >>> nodes.simulate_options()
        "--ros-node 'python3 a.py'"
        """
        if self.runs_as:
            return shlex.join(self.runs_as)
        if self.label.startswith("cmd: "):
            return f'--cmd "{self.label[5:]}"'
        return f"--planner {self.label}"

    @classmethod
    def from_spec(
        cls,
        spec: str,
        *,
        promises: Promises | str | None = None,
        equations: object | None = None,
    ) -> Implementation:
        """A Python planner named like ``ifgm-ref serve --planner``: built-in or module:attr.

        ``promises`` defaults to what the planner declares (:func:`promises_for`): a built-in
        planner's own, a factory's ``promises`` attribute; anything else must be told, or it
        is an :class:`ImplementationError`, as is a factory that makes no planner, here,
        before any check.
        """
        factory = load_planner_factory(spec)
        return cls(factory, spec, promises_for(factory, spec, promises), equations)

    def declare_readings(self, readings: Mapping[str, str]) -> None:
        """Declare the readings it takes of the paper's open choices (``--reading``,
        :attr:`Promises.readings`), beside what it promises otherwise."""
        self.promises = replace(self.promises, readings=dict(readings))

    @property
    def is_program(self) -> bool:
        """Whether it is a program run through the JSON-lines protocol (``from_command``) or
        ROS nodes (``--ros-node``, :class:`~ifgm_ref.io.ros.bridge.RosFactory`)."""
        from ifgm_ref.io.ros.bridge import RosFactory
        from ifgm_ref.io.transport.external import ExternalFactory

        return isinstance(self.factory, ExternalFactory | RosFactory)

    def close(self) -> None:
        """Stop a program under test (a factory with ``close``, e.g. ``from_command``)."""
        close = getattr(self.factory, "close", None)
        if close is not None:
            close()

    def answers_reset(self) -> None:
        """Start a planner and reset it once on an empty problem (the origin, heading 0, the
        goal 10 robot radii ahead), then close it: a program that cannot start, or does not
        answer ``reset`` with ``ready``, is bad input, said once, before any check.

        Raises
        ------
        ImplementationError
            The program's failure, as the transport words it.
        """
        params = EpisodeParams()
        planner = self.factory()
        try:
            planner.reset(Pose(0.0, 0.0, 0.0), Point(10 * params.robot.radius, 0.0), params)
        finally:
            self.close()

    @classmethod
    def from_command(
        cls,
        command: str | Sequence[str],
        *,
        timeout: float = TIMEOUT,
        startup_timeout: float | None = None,
        promises: Promises | str | None = None,
        equations: object | None = None,
    ) -> Implementation:
        """A program speaking the JSON-lines protocol, started at the first episode and kept
        for every later one (a worker process of :func:`~ifgm_ref.oracle.runner.check_planner`
        starts it anew for each check it runs); labelled ``cmd: COMMAND``. ``promises``
        defaults to IFGM's.

        ``timeout`` is the wait for each reply, ``startup_timeout`` for the first reply of
        each start of the program and its exit (default: 60 s, or ``timeout`` if longer), in
        s; see
        :class:`~ifgm_ref.io.transport.external.ExternalPlanner`. A timeout that is not a finite
        number > 0 is a :class:`~ifgm_ref.core.errors.ParameterError` here.
        """
        from ifgm_ref.io.transport.external import ExternalFactory

        if not isinstance(promises, Promises):
            promises = promises_of(promises or "ifgm")
        factory = ExternalFactory(command, timeout=timeout, startup_timeout=startup_timeout)
        text = command if isinstance(command, str) else shlex.join(command)
        return cls(factory, f"cmd: {text}", promises, equations)
