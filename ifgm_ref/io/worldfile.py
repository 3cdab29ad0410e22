"""World files: read and write a :class:`~ifgm_ref.sim.world.World` as JSON.

The format is specified in ``docs/world-format.md``. In short::

    {"name": "...", "bounds": [xmin, ymin, xmax, ymax],
     "start": [x, y, theta], "goal": [x, y],
     "obstacles": [{"polygon": [[x, y], ...]}, {"circle": {"center": [x, y], "radius": r}}],
     "robot": {...}, "sensor": {...}}

Only ``start`` and ``goal`` are required; an optional field may be left out or be ``null``.
Units are feet, seconds and radians.

Every problem raises :class:`~ifgm_ref.core.errors.WorldError` with one line naming the file and
the JSON path, e.g. ``world.json: obstacles[1].circle.radius: must be a finite number > 0,
got -2``. The checks on values are those of :mod:`ifgm_ref.sim.world` and
:mod:`ifgm_ref.core.params` (worded by :mod:`ifgm_ref.core.validate`); this module adds only what is
about the file: its JSON syntax, its fields, and the JSON literals ``NaN`` and ``Infinity`` (and
overflowing numbers such as ``1e999``), which Python's ``json`` accepts but JSON does not.

Writing is canonical: :func:`dumps_world` gives one text per world, floats are written with
``repr`` (which reads back to the same float), and the ``robot`` and ``sensor`` blocks list
only the fields that differ from the defaults. So ``loads_world(dumps_world(w)) == w`` and
``dumps_world(loads_world(dumps_world(w))) == dumps_world(w)``. For files people read and edit,
``digits`` rounds the geometry (bounds, start, goal, obstacles) to that many significant digits
(``ifgm-ref worlds --export`` writes :data:`EXPORT_DIGITS`), so that a built shape's rounding
(``11.999999999999998``) is written as the number it stands for (``12.0``).
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import fields
from pathlib import Path
from typing import Any, TypeVar

from ifgm_ref.core.errors import ParameterError, WorldError
from ifgm_ref.core.outputs import written
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.sim.world import Circle, Obstacle, Polygon, World

__all__ = [
    "dumps_world",
    "load_world",
    "loads_world",
    "save_world",
    "world_from_dict",
    "world_to_dict",
]

#: Top-level fields in the order :func:`dumps_world` writes them.
FIELDS = ("name", "bounds", "start", "goal", "obstacles", "robot", "sensor")
#: Top-level fields a world file must have.
REQUIRED = ("start", "goal")
#: Significant digits of the geometry that ``ifgm-ref worlds --export`` writes: a built
#: shape's coordinates are off by a few units in the 16th digit (rotations by pi/2, sums of
#: offsets); 12 digits drop that and move no coordinate by more than 5e-12 of itself.
EXPORT_DIGITS = 12


_Block = TypeVar("_Block", RobotParams, SensorParams)


class _Literal(float):
    """A JSON number that is no finite float (``NaN``, ``Infinity``, ``1e999``), with its text.

    Its ``repr`` is the text of the file, so that a validator's message ("must be a finite
    number, got NaN") quotes the file rather than Python.
    """

    text: str

    def __new__(cls, text: str) -> _Literal:
        literal = super().__new__(cls, text)
        literal.text = text
        return literal

    def __repr__(self) -> str:
        return self.text


class _Object(dict[str, Any]):
    """A JSON object that remembers the keys it held more than once (JSON does not forbid it)."""

    duplicates: tuple[str, ...] = ()


def _object_pairs(pairs: list[tuple[str, Any]]) -> _Object:
    obj = _Object()
    duplicates = []
    for key, value in pairs:
        if key in obj:
            duplicates.append(key)
        obj[key] = value
    obj.duplicates = tuple(duplicates)
    return obj


def _parse_float(text: str) -> float:
    value = float(text)
    return value if math.isfinite(value) else _Literal(text)


def _json_type(value: object) -> str:
    """The JSON name of the type of a parsed value."""
    if isinstance(value, dict):
        return "object"
    if isinstance(value, list):
        return "array"
    if isinstance(value, str):
        return "string"
    if isinstance(value, bool):
        return "boolean"
    if value is None:
        return "null"
    if isinstance(value, int | float):
        return "number"
    return type(value).__name__  # not from JSON: a dict built in Python may hold anything


def _check_object(
    value: object, where: str, *, allowed: tuple[str, ...], required: tuple[str, ...] = ()
) -> dict[str, Any]:
    """Check that ``value`` is an object with no repeated, unknown or missing field."""
    if not isinstance(value, dict):
        raise WorldError(f"{where}: must be an object, got {_json_type(value)}")
    duplicates = getattr(value, "duplicates", ())
    if duplicates:
        raise WorldError(f"{where}: repeated field(s) {', '.join(sorted(set(duplicates)))}")
    unknown = sorted(set(value) - set(allowed))
    if unknown:
        raise WorldError(
            f"{where}: unknown field(s) {', '.join(unknown)}; allowed: {', '.join(allowed)}"
        )
    missing = [name for name in required if name not in value]
    if missing:
        raise WorldError(f"{where}: missing required field(s) {', '.join(missing)}")
    return value


def _obstacle(entry: object, where: str) -> Obstacle:
    """Build one entry of ``obstacles`` (``where`` is ``"<file>: obstacles[i]"``)."""
    kinds = _check_object(entry, where, allowed=("polygon", "circle"))
    if len(kinds) != 1:
        got = ", ".join(kinds) if kinds else "none"
        raise WorldError(f"{where}: must have exactly one field, polygon or circle, got {got}")
    ((kind, body),) = kinds.items()
    if kind == "circle":
        body = _check_object(
            body, f"{where}.circle", allowed=("center", "radius"), required=("center", "radius")
        )
    try:
        if kind == "polygon":
            return Polygon(body)
        return Circle(body["center"], body["radius"])
    except WorldError as err:  # its message starts with "polygon" or "circle."
        raise WorldError(f"{where}.{err}") from None


def _block(cls: type[_Block], raw: object, key: str, source: str) -> _Block:
    """Build the ``robot`` or ``sensor`` block; a missing block means every default."""
    if raw is None:
        return cls()
    names = tuple(f.name for f in fields(cls))
    data = _check_object(raw, f"{source}: {key}", allowed=names)
    try:
        return cls.from_mapping(data, where=key)
    except ParameterError as err:
        raise WorldError(f"{source}: {err}") from None


def world_from_dict(data: object, *, source: str = "<dict>") -> World:
    """Build a world from parsed JSON (the inverse of :func:`world_to_dict`).

    Parameters
    ----------
    data : object
        The parsed top-level value, normally a ``dict``.
    source : str, default "<dict>"
        Where the data came from; it starts every error message.

    Raises
    ------
    WorldError
        On any deviation from the format or an invalid world.

    Examples
    --------
    >>> world_from_dict({"start": [0, 0, 0], "goal": [10, 0]}).goal
    Point(x=10.0, y=0.0)
    >>> world_from_dict({"start": [0, 0, 0], "goal": [10, 0], "gaol": [1, 1]})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.WorldError: <dict>: unknown field(s) gaol; allowed: name, bounds, ...
    """
    if not isinstance(data, dict):
        raise WorldError(f"{source}: the top level must be an object, got {_json_type(data)}")
    _check_object(data, source, allowed=FIELDS, required=REQUIRED)
    raw_obstacles = data.get("obstacles")
    if raw_obstacles is None:
        raw_obstacles = []
    if not isinstance(raw_obstacles, list):
        raise WorldError(f"{source}: obstacles: must be an array, got {_json_type(raw_obstacles)}")
    obstacles = tuple(
        _obstacle(entry, f"{source}: obstacles[{i}]") for i, entry in enumerate(raw_obstacles)
    )
    robot = _block(RobotParams, data.get("robot"), "robot", source)
    sensor = _block(SensorParams, data.get("sensor"), "sensor", source)
    try:
        return World(
            start=data["start"],
            goal=data["goal"],
            obstacles=obstacles,
            bounds=data.get("bounds"),
            robot=robot,
            sensor=sensor,
            name=data.get("name"),
        )
    except WorldError as err:  # its message starts with the field's path
        raise WorldError(f"{source}: {err}") from None


def loads_world(text: str, *, source: str = "<string>") -> World:
    """Read a world from the text of a world file.

    Parameters
    ----------
    text : str
        JSON text.
    source : str, default "<string>"
        The name to start error messages with, normally the file's path.

    Examples
    --------
    >>> loads_world('{"start": [0, 0, 0], "goal": [10, 0], "robot": {"radius": 0.5}}').robot.radius
    0.5
    >>> loads_world('{"start": [0, 0, NaN], "goal": [10, 0]}')
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.WorldError: <string>: start[2]: must be a finite number, got NaN
    >>> loads_world('{"start": [0, 0, 0],\\n "goal": [10, 0]')  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ifgm_ref.core.errors.WorldError: <string>: invalid JSON at line 2, column 17: Expecting ',' ...
    """
    try:
        data = json.loads(
            text,
            parse_float=_parse_float,
            parse_constant=_Literal,
            object_pairs_hook=_object_pairs,
        )
    except json.JSONDecodeError as err:
        raise WorldError(
            f"{source}: invalid JSON at line {err.lineno}, column {err.colno}: {err.msg}"
        ) from None
    except (ValueError, RecursionError) as err:  # e.g. an integer of more than 4300 digits
        raise WorldError(f"{source}: invalid JSON: {err}") from None
    return world_from_dict(data, source=source)


def load_world(path: str | os.PathLike[str]) -> World:
    """Read a world file (UTF-8 JSON); error messages start with ``path``."""
    source = os.fspath(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as err:
        raise WorldError(f"{source}: cannot read the world file: {err.strerror or err}") from None
    except UnicodeDecodeError as err:
        raise WorldError(f"{source}: not UTF-8 text (byte {err.start}: {err.reason})") from None
    return loads_world(text, source=source)


def _changed(block: RobotParams | SensorParams) -> dict[str, Any]:
    """The fields of ``block`` that differ from its class's defaults (a dynamics field at its
    default is not in the mapping at all: :meth:`~ifgm_ref.core.params.RobotParams.to_mapping`)."""
    default = type(block)().to_mapping()
    return {k: v for k, v in block.to_mapping().items() if k not in default or v != default[k]}


def _obstacle_to_dict(obstacle: Obstacle, digits: int | None) -> dict[str, Any]:
    if isinstance(obstacle, Circle):
        center, radius = _rounded(obstacle.center, digits), _rounded([obstacle.radius], digits)
        return {"circle": {"center": center, "radius": radius[0]}}
    return {"polygon": [_rounded(vertex, digits) for vertex in obstacle.vertices]}


def _rounded(values: Any, digits: int | None) -> list[float]:
    """``values`` as a list, each rounded to ``digits`` significant digits (``None``: as is)."""
    if digits is None:
        return list(values)
    return [float(f"{value:.{digits}g}") for value in values]


def world_to_dict(world: World, *, digits: int | None = None) -> dict[str, Any]:
    """The world as JSON-ready data, fields in :data:`FIELDS` order.

    ``name`` and ``bounds`` appear when set; ``robot`` and ``sensor`` list only the fields
    that differ from the defaults and are left out when none does; ``obstacles`` is always
    written. ``digits`` rounds the geometry (bounds, start, goal, obstacles) to that many
    significant digits; ``None`` (the default) keeps every float exactly.

    Examples
    --------
    >>> from dataclasses import replace
    >>> world = World(start=(0, 0, 0), goal=(9, 0), obstacles=[Circle((4, 4), 1)])
    >>> data = world_to_dict(world)
    >>> data["start"], data["goal"]
    ([0.0, 0.0, 0.0], [9.0, 0.0])
    >>> data["obstacles"]
    [{'circle': {'center': [4.0, 4.0], 'radius': 1.0}}]
    >>> "robot" in data, world_to_dict(replace(world, robot=RobotParams(radius=2.0)))["robot"]
    (False, {'radius': 2.0})
    >>> world_to_dict(replace(world, goal=(11.999999999999998, 0.1 + 0.2)), digits=12)["goal"]
    [12.0, 0.3]
    """
    data: dict[str, Any] = {}
    if world.name is not None:
        data["name"] = world.name
    if world.bounds is not None:
        data["bounds"] = _rounded(world.bounds, digits)
    data["start"] = _rounded(world.start, digits)
    data["goal"] = _rounded(world.goal, digits)
    data["obstacles"] = [_obstacle_to_dict(obstacle, digits) for obstacle in world.obstacles]
    for key, block in (("robot", world.robot), ("sensor", world.sensor)):
        changed = _changed(block)
        if changed:
            data[key] = changed
    return data


def _compact(value: object) -> str:
    return json.dumps(value, ensure_ascii=False, allow_nan=False, separators=(", ", ": "))


def dumps_world(world: World, *, digits: int | None = None) -> str:
    """The text of the world's file: one field per line, one obstacle per line.

    ``digits`` rounds the geometry to that many significant digits (:func:`world_to_dict`).

    Examples
    --------
    >>> world = World(start=(0, 0, 0), goal=(9, 0), obstacles=[Circle((4, 4), 1)], name="pillar")
    >>> print(dumps_world(world), end="")
    {
      "name": "pillar",
      "start": [0.0, 0.0, 0.0],
      "goal": [9.0, 0.0],
      "obstacles": [
        {"circle": {"center": [4.0, 4.0], "radius": 1.0}}
      ]
    }
    """
    lines = []
    for key, value in world_to_dict(world, digits=digits).items():
        if key == "obstacles" and value:
            body = ",\n".join(f"    {_compact(obstacle)}" for obstacle in value)
            lines.append(f'  "obstacles": [\n{body}\n  ]')
        else:
            lines.append(f"  {_compact(key)}: {_compact(value)}")
    return "{\n" + ",\n".join(lines) + "\n}\n"


def save_world(world: World, path: str | os.PathLike[str], *, digits: int | None = None) -> None:
    """Write the world to ``path`` as UTF-8 JSON (see :func:`dumps_world`; ``digits`` rounds
    the geometry to that many significant digits, ``None`` keeps every float exactly), whole
    or not at all (:func:`ifgm_ref.core.outputs.written`; one of many files, it is not said)."""
    try:
        with written(path, announce=False) as partial:
            partial.write_text(dumps_world(world, digits=digits), encoding="utf-8")
    except OSError as err:
        raise WorldError(
            f"{os.fspath(path)}: cannot write the world file: {err.strerror or err}"
        ) from None
