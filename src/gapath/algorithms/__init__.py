"""Configured pymoo algorithms for grid path problems."""

from gapath.algorithms.paper import PathNSGA2, paper_nsga2

__all__ = ["PathNSGA2", "paper_nsga2"]
