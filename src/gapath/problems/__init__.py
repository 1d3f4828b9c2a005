"""pymoo problems over grid paths."""

from gapath.problems.grid_path import GenomeWarning, GridPathProblem

__all__ = ["GenomeWarning", "GridPathProblem"]
