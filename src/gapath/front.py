"""Turning a population into the front a user sees.

Ahmed & Deb's post-processing: keep the feasible, non-dominated individuals and,
among those that share an objective vector (SPEC's tolerance), the smoothest
path.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from gapath.metrics import dedupe, nondominated
from gapath.objectives import INTERFERING, OBJECTIVES, SMOOTHNESS


@dataclass(frozen=True, eq=False)
class PathFront:
    """A set of mutually non-dominated feasible paths.

    Attributes
    ----------
    objectives : names of the objective columns of ``F``.
    F : (k, m) unpenalised objective values, sorted lexicographically.
    metrics : (k, 4) all metrics (:data:`gapath.objectives.OBJECTIVES`).
    X : (k, n_var) genomes (empty when the paths do not come from a GA).
    paths : k arrays of (row, col) workspace cells.
    """

    objectives: tuple[str, ...]
    F: np.ndarray
    metrics: np.ndarray
    X: np.ndarray
    paths: list = field(repr=False)

    def __len__(self) -> int:
        return len(self.F)

    def records(self) -> list[dict]:
        """``[{"objectives": {name: value}, "path": [[r, c], ...]}]`` (plus the
        other metrics under ``"metrics"``)."""
        out = []
        for f, m, p in zip(self.F, self.metrics, self.paths):
            out.append(
                {
                    "objectives": {n: float(v) for n, v in zip(self.objectives, f)},
                    "metrics": {
                        n: (int(v) if n == "interfering" else float(v)) for n, v in zip(OBJECTIVES, m)
                    },
                    "path": np.asarray(p).tolist(),
                }
            )
        return out

    def best(self, name: str) -> int:
        """Index of the path with the smallest value of objective ``name``
        (ties: the first in the front's lexicographic order)."""
        return int(np.argmin(self.F[:, self.objectives.index(name)]))

    def knee(self) -> int:
        """Index of the knee: the point nearest the ideal point once every
        objective is scaled to [0, 1] over the front."""
        lo, hi = self.F.min(axis=0), self.F.max(axis=0)
        span = np.where(hi > lo, hi - lo, 1.0)
        return int(np.argmin(np.linalg.norm((self.F - lo) / span, axis=1)))


def select_front(F: np.ndarray, metrics: np.ndarray) -> np.ndarray:
    """Indices of the feasible (``interfering == 0``), non-dominated rows of
    ``F``, one per objective vector (the smoothest), sorted lexicographically
    by ``F``."""
    feasible = np.flatnonzero(metrics[:, INTERFERING] == 0)
    if len(feasible) == 0:
        return feasible
    nd = feasible[nondominated(F[feasible], tol=1e-9)]
    nd = nd[dedupe(F[nd], prefer=metrics[nd, SMOOTHNESS])]
    return nd[np.lexsort(F[nd].T[::-1])]


def path_front(problem, X) -> PathFront:
    """The front of genomes ``X`` of a :class:`gapath.problems.GridPathProblem`.

    Objectives are recomputed unpenalised from the decoded paths.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import default_workspace
    >>> from gapath.problems import GridPathProblem
    >>> p = GridPathProblem(default_workspace())
    >>> front = path_front(p, np.zeros((3, p.n_var), int))
    >>> len(front) <= 1
    True
    """
    X = np.atleast_2d(np.asarray(X))
    metrics = problem.metrics(X)
    F = problem.objective_values(metrics)
    keep = select_front(F, metrics)
    X = X[keep]
    return PathFront(problem.objectives, F[keep], metrics[keep], X, problem.decode(X) if len(X) else [])
