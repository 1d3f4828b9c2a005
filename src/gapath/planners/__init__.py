"""Graph-search planners: A*, D* Lite and exact multi-objective fronts."""

from gapath.planners.astar import PlanResult, astar
from gapath.planners.dstar_lite import DStarLite
from gapath.planners.exact import ExactFront, monotone_front

__all__ = ["DStarLite", "ExactFront", "PlanResult", "astar", "monotone_front"]
