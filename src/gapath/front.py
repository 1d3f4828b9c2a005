"""Turning a population into the front a user sees.

Ahmed & Deb's post-processing: keep the feasible, non-dominated individuals and,
among those that share an objective vector (SPEC's tolerance), the smoothest
path.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from gapath.metrics import dedupe, nondominated
from gapath.objectives import INTERFERING, OBJECTIVES, SMOOTHNESS

if TYPE_CHECKING:
    from gapath.workspace import Workspace


class PathProblem(Protocol):
    """What :func:`path_front` needs of a problem (a
    :class:`gapath.problems.GridPathProblem` or ``FreePathProblem``; typed
    structurally, so that this ground-floor module does not import the
    problems above it)."""

    objectives: Sequence[str]

    def metrics(self, X: Any) -> np.ndarray: ...

    def objective_values(self, metrics: np.ndarray) -> np.ndarray: ...

    def decode(self, X: Any) -> list: ...


#: The paths :meth:`PathFront.marked` picks: label -> objective it minimises
#: (the knee is picked among all objectives).
MARKED = (("shortest", "length"), ("safest", "vulnerability"))


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
    paths: list[np.ndarray] = field(repr=False)

    @classmethod
    def from_paths(
        cls,
        workspace: Workspace,
        paths: Sequence[Any],
        objectives: Sequence[str],
        F: np.ndarray | None = None,
    ) -> PathFront:
        """A front of given paths (e.g. a planner's), their metrics
        computed on ``workspace``.

        Parameters
        ----------
        workspace : Workspace
            The grid the paths are on (obstacles, potential, cell size,
            corner rule).
        paths : sequence of (m_i, 2) int arrays
            Cells ``(row, col)``, start to goal; kept in the given order (no
            filtering: the caller knows they are mutually non-dominated).
        objectives : sequence of str
            Names of the columns of ``F``.
        F : (k, m) float array, optional
            The paths' objective values (e.g. an exact front's, or a
            costmap planner's layer objectives); default the ``objectives``
            columns of the metrics (:data:`gapath.objectives.OBJECTIVES`
            names only).

        Returns
        -------
        PathFront
            With no genomes (``X`` of shape ``(k, 0)``).

        Raises
        ------
        ConfigError
            Without ``F``, on an objective that is not a metric.

        Examples
        --------
        >>> from gapath import Workspace
        >>> ws = Workspace(np.zeros((2, 3), bool))
        >>> front = PathFront.from_paths(ws, [np.array([[1, 0], [1, 1], [0, 2]])], ["length"])
        >>> front.F.round(4).tolist(), front.marked()
        ([[2.4142]], {'shortest': 0, 'knee': 0})
        """
        from gapath.objectives import evaluate_paths, objective_index, pad_paths

        paths = [np.asarray(p, dtype=np.int64).reshape(-1, 2) for p in paths]
        names = tuple(objectives)
        if paths:
            P, L = pad_paths(paths)
            metrics = evaluate_paths(
                P, L, workspace.occ, workspace.potential, workspace.cell_size, workspace.corner_cutting
            )
        else:
            metrics = np.empty((0, len(OBJECTIVES)))
        if F is None:
            F = metrics[:, objective_index(list(names))]
        F = np.asarray(F, dtype=float).reshape(len(paths), len(names))
        return cls(names, F, metrics, np.empty((len(paths), 0)), paths)

    def __len__(self) -> int:
        return len(self.F)

    def marked(self) -> dict[str, int]:
        """Indices of the shortest, the safest (least vulnerable) and the
        knee path (see :meth:`knee`), as ``summary.json``'s ``marked`` entry
        and the plots show them; objectives not in the front are left out,
        an empty front has none.

        Returns
        -------
        dict of str to int
            ``{"shortest": i, "safest": j, "knee": k}`` (those that apply).
        """
        marks: dict[str, int] = {}
        if len(self) == 0:
            return marks
        for label, name in MARKED:
            if name in self.objectives:
                marks[label] = self.best(name)
        marks["knee"] = self.knee()
        return marks

    def records(self) -> list[dict[str, Any]]:
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


def path_front(problem: PathProblem, X: Any) -> PathFront:
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
    return PathFront(
        tuple(problem.objectives), F[keep], metrics[keep], X, problem.decode(X) if len(X) else []
    )
