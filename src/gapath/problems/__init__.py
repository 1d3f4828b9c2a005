"""pymoo problems over grid paths."""

from gapath.problems.grid_path import GridPathProblem
from gapath.problems.free_path import FreePathProblem, path_problem

__all__ = ["FreePathProblem", "GridPathProblem", "path_problem"]
