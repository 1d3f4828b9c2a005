"""Configured pymoo algorithms for grid path problems."""

from gapath.algorithms.fast_nsga2 import FastNSGA2
from gapath.algorithms.paper import PathNSGA2, paper_nsga2

__all__ = ["FastNSGA2", "PathNSGA2", "paper_nsga2"]
