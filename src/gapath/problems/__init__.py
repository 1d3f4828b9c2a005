"""pymoo problems over grid paths."""

from gapath.problems.grid_path import GridPathProblem

__all__ = ["GridPathProblem"]
