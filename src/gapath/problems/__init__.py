"""pymoo problems over grid paths."""

from gapath.problems.free_path import FreePathProblem, path_problem
from gapath.problems.grid_path import GenomeWarning, GridPathProblem

__all__ = ["FreePathProblem", "GenomeWarning", "GridPathProblem", "path_problem"]
