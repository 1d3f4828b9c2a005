"""Duplicate elimination by decoded path (SPEC: duplicates and ties)."""

from __future__ import annotations

import numpy as np
from pymoo.core.duplicate import DuplicateElimination

from gapath.operators.columns import ColumnCache, column


def _row_keys(A: np.ndarray) -> np.ndarray:
    A = np.ascontiguousarray(A)
    return A.view(np.dtype((np.void, A.dtype.itemsize * A.shape[1]))).ravel()


def duplicate_mask(keys: np.ndarray, other: np.ndarray | None = None) -> np.ndarray:
    """Boolean mask of the rows of ``keys`` that repeat an earlier row, or,
    when ``other`` is given, a row of ``other``. Sorting, O(N log N).

    Empty ``keys`` give an empty mask; an empty ``other`` is the same as none.
    """
    n = len(keys)
    if n == 0:
        return np.zeros(0, dtype=bool)
    if other is not None and len(other) == 0:
        other = None
    both = keys if other is None else np.concatenate([other, keys])
    _, inverse = np.unique(_row_keys(both), return_inverse=True)
    first = np.full(inverse.max() + 1, len(both))
    np.minimum.at(first, inverse, np.arange(len(both)))
    if other is None:
        return first[inverse] != np.arange(n)
    return first[inverse[len(other) :]] < len(other)


class PathDuplicateElimination(DuplicateElimination):
    """Two individuals are duplicates when they decode to the same path.

    Many genomes decode to the same path; eliminating only gene-equal
    members lets a population collapse onto a handful of paths. This
    elimination compares the decoded column profiles, by sorting (no O(N^2)
    distance matrix). Without a gapath problem bound to it (see
    :meth:`bind`), it compares the genes.

    Examples
    --------
    >>> import numpy as np
    >>> duplicate_mask(np.array([[1, 2], [1, 2], [3, 4]])).tolist()
    [False, True, False]
    """

    def __init__(self, problem=None):
        super().__init__()
        self.problem = problem
        self._cache = ColumnCache()

    def bind(self, problem) -> PathDuplicateElimination:
        """Use ``problem.encoding`` to decode genomes into paths."""
        self.problem = problem if hasattr(problem, "encoding") else None
        self._cache = ColumnCache()
        return self

    def keys(self, pop) -> np.ndarray:
        X = column(pop, "X")
        if self.problem is None:
            return np.asarray(X)
        if hasattr(self.problem, "path_keys"):  # free paths: identity rows
            return self.problem.path_keys(X)
        entries, exits = self.problem.encoding.decode(X)
        return np.concatenate([entries, exits], axis=1)

    def _do(self, pop, other, is_duplicate):
        other_keys = None if other is None else self._cache.get(other, self.keys)
        mask = duplicate_mask(self.keys(pop), other_keys)
        return is_duplicate | mask
