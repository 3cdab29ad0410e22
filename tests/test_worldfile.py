"""Tests of :mod:`ifgm_ref.io.worldfile`: exact round trips, canonical text, every error message."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ifgm_ref.core.errors import WorldError
from ifgm_ref.core.params import RobotParams, SensorParams
from ifgm_ref.io.worldfile import (
    dumps_world,
    load_world,
    loads_world,
    save_world,
    world_from_dict,
    world_to_dict,
)
from ifgm_ref.sim.shapes import circle, h_shape, rectangle, regular_polygon, u_shape
from ifgm_ref.sim.world import Bounds, Circle, Obstacle, Polygon, World

DOC = Path(__file__).resolve().parent.parent / "docs" / "world-format.md"

# --- strategies -------------------------------------------------------------------------------
# Obstacles are drawn inside the square [0, 100]^2 and at most ~7.1 ft from their centre; the
# start lies at x <= -40 and the goal at x >= 150, so a robot of radius <= 5 is always clear:
# every drawn world is valid by construction, and shrinks towards fewer, simpler obstacles.

places = st.tuples(st.floats(0.0, 100.0), st.floats(0.0, 100.0))
sizes = st.floats(0.5, 10.0)
turns = st.floats(-math.pi, math.pi)
fractions = st.floats(0.05, 0.95)


@st.composite
def obstacles(draw: st.DrawFn) -> Obstacle:
    """One obstacle of any kind the format holds, through the :mod:`ifgm_ref.sim.shapes`
    builders."""
    kind = draw(st.sampled_from(["circle", "rectangle", "regular", "u", "h"]), label="kind")
    at = draw(places, label="center")
    if kind == "circle":
        return circle(at, draw(sizes, label="diameter") / 2.0)
    if kind == "rectangle":
        return rectangle(at, draw(sizes), draw(sizes), draw(turns, label="angle"))
    if kind == "regular":
        return regular_polygon(at, draw(sizes) / 2.0, draw(st.integers(3, 12)), draw(turns))
    width, length = draw(sizes, label="width"), draw(sizes, label="length")
    if kind == "u":
        thickness = draw(fractions, label="thickness") * min(width / 2.0, length)
        return u_shape(at, width, length, thickness, opening=draw(turns, label="opening"))
    thickness = draw(fractions, label="thickness") * min(width / 2.0, length)
    return h_shape(at, width, length, thickness, orientation=draw(turns, label="orientation"))


robots = st.fixed_dictionaries(
    {},
    optional={
        "radius": st.floats(0.05, 5.0),
        "speed": st.floats(0.01, 20.0),
        "max_turn_rate": st.floats(0.01, 20.0),
    },
).map(lambda kw: RobotParams(**kw))
sensors = st.fixed_dictionaries(
    {},
    optional={
        "fov": st.floats(0.01, 6.28),
        "rays": st.integers(2, 2000),
        "range_max": st.floats(1.0, 500.0),
        "range_min": st.floats(0.0, 0.99),
        "noise_std": st.floats(0.0, 2.0),
        "seed": st.integers(0, 2**64),
    },
).map(lambda kw: SensorParams(**kw))


@st.composite
def worlds(draw: st.DrawFn) -> World:
    """Valid worlds with full-precision floats, optional name, bounds, robot and sensor."""
    bounds = draw(
        st.none()
        | st.tuples(*[st.floats(100.0, 1000.0)] * 4).map(
            lambda m: Bounds(-m[0], -m[1], 200.0 + m[2], 100.0 + m[3])
        ),
        label="bounds",
    )
    return World(
        start=(
            draw(st.floats(-90.0, -40.0), label="start x"),
            draw(st.floats(0.0, 100.0), label="start y"),
            draw(st.floats(-10.0, 10.0), label="start theta"),
        ),
        goal=(draw(st.floats(150.0, 200.0), label="goal x"), draw(st.floats(0.0, 100.0))),
        obstacles=draw(st.lists(obstacles(), max_size=6), label="obstacles"),
        bounds=bounds,
        robot=draw(robots, label="robot"),
        sensor=draw(sensors, label="sensor"),
        name=draw(st.none() | st.text(max_size=20), label="name"),
    )


# --- round trips ------------------------------------------------------------------------------


@given(worlds())
def test_load_of_dump_is_the_same_world(world: World) -> None:
    text = dumps_world(world)
    again = loads_world(text)
    assert again == world
    assert dumps_world(again) == text
    assert json.loads(text) == world_to_dict(world)
    assert world_from_dict(world_to_dict(world)) == world


@given(worlds())
def test_dump_lists_only_changed_parameters(world: World) -> None:
    data = world_to_dict(world)
    for key, block in (("robot", world.robot), ("sensor", world.sensor)):
        written = data.get(key, {})
        default = type(block)()
        for name, value in block.to_mapping().items():
            if value == getattr(default, name):
                assert name not in written, f"{key}.{name}={value!r} is the default"
            else:
                assert written[name] == value, f"{key}.{name} is not written"


def test_save_and_load(tmp_path: Path) -> None:
    world = World(
        start=(0.1, 0.2, 0.3),
        goal=(10.0 / 3.0, 1e-300),
        obstacles=(Circle((5.0, 5.0), math.pi), rectangle((-5.0, -5.0), 1.0, 2.0, angle=0.1)),
        bounds=Bounds(-10.0, -10.0, 10.0, 10.0),
        robot=RobotParams(radius=0.5),
        sensor=SensorParams(rays=181, seed=7),
        name="Ümlaut ☃",
    )
    path = tmp_path / "w.json"
    save_world(world, path)
    assert load_world(path) == world
    assert load_world(str(path)) == world
    text = path.read_text(encoding="utf-8")
    assert text == dumps_world(world)
    assert '"name": "Ümlaut ☃"' in text
    assert '"robot": {"radius": 0.5}' in text
    assert '"sensor": {"rays": 181, "seed": 7}' in text
    assert "3.3333333333333335" in text


def test_minimal_world_is_short() -> None:
    world = World(start=(0.0, 0.0, 0.0), goal=(1.0, 1.0))
    expected = '{\n  "start": [0.0, 0.0, 0.0],\n  "goal": [1.0, 1.0],\n  "obstacles": []\n}\n'
    assert dumps_world(world) == expected


def test_null_optional_fields_mean_the_defaults() -> None:
    text = (
        '{"start": [0, 0, 0], "goal": [1, 1], "name": null, "bounds": null,'
        ' "obstacles": null, "robot": null, "sensor": null}'
    )
    assert loads_world(text) == World(start=(0.0, 0.0, 0.0), goal=(1.0, 1.0))


def test_integer_parameters_stay_integers() -> None:
    world = loads_world('{"start": [0, 0, 0], "goal": [1, 1], "sensor": {"rays": 181}}')
    assert world.sensor.rays == 181 and type(world.sensor.rays) is int
    assert '"sensor": {"rays": 181}' in dumps_world(world)


def test_docs_example_loads_and_is_canonical() -> None:
    text = re.search(r"```json\n(.*?)```", DOC.read_text(encoding="utf-8"), re.S)
    assert text is not None, "docs/world-format.md has no ```json example"
    world = loads_world(text[1], source="example")
    assert dumps_world(world) == text[1]
    assert world.robot == RobotParams(radius=0.75)
    assert world.sensor == SensorParams(rays=136, range_max=20.0)
    # The docs say which builders made the polygons.
    made = [
        rectangle((30, 12), 8, 4),
        u_shape((60, 0), width=20, depth=12, thickness=1, opening=math.pi),
        h_shape((130, 0), width=16, height=20, thickness=1, orientation=math.pi / 2),
    ]
    polygons = [ob for ob in world.obstacles if isinstance(ob, Polygon)]
    for got, want in zip(polygons, made, strict=True):
        for got_vertex, want_vertex in zip(got.vertices, want.vertices, strict=True):
            assert got_vertex == pytest.approx(want_vertex, abs=1e-9)


# --- error messages ---------------------------------------------------------------------------

START_GOAL = '"start": [5.0, 0.0, 0.0], "goal": [195.0, 0.0]'


def extra(fields: str) -> str:
    """A world file with a valid start and goal and the JSON ``fields`` given."""
    return "{" + START_GOAL + ", " + fields + "}"


SQUARE = '{"polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]}'
#: (id, text of world.json, the full message).
CASES = [
    ("syntax", '{"start": [0, 0, 0],\n "goal": [10, 0]',
     "invalid JSON at line 2, column 17: Expecting ',' delimiter"),
    ("empty", "", "invalid JSON at line 1, column 1: Expecting value"),
    ("top-level-array", "[]", "the top level must be an object, got array"),
    ("missing-start", '{"goal": [1, 1]}', "missing required field(s) start"),
    ("missing-both", "{}", "missing required field(s) start, goal"),
    ("unknown-field", extra('"obstacle": []'),
     "unknown field(s) obstacle; allowed: name, bounds, start, goal, obstacles, robot, sensor"),
    ("repeated-field", '{"start": [0, 0, 0], "start": [1, 0, 0], "goal": [9, 9]}',
     "repeated field(s) start"),
    ("nan", '{"start": [0, 0, NaN], "goal": [9, 9]}', "start[2]: must be a finite number, got NaN"),
    ("minus-infinity", '{"start": [0, 0, 0], "goal": [-Infinity, 9]}',
     "goal[0]: must be a finite number, got -Infinity"),
    ("overflow", extra('"bounds": [0, -30, 1e999, 30]'),
     "bounds[2]: must be a finite number, got 1e999"),
    ("string-number", '{"start": [0, 0, 0], "goal": [1, "3"]}',
     "goal[1]: must be a finite number, got '3'"),
    ("boolean-number", '{"start": [true, 0, 0], "goal": [1, 3]}',
     "start[0]: must be a finite number, got True"),
    ("start-string", '{"start": "origin", "goal": [1, 3]}',
     "start: must be a sequence of 3 numbers (x, y, theta), got 'origin'"),
    ("goal-length", '{"start": [0, 0, 0], "goal": [1, 2, 0]}',
     "goal: must be a sequence of 2 numbers (x, y), got 3 item(s): [1, 2, 0]"),
    ("bounds-object", extra('"bounds": {"xmin": 0}'),
     "bounds: must be a sequence of 4 numbers (xmin, ymin, xmax, ymax), got {'xmin': 0}"),
    ("bounds-inverted", '{"start": [5, 5, 0], "goal": [6, 6], "bounds": [10, 0, 0, 10]}',
     "bounds: xmin must be < xmax, got 10.0 >= 0.0"),
    ("obstacles-object", extra('"obstacles": {}'),
     "obstacles: must be an array, got object"),
    ("obstacle-array", extra('"obstacles": [[1, 2]]'),
     "obstacles[0]: must be an object, got array"),
    ("obstacle-both", extra('"obstacles": [{"polygon": [], "circle": {}}]'),
     "obstacles[0]: must have exactly one field, polygon or circle, got polygon, circle"),
    ("obstacle-none", extra('"obstacles": [{}]'),
     "obstacles[0]: must have exactly one field, polygon or circle, got none"),
    ("obstacle-kind", extra('"obstacles": [{"box": [1, 2]}]'),
     "obstacles[0]: unknown field(s) box; allowed: polygon, circle"),
    ("circle-array", extra('"obstacles": [{"circle": [1, 2, 3]}]'),
     "obstacles[0].circle: must be an object, got array"),
    ("circle-missing", extra('"obstacles": [{"circle": {"center": [1, 2]}}]'),
     "obstacles[0].circle: missing required field(s) radius"),
    ("circle-unknown",
     extra('"obstacles": [{"circle": {"center": [1, 2], "radius": 1, "r": 1}}]'),
     "obstacles[0].circle: unknown field(s) r; allowed: center, radius"),
    ("circle-repeated",
     extra('"obstacles": [{"circle": {"center": [1, 2], "radius": 1, "radius": 2}}]'),
     "obstacles[0].circle: repeated field(s) radius"),
    ("circle-radius",
     extra(f'"obstacles": [{SQUARE}, {{"circle": {{"center": [50, 5], "radius": -2}}}}]'),
     "obstacles[1].circle.radius: must be a finite number > 0, got -2"),
    ("circle-center",
     extra('"obstacles": [{"circle": {"center": [50], "radius": 2}}]'),
     "obstacles[0].circle.center: must be a sequence of 2 numbers (x, y), got 1 item(s): [50]"),
    ("polygon-few", extra('"obstacles": [{"polygon": [[0, 0], [1, 1], [0, 0]]}]'),
     "obstacles[0].polygon: needs at least 3 distinct vertices, got 2"),
    ("polygon-collinear",
     extra('"obstacles": [{"polygon": [[0, 0], [1, 1], [2, 2]]}]'),
     "obstacles[0].polygon: vertices are collinear (zero area)"),
    ("polygon-crossing",
     extra(f'"obstacles": [{SQUARE}, {SQUARE}, {{"polygon": [[0, 0], [2, 2], [2, 0], [0, 2]]}}]'),
     "obstacles[2].polygon: is self-intersecting (Self-intersection[1 1])"),
    ("polygon-infinite",
     extra('"obstacles": [{"polygon": [[0, 0], [1, 0], [1, 1], [0, Infinity]]}]'),
     "obstacles[0].polygon[3][1]: must be a finite number, got Infinity"),
    ("polygon-object", extra('"obstacles": [{"polygon": {"x": 1}}]'),
     "obstacles[0].polygon: must be a sequence of (x, y) vertices, got {'x': 1}"),
    ("outside-bounds", '{"start": [-5, 0, 0], "goal": [195, 0], "bounds": [0, -30, 200, 30]}',
     "start: (-5.0, 0.0) is outside the bounds (0.0, -30.0, 200.0, 30.0)"),
    ("inside-obstacle",
     '{"start": [5, 0, 0], "goal": [60.0, 9.5], "obstacles": ['
     f'{SQUARE}, {SQUARE}, {{"polygon": [[54, 9], [66, 9], [66, 10], [54, 10]]}}]}}',
     "goal: (60.0, 9.5) is inside obstacles[2]"),
    ("within-radius",
     '{"start": [1.0, 2.0, 0], "goal": [9, 9],'
     ' "obstacles": [{"polygon": [[1.4, 0], [3.4, 0], [3.4, 4], [1.4, 4]]}]}',
     "start: (1.0, 2.0) is within the robot radius 1.0 ft of obstacles[0] (distance 0.4 ft)"),
    ("within-own-radius",
     '{"start": [0, 0, 0], "goal": [9, 0], "robot": {"radius": 2},'
     ' "obstacles": [{"circle": {"center": [9, 3], "radius": 1}}]}',
     "goal: (9.0, 0.0) is within the robot radius 2 ft of obstacles[0] (distance 2 ft)"),
    ("robot-radius", extra('"robot": {"radius": 0}'),
     "robot: `radius` must be a finite number > 0, got 0"),
    ("robot-array", extra('"robot": [1]'), "robot: must be an object, got array"),
    ("robot-nan", extra('"robot": {"speed": NaN}'),
     "robot: `speed` must be a finite number > 0, got NaN"),
    ("sensor-unknown", extra('"sensor": {"range": 5}'),
     "sensor: unknown field(s) range; allowed: fov, rays, range_max, range_min, noise_std, seed, "
     "noise_rel, dropout, spurious"),
    ("sensor-rays", extra('"sensor": {"rays": 76.5}'),
     "sensor: `rays` must be an integer >= 2, got 76.5"),
    ("sensor-range", extra('"sensor": {"range_min": 20}'),
     "sensor: `range_min` must be < `range_max`, got 20 >= 15.0"),
    ("sensor-repeated", extra('"sensor": {"seed": 1, "seed": 2}'),
     "sensor: repeated field(s) seed"),
    ("name", extra('"name": 3'), "name: must be a string, got 3"),
]  # fmt: skip


@pytest.mark.parametrize(("text", "message"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_loads_world_rejects(text: str, message: str) -> None:
    with pytest.raises(WorldError, match=f"^{re.escape('world.json: ' + message)}$"):
        loads_world(text, source="world.json")


def test_huge_integer_literal_is_refused() -> None:
    text = '{"start": [0, 0, ' + "9" * 5000 + '], "goal": [1, 1]}'
    with pytest.raises(WorldError, match=r"^w\.json: invalid JSON: .*4300"):
        loads_world(text, source="w.json")


def test_world_from_dict_names_its_source() -> None:
    with pytest.raises(WorldError, match=r"^scene: missing required field\(s\) goal$"):
        world_from_dict({"start": [0, 0, 0]}, source="scene")
    with pytest.raises(WorldError, match=r"^<dict>: obstacles: must be an array, got tuple$"):
        world_from_dict({"start": [0, 0, 0], "goal": [1, 1], "obstacles": ()})


@pytest.fixture
def in_tmp(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_load_world_missing_file(in_tmp: Path) -> None:
    message = "world.json: cannot read the world file: No such file or directory"
    with pytest.raises(WorldError, match=f"^{re.escape(message)}$"):
        load_world("world.json")


def test_load_world_directory(in_tmp: Path) -> None:
    (in_tmp / "world.json").mkdir()
    message = r"^world\.json: cannot read the world file: Is a directory$"
    with pytest.raises(WorldError, match=message):
        load_world(Path("world.json"))


def test_load_world_not_utf8(in_tmp: Path) -> None:
    (in_tmp / "world.json").write_bytes(b'{"name": "\xff"}')
    message = "world.json: not UTF-8 text (byte 10: invalid start byte)"
    with pytest.raises(WorldError, match=f"^{re.escape(message)}$"):
        load_world("world.json")


def test_load_world_reports_the_path_in_json_errors(in_tmp: Path) -> None:
    (in_tmp / "world.json").write_text('{"start": [0, 0, 0], "goal": [1]}', encoding="utf-8")
    with pytest.raises(WorldError, match=r"^world\.json: goal: must be a sequence of 2 numbers"):
        load_world("world.json")


def test_save_world_unwritable(in_tmp: Path) -> None:
    world = World(start=(0.0, 0.0, 0.0), goal=(1.0, 1.0))
    message = "missing/world.json: cannot write the world file: No such file or directory"
    with pytest.raises(WorldError, match=f"^{re.escape(message)}$"):
        save_world(world, "missing/world.json")


def _documented_messages() -> set[str]:
    """Every example message in the docs' validation table (cells quoted with ` or ``)."""
    found: set[str] = set()
    for line in DOC.read_text(encoding="utf-8").splitlines():
        if line.startswith("|"):
            quoted = re.findall(r"``(world\.json: .*?)``|`(world\.json: [^`]*)`", line)
            found.update(double or single for double, single in quoted)
    return found


def test_documented_messages_are_the_real_ones() -> None:
    """Each message the docs show is produced, word for word, by a case above."""
    tested = {"world.json: " + message for _, _, message in CASES}
    tested.add("world.json: cannot read the world file: No such file or directory")
    documented = _documented_messages()
    assert len(documented) >= 20, documented
    assert documented - tested == set()


def test_loaded_numbers_are_floats() -> None:
    world = loads_world(
        '{"start": [0, 0, 0], "goal": [1, 1],'
        ' "obstacles": [{"circle": {"center": [5, 5], "radius": 1}}]}'
    )
    assert all(type(v) is float for v in (*world.start, *world.goal))
    pillar = world.obstacles[0]
    assert isinstance(pillar, Circle) and type(pillar.radius) is float
