"""Graph-search planners: A*, D* Lite, the costmap planners of Lavin (A*-PO,
D*-PO and their weighted-sum baselines) and exact multi-objective fronts."""

from gapath.planners.astar import PlanResult, astar
from gapath.planners.dstar_lite import DStarLite
from gapath.planners.exact import ExactFront, free_front, monotone_front
from gapath.planners.pareto import (
    DStarPO,
    ParetoPlanResult,
    WeightedSumDStar,
    astar_po,
    weighted_sum_astar,
)

__all__ = [
    "DStarLite",
    "DStarPO",
    "ExactFront",
    "ParetoPlanResult",
    "PlanResult",
    "WeightedSumDStar",
    "astar",
    "astar_po",
    "free_front",
    "monotone_front",
    "weighted_sum_astar",
]
