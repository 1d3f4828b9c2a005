"""Seeding a free-path GA population with planner paths."""

from __future__ import annotations

import numpy as np
from pymoo.core.sampling import Sampling

from gapath.errors import ConfigError, NoPathError
from gapath.operators.duplicates import duplicate_mask

#: What :class:`FreeSampling` can seed from.
FREE_SEED_SOURCES = ("weighted", "exact", "none")


def free_seed_genomes(problem, source: str = "weighted", n_weights: int = 17, max_exact: int = 200):
    """Genomes of planner paths in a :class:`~gapath.problems.FreePathProblem`'s encoding.

    * ``"weighted"``: the optimal paths of ``n_weights`` weight genes evenly
      spread over [0, 1] (weighted-sum A* searches of length against the
      decoders' cell cost, see :mod:`gapath.encodings.free`), encoded with
      the weight that produced them: the via points are spread along the
      path and every segment gets the path's weight, so the genome decodes
      to the planner's path up to ties between equal-cost segments; for the
      field encoding a neutral field reproduces it exactly;
    * ``"exact"``: the weighted seeds plus the paths of the exact free front
      (:func:`gapath.planners.exact.free_front`, objectives among length,
      vulnerability and smoothness) when it has at most ``max_exact`` points
      (evenly thinned otherwise), encoded with fitted segment weights;
    * ``"none"``: no genomes.
    """
    if source not in FREE_SEED_SOURCES:
        raise ConfigError(f"unknown seed source {source!r}; expected one of {', '.join(FREE_SEED_SOURCES)}")
    enc = problem.encoding
    if source == "none":
        return np.zeros((0, problem.n_var))
    genes = np.linspace(0.0, 1.0, int(n_weights))
    X = [enc.encode(enc.weighted_paths(genes), weights=genes)]
    if source == "exact":
        from gapath.planners.exact import EXACT_OBJECTIVES, free_front

        names = [n for n in problem.objectives if n in EXACT_OBJECTIVES] or ["length"]
        try:
            front = free_front(problem.workspace, names)
            paths = list(front.paths)
            if len(paths) > max_exact:
                keep = np.unique(np.rint(np.linspace(0, len(paths) - 1, max_exact)).astype(int))
                paths = [paths[i] for i in keep]
            X.insert(0, enc.encode(paths))
        except NoPathError:
            pass
    return np.concatenate(X)


class FreeSampling(Sampling):
    """Initial population of a free-path problem: planner paths, then random
    genomes, all decoding to distinct paths (fewer than asked when 100
    rounds of random genomes find no more distinct paths: a tiny map).

    Parameters
    ----------
    source : ``"weighted"`` (default), ``"exact"`` or ``"none"`` (see
        :func:`free_seed_genomes`).
    n_weights : number of weighted-sum seeds.
    max_share : largest share of the population taken by seeds.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import default_workspace
    >>> from gapath.problems import FreePathProblem
    >>> p = FreePathProblem(default_workspace())
    >>> X = FreeSampling()._do(p, 30, random_state=np.random.default_rng(1))
    >>> X.shape == (30, p.n_var)
    True
    """

    def __init__(self, source: str = "weighted", n_weights: int = 17, max_share: float = 0.5):
        super().__init__()
        if source not in FREE_SEED_SOURCES:
            raise ConfigError(
                f"unknown seed source {source!r}; expected one of {', '.join(FREE_SEED_SOURCES)}"
            )
        self.source = source
        self.n_weights = n_weights
        self.max_share = max_share

    def _do(self, problem, n_samples, random_state=None, **kwargs):
        if random_state is None:
            random_state = np.random.default_rng()
        X = free_seed_genomes(problem, self.source, self.n_weights)
        if len(X):
            X = X[~duplicate_mask(problem.path_keys(X))]
            X = X[: max(1, int(self.max_share * n_samples))]
        for _ in range(100):
            missing = n_samples - len(X)
            if missing <= 0:
                break
            # random genomes rarely decode to the same path: draw a few more
            # than needed (each one is decoded), not twice as many
            R = random_state.random((max(missing + missing // 8 + 1, 50), problem.n_var))
            keys = problem.path_keys(R)
            R = R[~duplicate_mask(keys, problem.path_keys(X) if len(X) else None) & ~duplicate_mask(keys)][
                :missing
            ]
            X = np.concatenate([X, R])
        return X


__all__ = ["FREE_SEED_SOURCES", "FreeSampling", "free_seed_genomes"]
