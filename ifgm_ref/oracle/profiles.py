"""The oracle's profiles: how hard it looks (examples per check) and under which noise.

``quick`` (50 examples per check, the default), ``standard`` (200) and ``thorough`` (1000) are
noise-free; ``robust`` runs the quick profile's 50 under the noise levels the implementation
promises (:attr:`~ifgm_ref.oracle.implementation.Promises.noise`), and :func:`with_noise` puts
given levels on any profile: a robustness run (:mod:`ifgm_ref.oracle.robust`).
:func:`on_engine` runs any profile's simulations on another engine (:mod:`ifgm_ref.sim.engine`):
the robot with mass of ``mujoco`` (``docs/oracle.md``, "On the physical robot").
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from hypothesis import HealthCheck, Phase, settings

from ifgm_ref.core.errors import ImplementationError
from ifgm_ref.core.params import (
    DT,
    GOAL_TOLERANCE,
    EngineName,
    SensorParams,
    SimParams,
    engine_named,
)
from ifgm_ref.oracle.implementation import Promises, promised_noise
from ifgm_ref.sim.engine import require_physics
from ifgm_ref.sim.noise import NoiseLevels
from ifgm_ref.sim.physics.bodies import body_named

__all__ = [
    "PROFILES",
    "PROFILE_ALIASES",
    "Profile",
    "engine_tag",
    "noise_tags",
    "on_engine",
    "profile_named",
    "with_noise",
]


@dataclass(frozen=True)
class Profile:
    """How hard to look: examples per check, derandomized draws, and whether a failing
    example is shrunk (to the simplest world that still fails) before it is reported.

    ``seed`` draws the examples from that seed instead (random, but repeatable): how the
    oracle's power over many draws is measured (``benchmarks/bench_oracle_power.py``).

    ``noise`` puts those noise levels in every world simulated; a ``robust`` profile without
    its own levels checks those the implementation promises (:meth:`levels`). Either makes a
    robustness run (:mod:`ifgm_ref.oracle.robust`).

    ``engine`` senses and moves the robot in every episode the checks simulate
    (:class:`ifgm_ref.core.params.EngineName`: ``kinematic``, the default, or ``mujoco``), with
    the ``mujoco`` engine's ``body`` (``None``: the robot's default); either wrong is a
    :class:`~ifgm_ref.core.errors.ParameterError`, as :class:`SimParams` words it. It changes
    no draw: the same examples run on either engine. ``robot`` changes these fields of the
    robot of every world drawn (``--robot``, ``--speed``:
    :func:`~ifgm_ref.core.params.changed_robot`), as pairs.
    ``sensor`` (``None``: each world's own) replaces the sensor of every world drawn, and
    every episode runs at ``dt`` and ends as reached within ``goal_tolerance``: what an
    implementation declares in its specification (:mod:`ifgm_ref.oracle.specification`).
    """

    name: str
    max_examples: int
    derandomize: bool = True
    shrink: bool = True
    seed: int | None = None
    noise: NoiseLevels | None = None
    robust: bool = False
    engine: EngineName | str = EngineName.KINEMATIC  # made an EngineName on construction
    body: str | None = None
    robot: tuple[tuple[str, float], ...] = ()
    sensor: SensorParams | None = None
    dt: float = DT
    goal_tolerance: float = GOAL_TOLERANCE

    def __post_init__(self) -> None:
        object.__setattr__(self, "engine", self.sim().engine)  # SimParams checks engine, body
        if self.body is not None:
            body_named(self.body)

    @property
    def physical(self) -> bool:
        """Whether its episodes run on a robot with mass (not the kinematic engine)."""
        return self.engine is not EngineName.KINEMATIC

    def sim(self) -> SimParams:
        """The simulation settings every episode of its checks starts from: the engine and
        body, the time step and the goal tolerance; each episode sets its own time bound."""
        return SimParams(
            dt=self.dt, goal_tolerance=self.goal_tolerance, engine=self.engine, body=self.body
        )

    @property
    def is_robustness_run(self) -> bool:
        """Whether it checks under noise (its own levels, or the promised ones)."""
        return self.robust or self.noise is not None

    def levels(self, promises: Promises) -> NoiseLevels | None:
        """The noise levels it checks an implementation of ``promises`` at: its own, else for
        a robust profile the promised ones; ``None``: none (a noise-free run, or nothing
        promised).

        >>> from ifgm_ref.oracle.implementation import REFERENCE_NOISE
        >>> promised = Promises(noise=REFERENCE_NOISE.tags())
        >>> PROFILES["robust"].levels(promised).tags()
        'range=0.02,dropout=0.05,odometry=0.01'
        >>> PROFILES["quick"].levels(promised) is None
        True
        """
        levels = (
            self.noise if self.noise is not None or not self.robust else promised_noise(promises)
        )
        return levels if levels is not None and levels.on else None

    def settings(self) -> settings:
        """Hypothesis settings of this profile (no deadline, no example database)."""
        phases = [Phase.explicit, Phase.reuse, Phase.generate]
        return settings(
            max_examples=self.max_examples,
            phases=[*phases, Phase.shrink] if self.shrink else phases,
            derandomize=self.derandomize and self.seed is None,
            deadline=None,
            database=None,
            print_blob=False,
            # One counterexample per check: a check that fails in two ways (two raise sites)
            # would otherwise end in an ExceptionGroup, which is no verdict.
            report_multiple_bugs=False,
            suppress_health_check=[
                HealthCheck.too_slow,
                HealthCheck.filter_too_much,
                HealthCheck.data_too_large,
            ],
        )


#: The profiles, by examples per check: ``quick`` 50 (the default), ``standard`` 200,
#: ``thorough`` 1000; ``robust``, the quick profile's 50 under the noise levels the
#: implementation promises; ``brief`` 10, every check in a fifth of the quick profile's time
#: (the project's own test run uses it). All are derandomized: the same implementation gives
#: the same verdicts on every run.
PROFILES: dict[str, Profile] = {
    p.name: p
    for p in (
        Profile("quick", 50),
        Profile("standard", 200),
        Profile("thorough", 1000),
        Profile("robust", 50, robust=True),
        Profile("brief", 10),
    )
}
#: Old profile names that still work: ``default`` was ``standard``'s name (it was never the
#: default: ``quick`` is).
PROFILE_ALIASES: dict[str, str] = {"default": "standard"}


def profile_named(name: str) -> Profile:
    """The profile called ``name`` (or an old alias of it, :data:`PROFILE_ALIASES`).

    >>> profile_named("default").name
    'standard'
    >>> profile_named("fast")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: unknown profile 'fast'; known: quick, standard, ...
    """
    try:
        return PROFILES[PROFILE_ALIASES.get(name, name)]
    except KeyError:
        known = ", ".join(PROFILES)
        raise ImplementationError(f"unknown profile {name!r}; known: {known}") from None


def with_noise(profile: Profile | str, noise: NoiseLevels | str | None) -> Profile:
    """``profile`` (or the one named) checking at the noise levels ``noise``, if given
    (``"KIND=LEVEL,..."`` as :meth:`~ifgm_ref.sim.noise.NoiseLevels.parse` reads it).

    >>> with_noise("quick", "dropout=0.1").noise.tags()
    'dropout=0.1'
    >>> with_noise("quick", "none")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ImplementationError: noise 'none' turns no noise on: leave it out
    """
    profile = profile_named(profile) if isinstance(profile, str) else profile
    if noise is None:
        return profile
    levels = NoiseLevels.parse(noise) if isinstance(noise, str) else noise
    if not levels.on:
        raise ImplementationError(f"noise {noise!r} turns no noise on: leave it out")
    return replace(profile, noise=levels)


def on_engine(profile: Profile | str, engine: str | None, body: str | None = None) -> Profile:
    """``profile`` (or the one named) simulating on ``engine`` with ``body`` (``None``: as it
    is). The ``mujoco`` engine needs MuJoCo installed: a
    :class:`~ifgm_ref.core.errors.ParameterError` says what to install otherwise.

    >>> print(on_engine("quick", "mujoco", "jackal").sim().engine)
    mujoco
    >>> on_engine("quick", "kinematic", "jackal")
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: `body` applies to the mujoco engine only, got 'jackal'
    """
    profile = profile_named(profile) if isinstance(profile, str) else profile
    if engine is None and body is None:
        return profile
    name = profile.engine if engine is None else engine_named(engine)
    if name is EngineName.MUJOCO:
        require_physics()
    return replace(profile, engine=name, body=body)


def engine_tag(profile: Profile) -> str:
    """The engine ``profile`` simulates on, and its body if one was chosen.

    >>> engine_tag(on_engine("quick", "mujoco", "jackal")), engine_tag(profile_named("quick"))
    ('mujoco (body jackal)', 'kinematic')
    """
    return profile.engine + (f" (body {profile.body})" if profile.body else "")


def noise_tags(profile: Profile, promises: Promises) -> tuple[str | None, str]:
    """The noise levels ``profile`` checks an implementation of ``promises`` at (``None`` in
    a noise-free run) and those it promises, as :meth:`~ifgm_ref.sim.noise.NoiseLevels.tags`.

    >>> noise_tags(PROFILES["robust"], Promises())
    ('none', 'none')
    >>> noise_tags(PROFILES["quick"], Promises(noise="range=0.02,odometry=0.01"))
    (None, 'range=0.02,odometry=0.01')
    """
    levels = profile.levels(promises)
    checked = (levels or NoiseLevels()).tags() if profile.is_robustness_run else None
    return checked, promises.noise or "none"
