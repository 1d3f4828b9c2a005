"""Graph-search planners: A*, D* Lite, the costmap planners of Lavin (A*-PO,
D*-PO and their weighted-sum baselines), hybrid A* and RRT(*) for a car, and
exact multi-objective fronts.

:func:`plan` plans one path with any of them by name (:data:`PLANNERS`) and
returns a :class:`PlanOutcome`.
"""

from gapath.planners.astar import PlanResult, astar
from gapath.planners.dstar_lite import DStarLite
from gapath.planners.exact import ExactFront, exact_path_front, free_front, monotone_front
from gapath.planners.pareto import (
    DStarPO,
    ParetoPlanResult,
    WeightedSumDStar,
    astar_po,
    weighted_sum_astar,
)
from gapath.planners.registry import (
    PLANNERS,
    CarSettings,
    PlannerInfo,
    PlanOutcome,
    plan,
    planner_info,
    planner_names,
)

__all__ = [
    "PLANNERS",
    "CarSettings",
    "DStarLite",
    "DStarPO",
    "ExactFront",
    "ParetoPlanResult",
    "PlanOutcome",
    "PlanResult",
    "PlannerInfo",
    "WeightedSumDStar",
    "astar",
    "astar_po",
    "exact_path_front",
    "free_front",
    "monotone_front",
    "plan",
    "planner_info",
    "planner_names",
    "weighted_sum_astar",
]
