"""BARN's worlds, task and score under the benchmark's import path.

They live in :mod:`ifgm_ref.barn`, below both the benchmark and the oracle (whose reference
conformance replays BARN samples: :mod:`ifgm_ref.oracle.checks`); this module keeps the path
that scripts written against ``ifgm_ref.bench.barn`` import from.
"""

from ifgm_ref.barn import (
    BUNDLED,
    CELL,
    CYLINDER_RADIUS,
    DEFAULT_SENSOR,
    GOAL,
    OPTIMAL_SPEED,
    ROBOT,
    SIM,
    START,
    BarnFiles,
    GazeboTask,
    barn_score,
    barn_sensor,
    bundled_barn_folder,
    cell_to_world,
    find_barn_worlds,
    gazebo_task,
    load_barn_world,
    parse_selection,
    reference_length,
)

__all__ = [
    "BUNDLED",
    "CELL",
    "CYLINDER_RADIUS",
    "DEFAULT_SENSOR",
    "GOAL",
    "OPTIMAL_SPEED",
    "ROBOT",
    "SIM",
    "START",
    "BarnFiles",
    "GazeboTask",
    "barn_score",
    "barn_sensor",
    "bundled_barn_folder",
    "cell_to_world",
    "find_barn_worlds",
    "gazebo_task",
    "load_barn_world",
    "parse_selection",
    "reference_length",
]
