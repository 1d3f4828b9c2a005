"""Seeding a GA population with planner paths."""

from __future__ import annotations

import numpy as np
from pymoo.core.sampling import Sampling
from pymoo.operators.sampling.rnd import IntegerRandomSampling

from gapath.errors import ConfigError, NoPathError
from gapath.monotone import Frame, expand_profiles, monotone_projection, split_paths
from gapath.operators.duplicates import duplicate_mask
from gapath.planners.astar import astar
from gapath.planners.exact import monotone_front
from gapath.planners.weighted_sum import weighted_sum_paths

#: What :class:`PlannerSampling` can seed from.
SEED_SOURCES = ("weighted", "exact", "astar", "none")


def planner_paths(
    workspace, source: str, objectives=("length", "vulnerability"), n_weights: int = 9
) -> list[np.ndarray]:
    """Seed paths for ``source``:

    * ``"weighted"``: the shortest, the safest and weighted-sum optimal
      column-monotone paths (:func:`gapath.planners.weighted_sum.weighted_sum_paths`);
    * ``"exact"``: every path of the exact monotone front for ``objectives``;
    * ``"astar"``: the A* shortest path and A* paths with the potential
      field as a cost layer (weights 1, 10, 100), each projected onto the
      column-monotone path set (:func:`gapath.monotone.monotone_projection`);
    * ``"none"``: no paths.

    A workspace without a feasible column-monotone path gives no seeds.
    """
    if source not in SEED_SOURCES:
        raise ConfigError(f"unknown seed source {source!r}; expected one of {', '.join(SEED_SOURCES)}")
    try:
        if source == "weighted":
            return weighted_sum_paths(workspace, n_weights)
        if source == "exact":
            return list(monotone_front(workspace, objectives).paths)
        if source == "astar":
            return _astar_paths(workspace)
    except NoPathError:
        pass
    return []


def _astar_paths(workspace) -> list[np.ndarray]:
    frame = Frame.of(workspace)
    paths = []
    for w in (0.0, 1.0, 10.0, 100.0):
        plan = astar(workspace, cost=None if w == 0 else w * workspace.potential)
        entries, exits = monotone_projection(frame, plan.path)
        paths.append(split_paths(*expand_profiles(frame, entries[None], exits[None]))[0])
    return paths


class PlannerSampling(Sampling):
    """Initial population from planner paths, the rest random, all distinct.

    The planner paths are encoded into the problem's encoding (at most
    ``max_share`` of the population); the remaining individuals are drawn
    at random, edge-fixed with pymoo's ``random_state`` and kept only if
    they decode to a path not yet in the population, so duplicate
    elimination never shrinks the population below its size.

    A small map may have fewer distinct paths than the population (a 3x3
    free grid has nine column-monotone paths). The sampler then returns
    every distinct path it found, fewer rows than asked: it stops after
    :attr:`stall_rounds` random rounds in a row that add no new path (or
    100 rounds in all). It never pads with copies, which duplicate
    elimination would drop anyway; both engines run on the smaller
    population.

    Parameters
    ----------
    source : ``"weighted"`` (default), ``"exact"``, ``"astar"`` or ``"none"``
        (see :func:`planner_paths`).
    n_weights : number of weighted-sum paths for ``"weighted"``.
    max_share : largest share of the population taken by planner paths.
    random : the sampling of the random part (default: uniform integers in
        the problem's bounds).

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import default_workspace
    >>> from gapath.problems import GridPathProblem
    >>> p = GridPathProblem(default_workspace())
    >>> X = PlannerSampling()._do(p, 50, random_state=np.random.default_rng(1))
    >>> X.shape
    (50, 31)
    """

    #: Random rounds in a row without a new path after which sampling stops.
    stall_rounds = 10

    def __init__(
        self,
        source: str = "weighted",
        n_weights: int = 9,
        max_share: float = 0.5,
        random: Sampling | None = None,
    ):
        super().__init__()
        if source not in SEED_SOURCES:
            raise ConfigError(f"unknown seed source {source!r}; expected one of {', '.join(SEED_SOURCES)}")
        self.source = source
        self.n_weights = n_weights
        self.max_share = max_share
        self.random = random

    def _random_sampling(self, problem) -> Sampling:
        if self.random is not None:
            return self.random
        try:
            from gapath.operators.defaults import default_operators

            return default_operators(problem.encoding.name)["sampling"]
        except (ImportError, KeyError):
            return IntegerRandomSampling()

    def _do(self, problem, n_samples, random_state=None, **kwargs):
        if random_state is None:
            random_state = np.random.default_rng()
        encoding = problem.encoding
        paths = planner_paths(problem.workspace, self.source, problem.objectives, self.n_weights)
        dtype = np.bool_ if encoding.vtype is bool else np.int64
        X = np.empty((0, problem.n_var), dtype=dtype)
        if paths:
            X = encoding.encode(paths).astype(dtype)
            X = X[: max(1, int(self.max_share * n_samples))]

        def keys(A):
            entries, exits = encoding.decode(A)
            return np.concatenate([entries, exits], axis=1)

        X = X[~duplicate_mask(keys(X))] if len(X) else X
        sampling = self._random_sampling(problem)
        stalled = 0
        for _ in range(100):
            missing = n_samples - len(X)
            if missing <= 0 or stalled >= self.stall_rounds:
                break
            R = sampling._do(problem, 2 * missing, random_state=random_state)
            R = encoding.edge_fix(R, random_state).astype(X.dtype)
            R = R[~duplicate_mask(keys(R), keys(X) if len(X) else None)]
            R = R[~duplicate_mask(keys(R))][:missing]
            stalled = 0 if len(R) else stalled + 1
            X = np.concatenate([X, R])
        return X
