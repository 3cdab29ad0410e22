"""IFGM, the paper's Intelligent Follow the Gap Method (section 4, Figure 3): its parameters
and per-step atoms (:mod:`.atoms`), their decision margins (:mod:`.margins`), the readings of
the paper's open choices (:mod:`.readings`) and the planner (:mod:`.planner`).

``ifgm_ref.planners.ifgm:IFGMPlanner`` names the planner, as before the folder existed.
"""

from ifgm_ref.planners.ifgm.atoms import IFGMParams as IFGMParams
from ifgm_ref.planners.ifgm.planner import IFGMPlanner as IFGMPlanner
