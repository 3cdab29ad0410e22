"""ifgm-ref: the executable reference specification of IFGM and IBA.

The paper: "An Improved Algorithm for Collision Avoidance in Environments Having U and H
Shaped Obstacles" (Intelligent Follow the Gap Method, IFGM, and Intelligent Bug Algorithm,
IBA). The package's folders are its layers, bottom up (docs/architecture.md); a module imports
from its own folder and the folders below it only (``tests/test_layers.py``):

- :mod:`ifgm_ref.core`: the foundations every layer uses (errors, validation, poses, the
  planner's protocol, parameters, formulas, the paper's element index);
- :mod:`ifgm_ref.paper`: the paper itself (equations (1)-(4), Figure 3, the percepts);
- :mod:`ifgm_ref.planners` and :mod:`ifgm_ref.sim`, side by side: the planners, which never
  see the map, and the simulated world that does;
- :mod:`ifgm_ref.io`: worlds, bags and programs from and to the outside (world files, Gazebo
  and BARN, ROS bags, the JSON-lines transport, ROS nodes);
- :mod:`ifgm_ref.oracle`: the properties that check an implementation;
- :mod:`ifgm_ref.apps`: the command line, the benchmark, the paper's figures.
"""

from ifgm_ref.core.moved import install_moved_names

__version__ = "0.1.0"

install_moved_names()
