"""An implementation's own specification, declared in one TOML file (issue 42).

Instead of waiving checks, the implementer declares what the implementation is: what it
promises (:class:`~ifgm_ref.oracle.implementation.Promises`), its goal tolerance, its control
period, its sensor, its robot's size, speed and dynamics, and its readings of the paper's
open choices. The oracle then holds it to exactly that (``ifgm-ref oracle --spec FILE``,
``pytest --ifgm-spec FILE``, ``check_planner(..., spec=FILE)``): every world drawn carries
that robot and sensor, every episode runs at that ``dt`` and ends at that goal tolerance,
and the report's first lines say what it was held to (:meth:`Specification.held_to`).

The file states its length unit (``unit = "ft"`` or ``"m"``); the oracle's worlds are in
feet, so every length is converted to feet on reading (:data:`FEET_PER`). Every key, its unit,
default and meaning: ``docs/oracle.md``, "Declaring your implementation's specification".
Anything wrong in the file (an unknown key, a wrong type, a value out of range) is one
:class:`~ifgm_ref.core.errors.ParameterError` naming the file and the key.

>>> spec = Specification.parse({"unit": "m", "goal_tolerance": 0.3}, "port.toml")
>>> round(spec.goal_tolerance, 4), spec.dt
(0.9843, 0.1)
>>> Specification.parse({"unit": "m", "goal_tolerence": 0.3}, "port.toml")
Traceback (most recent call last):
...
ifgm_ref.core.errors.ParameterError: port.toml: goal_tolerence: unknown key; known: dt, \
goal_tolerance, level, promises, readings, robot, sensor, unit
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from ifgm_ref.core.errors import IfgmRefError, ParameterError
from ifgm_ref.core.params import (
    DT,
    GOAL_TOLERANCE,
    ROBOT_OPTIONS,
    SENSOR_PRESET_UNITS,
    SENSOR_PRESETS,
    RobotParams,
    SensorParams,
    changed_robot,
)
from ifgm_ref.core.validate import NON_NEGATIVE, POSITIVE, Domain, require
from ifgm_ref.oracle.implementation import (
    ALL_CLASSES,
    PROMISES,
    Implementation,
    Promises,
    promises_of,
)
from ifgm_ref.oracle.profiles import Profile, profile_named
from ifgm_ref.planners.ifgm.readings import OPEN_READINGS
from ifgm_ref.sim.noise import NoiseLevels
from ifgm_ref.sim.world import World

__all__ = [
    "FEET_PER",
    "LEVELS",
    "Specification",
    "declared",
    "in_feet",
    "load_specification",
    "refuse_options",
]

#: Feet in one of each length unit a file may state (the oracle's worlds are in feet).
FEET_PER: dict[str, float] = {"ft": 1.0, "m": 1.0 / 0.3048}
#: The levels of conformance a file may declare (``--level``).
LEVELS = ("paper", "reference")
#: The keys of the file's top level, and of each of its tables.
TOP_KEYS = ("unit", "goal_tolerance", "dt", "level", "promises", "sensor", "robot", "readings")
PROMISE_KEYS = ("like", *(f.name for f in fields(Promises) if f.name != "readings"))
SENSOR_KEYS = ("preset", "fov_degrees", "rays", "range_max", "range_min")
#: The robot's fields that are lengths (or lengths per second, per second squared): converted.
ROBOT_LENGTHS = frozenset({"radius", "speed", "braking", "acceleration"})
#: The prefix of worlds in metres among the oracle's explicit examples (BARN's samples, with
#: their own Jackal and LiDAR: :data:`~ifgm_ref.oracle.strategies.BARN_SAMPLES`).
METRE_WORLDS = "barn-"


def in_feet(example: Any) -> bool:
    """Whether the world of ``example`` (a world, or a tuple whose first item is its world)
    is in the oracle's unit, feet: every drawn and built-in world, not BARN's samples.

    >>> in_feet(World(start=(0, 0, 0), goal=(9, 0), name="u_trap"))
    True
    """
    world = example if isinstance(example, World) else example[0]
    return not (world.name or "").startswith(METRE_WORLDS)


@dataclass(frozen=True)
class Specification:
    """What an implementation declares it is, every length in feet.

    Parameters
    ----------
    source : str
        Where it was read from (the file's path), named in every error and in the report.
    unit : {"ft", "m"}
        The length unit the file was written in; :meth:`held_to` shows lengths in both.
    goal_tolerance : float
        Ft: an episode ends as reached when the robot's centre is this close to the goal.
    dt : float
        The control period, s: the simulator's step and the ``dt`` the planner is told.
    sensor : SensorParams
        The sensor of every world the oracle draws (ranges in ft).
    sensor_from : str
        The preset it started from (``paper_ir``, ``jackal_lidar``, ``lidar_180``).
    robot : tuple of (str, float)
        Changes to the robot of every world drawn (:data:`~ifgm_ref.core.params.ROBOT_OPTIONS`,
        in ft, s and rad), as :attr:`~ifgm_ref.oracle.profiles.Profile.robot` holds them.
    promises : Promises
        What it promises, its readings included.
    like : str
        The built-in planner whose promises it started from (``ifgm`` by default).
    level : {"paper", "reference"}
        The level of conformance it is checked at.
    """

    source: str
    unit: str
    goal_tolerance: float = GOAL_TOLERANCE
    dt: float = DT
    sensor: SensorParams = field(default_factory=SensorParams)
    sensor_from: str = "paper_ir"
    robot: tuple[tuple[str, float], ...] = ()
    promises: Promises = PROMISES["ifgm"]
    like: str = "ifgm"
    level: str = "paper"

    @classmethod
    def parse(cls, data: Mapping[str, Any], source: str) -> Specification:
        """The specification the mapping ``data`` (a parsed TOML file) declares.

        Raises
        ------
        ParameterError
            ``"SOURCE: KEY: what is wrong"``: an unknown key, a wrong type, a value out of
            range, a missing ``unit``.
        """
        _known(data, TOP_KEYS, source, "")
        if "unit" not in data:
            raise ParameterError(f'{source}: unit: missing; state the length unit, "ft" or "m"')
        unit = _choice(data["unit"], tuple(FEET_PER), source, "unit")
        feet = FEET_PER[unit]
        sensor, sensor_from = _sensor(_table(data, "sensor", source), feet, source)
        like, promises = _promises(_table(data, "promises", source), source)
        readings = _readings(_table(data, "readings", source), source)
        return cls(
            source=source,
            unit=unit,
            goal_tolerance=feet * _number(data, "goal_tolerance", 1.0, source)
            if "goal_tolerance" in data
            else GOAL_TOLERANCE,
            dt=_number(data, "dt", DT, source),
            sensor=sensor,
            sensor_from=sensor_from,
            robot=_robot(_table(data, "robot", source), feet, source),
            promises=replace(promises, readings=readings),
            like=like,
            level=_choice(data.get("level", "paper"), LEVELS, source, "level"),
        )

    def on(self, profile: Profile) -> Profile:
        """``profile`` holding every episode to this specification: its robot and sensor in
        every world drawn, its ``dt`` and goal tolerance in every episode.

        Raises
        ------
        ParameterError
            ``profile`` already changes the robot (``--robot``): one of the two would be
            ignored.
        """
        if profile.robot:
            changes = ",".join(f"{k}={v:g}" for k, v in profile.robot)
            raise ParameterError(
                f"{self.source}: robot: the profile already sets the robot ({changes}); "
                "declare it in the file's [robot] table only"
            )
        return replace(
            profile,
            robot=self.robot,
            sensor=self.sensor,
            dt=self.dt,
            goal_tolerance=self.goal_tolerance,
        )

    def held_to(self) -> str:
        """What the oracle holds the implementation to, a few lines for the report."""
        lines = [
            f"held to {self.source} (lengths in {self.unit}; the oracle's worlds are in ft):",
            f"  goal tolerance {self._length(self.goal_tolerance)}, dt {self.dt:g} s",
            f"  sensor {self._sensor()}",
            f"  robot {self._robot()}",
            f"  promises {self._promises()}",
            f"  level {self.level}, readings {self._readings()}",
        ]
        return "\n".join(lines)

    def _length(self, feet: float, per: str = "") -> str:
        shown = f"{feet:.4g} ft{per}"
        if self.unit != "ft":
            shown += f" ({feet / FEET_PER[self.unit]:.4g} {self.unit}{per})"
        return shown

    def _sensor(self) -> str:
        s = self.sensor
        fov = f"{math.degrees(s.fov):.4g} deg x {s.rays} rays"
        ranges = f"{self._length(s.range_min)} to {self._length(s.range_max)}"
        return f"{fov}, range {ranges}; preset {self.sensor_from}"

    def _robot(self) -> str:
        if not self.robot:
            return "each drawn world's own (the paper's: radius 1 ft, instant stop)"
        units = {"radius": "", "speed": "/s", "braking": "/s^2", "acceleration": "/s^2"}
        shown = []
        for name, value in self.robot:
            if name in ROBOT_LENGTHS and math.isfinite(value):
                shown.append(f"{name} {self._length(value, units[name])}")
            elif name in ROBOT_LENGTHS:
                shown.append(f"{name} inf (at once)")
            else:
                shown.append(f"{name} {value:g} {'rad/s' if name == 'max_turn_rate' else 's'}")
        return ", ".join(shown)

    def _promises(self) -> str:
        p = self.promises
        classes = ", ".join(sorted(p.converges_in)) or "no class"
        flags = [f.name for f in fields(Promises) if isinstance(getattr(p, f.name), bool)]
        kept = [name for name in flags if getattr(p, name)]
        not_kept = [name for name in flags if not getattr(p, name)]
        noise = p.noise or "none"
        return (
            f"(from {self.like}'s): converges in {classes}; {', '.join(kept) or 'nothing else'}; "
            f"not {', '.join(not_kept) or 'nothing'}; reference {p.reference or 'none'}; "
            f"noise {noise}"
        )

    def _readings(self) -> str:
        readings = self.promises.readings
        return ", ".join(f"{k}={v}" for k, v in sorted(readings.items())) or "the reference's"


def load_specification(path: str | Path) -> Specification:
    """The specification in the TOML file ``path``.

    Raises
    ------
    ParameterError
        The file cannot be read, is not TOML, or declares something wrong (one line naming
        the file and the key: :meth:`Specification.parse`).
    """
    try:
        with open(path, "rb") as file:
            data = tomllib.load(file)
    except OSError as err:
        raise ParameterError(f"{path}: cannot read it: {err.strerror or err}") from None
    except tomllib.TOMLDecodeError as err:
        raise ParameterError(f"{path}: not valid TOML: {err}") from None
    return Specification.parse(data, str(path))


#: The options that declare what a specification file declares, and the file's key for it.
DECLARING_OPTIONS = {
    "--promises": "[promises]",
    "--level": "level",
    "--reading": "[readings]",
    "--robot": "[robot]",
    "--speed": "[robot] speed",
}


def refuse_options(source: str, given: Mapping[str, object]) -> None:
    """Refuse an option given besides the specification ``source`` that declares what the
    file declares (``given``: option, as :data:`DECLARING_OPTIONS` or the plugin's
    ``--ifgm-...`` names it, and its value; ``None`` or empty: not given).

    The file is the whole declaration: an option beside it would either override it or be
    overridden, and a reader of the report could not tell which without the command line.

    >>> refuse_options("port.toml", {"--level": None, "--robot": ""})
    >>> refuse_options("port.toml", {"--robot": "speed=2"})
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.ParameterError: port.toml: --robot speed=2 given with the specification, \
which declares it ([robot]): change the file, or leave out the option
    """
    for option, value in given.items():
        if value is not None and value != "" and value != []:
            shown = ",".join(value) if isinstance(value, list) else value
            key = DECLARING_OPTIONS[option.replace("--ifgm-", "--")]
            raise ParameterError(
                f"{source}: {option} {shown} given with the specification, which declares it "
                f"({key}): change the file, or leave out the option"
            )


# -- reading the file's values -------------------------------------------------------------------


def _where(source: str, key: str) -> str:
    return f"{source}: {key}"


def _known(data: Mapping[str, Any], keys: tuple[str, ...], source: str, table: str) -> None:
    """Refuse the first key of ``data`` not in ``keys`` (``table`` prefixes its name)."""
    for key in data:
        if key not in keys:
            known = ", ".join(sorted(keys))
            raise ParameterError(f"{_where(source, table + key)}: unknown key; known: {known}")


def _table(data: Mapping[str, Any], key: str, source: str) -> dict[str, Any]:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise ParameterError(
            f"{_where(source, key)}: must be a table ([{key}]), got {type(value).__name__}"
        )
    return value


def _choice(value: object, choices: tuple[str, ...], source: str, key: str) -> str:
    if value not in choices:
        raise ParameterError(
            f"{_where(source, key)}: must be one of {', '.join(map(repr, choices))}, got {value!r}"
        )
    return str(value)


def _number(data: Mapping[str, Any], key: str, default: float, source: str) -> float:
    """``data[key]`` (or ``default``), a finite number > 0."""
    return _checked(data.get(key, default), key, POSITIVE, source)


def _checked(value: object, key: str, domain: Domain, source: str) -> float:
    """``value`` as a float, a finite number in ``domain``; else an error naming ``key``."""
    try:
        return require(key.rpartition(".")[2], value, domain)
    except ParameterError as err:
        raise ParameterError(f"{_where(source, key)}: {err}") from None


def _sensor(table: dict[str, Any], feet: float, source: str) -> tuple[SensorParams, str]:
    """The sensor of the ``[sensor]`` table: a preset (in its own unit), with the table's
    overrides (in the file's unit), every range in feet."""
    _known(table, SENSOR_KEYS, source, "sensor.")
    name = _choice(table.get("preset", "paper_ir"), tuple(SENSOR_PRESETS), source, "sensor.preset")
    base = SENSOR_PRESETS[name]()
    scale = FEET_PER[SENSOR_PRESET_UNITS[name]]
    values: dict[str, Any] = {
        "fov": base.fov,
        "rays": base.rays,
        "range_max": base.range_max * scale,
        "range_min": base.range_min * scale,
    }
    for key, domain in (("range_max", POSITIVE), ("range_min", NON_NEGATIVE)):
        if key in table:
            values[key] = feet * _checked(table[key], f"sensor.{key}", domain, source)
    if "fov_degrees" in table:
        degrees = _checked(table["fov_degrees"], "sensor.fov_degrees", POSITIVE, source)
        values["fov"] = math.radians(degrees)
    if "rays" in table:
        values["rays"] = table["rays"]
    try:
        return SensorParams(**values), name
    except ParameterError as err:
        key = next((k for k in ("rays", "range_min") if f"`{k}`" in str(err)), "fov_degrees")
        raise ParameterError(f"{_where(source, 'sensor.' + key)}: {err}") from None


def _robot(table: dict[str, Any], feet: float, source: str) -> tuple[tuple[str, float], ...]:
    """The ``[robot]`` table's changes to the robot, lengths in feet, checked as a robot of
    the defaults (the drawn worlds' robot) would check them."""
    _known(table, ROBOT_OPTIONS, source, "robot.")
    changes: dict[str, float] = {}
    for name, value in table.items():
        infinite = name in ("braking", "acceleration") and value == math.inf
        number = math.inf if infinite else _checked(value, f"robot.{name}", NON_NEGATIVE, source)
        changes[name] = number * (feet if name in ROBOT_LENGTHS else 1.0)
    try:
        changed_robot(RobotParams(), changes, option="robot")
    except ParameterError as err:
        key = str(err).partition("`")[2].partition("`")[0]  # the field it names first
        why = str(err).removeprefix("robot: ")
        raise ParameterError(f"{_where(source, 'robot.' + key)}: {why}") from None
    return tuple(changes.items())


def _promises(table: dict[str, Any], source: str) -> tuple[str, Promises]:
    """The ``[promises]`` table: a built-in planner's promises (``like``), with changes."""
    _known(table, PROMISE_KEYS, source, "promises.")
    like = _choice(table.get("like", "ifgm"), tuple(sorted(PROMISES)), source, "promises.like")
    changes: dict[str, Any] = {}
    for key, value in table.items():
        where = f"promises.{key}"
        if key == "converges_in":
            changes[key] = _classes(value, source)
        elif key == "noise":
            changes[key] = _noise(value, source)
        elif key == "reference":
            changes[key] = {"ifgm": "ifgm", "none": None}[
                _choice(value, ("ifgm", "none"), source, where)
            ]
        elif key != "like" and not isinstance(value, bool):
            raise ParameterError(f"{_where(source, where)}: must be true or false, got {value!r}")
        elif key != "like":
            changes[key] = value
    return like, replace(promises_of(like), **changes)


def _classes(value: object, source: str) -> frozenset[str]:
    where = _where(source, "promises.converges_in")
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise ParameterError(f"{where}: must be a list of world classes, got {value!r}")
    unknown = sorted(set(value) - ALL_CLASSES)
    if unknown:
        known = ", ".join(sorted(ALL_CLASSES))
        raise ParameterError(f"{where}: unknown world classes {unknown}; known: {known}")
    return frozenset(value)


def _noise(value: object, source: str) -> str | None:
    where = _where(source, "promises.noise")
    if not isinstance(value, str):
        raise ParameterError(f'{where}: must be a string "KIND=LEVEL,..." or "none", got {value!r}')
    try:
        levels = NoiseLevels.parse(value)
    except IfgmRefError as err:
        raise ParameterError(f"{where}: {err}") from None
    return levels.tags() if levels.on else None


def _readings(table: dict[str, Any], source: str) -> dict[str, str]:
    """The ``[readings]`` table: each open choice named, with the implementation's reading."""
    _known(table, tuple(OPEN_READINGS), source, "readings.")
    for key, value in table.items():
        if not isinstance(value, str):
            where = _where(source, "readings." + key)
            raise ParameterError(f"{where}: must be a string, got {value!r}")
    return dict(table)


def declared(
    spec: Specification | str | Path,
    impl: Implementation,
    profile: Profile | str,
    promises: object = None,
    level: str | None = None,
) -> tuple[Implementation, Profile, str, str]:
    """``impl`` and ``profile`` held to the specification ``spec`` (or the file it names),
    the level it declares, and what it holds them to (:meth:`Specification.held_to`).

    ``promises`` and ``level`` are what the caller was also given (``None``: nothing): the
    file declares both, so either given besides is a :class:`ParameterError`, as is a
    ``profile`` that already changes the robot; ``impl``'s own promises are replaced.
    """
    spec = spec if isinstance(spec, Specification) else load_specification(spec)
    for given, key, table in ((promises, "promises", "[promises]"), (level, "level", "level")):
        if given is not None:
            raise ParameterError(
                f"{spec.source}: {key}: declared by the file, and also given ({given!r}); "
                f"declare it in the file's {table} only"
            )
    profile = profile_named(profile) if isinstance(profile, str) else profile
    held = replace(impl, promises=spec.promises)
    return held, spec.on(profile), spec.level, spec.held_to()
