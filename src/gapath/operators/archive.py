"""An external archive of free paths, refined by segment re-routing.

A free-path GA keeps its population at ``pop_size`` paths, and its survival
drops non-dominated paths by crowding once the first front is larger than
that (three objectives on random maps: exact fronts of 300-600 points).
:class:`FreePathArchive` is a pymoo callback that keeps, beside the run,
every feasible non-dominated path it has seen (the offspring of every
generation, the initial population included), and each generation *refines*
it: ``n_refine`` archived paths, picked at random, each have one segment
(a random stretch of the path) replaced by the optimal path between the
segment's ends under a random weighting of length against the cell cost
(:meth:`gapath.encodings.free.FreeEncoding.reroute`, one numba kernel for
the whole batch). A Pareto-optimal path of additive objectives is made of
sub-paths that are Pareto optimal between their ends, so splicing
weighted-sum sub-paths into front paths reaches front points that no
weighting of the whole path reaches (the non-supported points).

Re-routed paths have no genome: they stay in the archive and are not fed
back to the population. :func:`gapath.solver.solve` returns the archive's
front (``PathFront.X`` is then empty) for free paths.
"""

from __future__ import annotations

import numpy as np
from pymoo.core.callback import Callback

from gapath.errors import ConfigError
from gapath.front import PathFront, select_front
from gapath.objectives import INTERFERING

#: Default range of ``log10`` of the re-routing searches' cell-cost weight.
LAM_RANGE = (-3.0, 12.0)


class FreePathArchive(Callback):
    """Every feasible non-dominated free path seen in a run, refined each
    generation by re-routing segments (see the module docstring).

    Parameters
    ----------
    problem : :class:`gapath.problems.FreePathProblem`.
    n_refine : re-routed paths per generation (0: a plain archive).
    seed : seed of the archive's own random numbers (the GA's are untouched,
        so the population evolves as without the archive).
    segment : ``(lo, hi)``, the share of a path's cells a re-routed segment
        spans, drawn uniformly.
    lam_range : ``(lo, hi)``, the range of ``log10`` of the cell-cost weight
        of the re-routing searches (see :mod:`gapath.encodings.free`), drawn
        log-uniformly; wider than the genomes' by default: the last points
        of the safe end of a front trade a step for a potential of 1e-9
        (MovingAI den312d).

    Attributes
    ----------
    n_eval : paths evaluated by the archive (re-routed ones).

    Raises
    ------
    ConfigError
        On a problem that is not a free-path problem, a negative
        ``n_refine`` or a bad ``segment``.

    Examples
    --------
    >>> from pymoo.optimize import minimize
    >>> from gapath import default_workspace
    >>> from gapath.algorithms import FastNSGA2
    >>> from gapath.problems import FreePathProblem
    >>> p = FreePathProblem(default_workspace())
    >>> archive = FreePathArchive(p, n_refine=10)
    >>> _ = minimize(p, FastNSGA2(20), ("n_gen", 3), seed=1, callback=archive)
    >>> front = archive.front()
    >>> len(front) > 0 and front.X.shape == (len(front), 0) or front.X.shape[1] == p.n_var
    True
    """

    def __init__(
        self,
        problem,
        n_refine: int = 100,
        seed: int = 1,
        segment=(0.05, 0.5),
        lam_range=LAM_RANGE,
        shortcut=None,
    ):
        super().__init__()
        if getattr(problem, "paths", None) != "free":
            raise ConfigError(f"FreePathArchive needs a FreePathProblem, got {type(problem).__name__}")
        try:
            n_refine = int(n_refine)
        except (TypeError, ValueError):
            raise ConfigError(f"n_refine must be an integer >= 0, got {n_refine!r}") from None
        if n_refine < 0:
            raise ConfigError(f"n_refine must be an integer >= 0, got {n_refine!r}")
        try:
            lo, hi = (float(v) for v in segment)
        except (TypeError, ValueError):
            raise ConfigError(f"segment must be two shares (lo, hi), got {segment!r}") from None
        if not 0.0 <= lo <= hi <= 1.0:
            raise ConfigError(f"segment must be two shares 0 <= lo <= hi <= 1, got {segment!r}")
        self.problem = problem
        self.n_refine = n_refine
        self.segment = (lo, hi)
        try:
            lam_lo, lam_hi = (float(v) for v in lam_range)
        except (TypeError, ValueError):
            raise ConfigError(f"lam_range must be two numbers (lo, hi), got {lam_range!r}") from None
        if not (np.isfinite(lam_lo) and np.isfinite(lam_hi) and lam_lo < lam_hi):
            raise ConfigError(f"lam_range must be two finite numbers lo < hi, got {lam_range!r}")
        self.lam_range = (lam_lo, lam_hi)
        #: with smoothness as an objective the re-routing searches weigh turns
        self.turns = "smoothness" in problem.objectives
        if shortcut is None:
            shortcut = 0.25 if self.turns else 0.0
        try:
            shortcut = float(shortcut)
        except (TypeError, ValueError):
            raise ConfigError(f"shortcut must be a share in [0, 1], got {shortcut!r}") from None
        if not 0.0 <= shortcut <= 1.0:
            raise ConfigError(f"shortcut must be a share in [0, 1], got {shortcut!r}")
        self.shortcut = shortcut
        self.rng = np.random.default_rng(seed)
        self.n_eval = 0
        enc = problem.encoding
        self._flat = np.zeros(0, np.int64)
        self._offsets = np.zeros(1, np.int64)
        self._keys = np.zeros((0, 3), np.int64)
        self._M = np.zeros((0, 0))
        self._X = np.zeros((0, enc.n_var))
        self._genome = np.zeros(0, bool)

    def __len__(self) -> int:
        return len(self._keys)

    @property
    def F(self) -> np.ndarray:
        """Unpenalised objectives of the archived paths."""
        if len(self) == 0:
            return np.zeros((0, self.problem.n_obj))
        return self.problem.objective_values(self._M)

    # -- the generation hook ---------------------------------------------------
    def notify(self, algorithm):
        off = algorithm.off
        X = np.zeros((0, self.problem.n_var)) if off is None or len(off) == 0 else off.get("X")
        self.add(np.asarray(X, dtype=float))
        if self.n_refine and len(self):
            self.refine(self.n_refine)

    def add(self, X) -> None:
        """Archive the decoded paths of genomes ``X`` (those non-dominated)."""
        if len(X) == 0:
            return
        enc = self.problem.encoding
        flat, offsets, keys = enc.decode_flat(X)
        self._merge(flat, offsets, keys, X, np.ones(len(X), bool))

    def refine(self, n: int) -> None:
        """Change one random segment of ``n`` randomly picked archived paths
        and archive the results: a share ``shortcut`` of them straightened
        (:meth:`~gapath.encodings.free.FreeEncoding.shortcut`), the others
        re-routed under a random weight gene
        (:meth:`~gapath.encodings.free.FreeEncoding.reroute`)."""
        rng = self.rng
        enc = self.problem.encoding
        pick = rng.integers(0, len(self), n)
        m = np.diff(self._offsets)[pick]
        lo, hi = self.segment
        span = np.maximum(2, np.rint(rng.uniform(lo, hi, n) * (m - 1))).astype(np.int64)
        span = np.minimum(span, m - 1)
        i0 = np.floor(rng.random(n) * (m - span)).astype(np.int64)
        genes = rng.random(n)
        n_short = int(round(self.shortcut * n))
        parts = []
        if n_short:
            s = slice(0, n_short)
            parts.append(
                enc.shortcut(self._flat, self._offsets, pick[s], i0[s], i0[s] + span[s], genes[s] < 0.5)
            )
        if n_short < n:
            s = slice(n_short, n)
            turns = rng.random(n - n_short) if self.turns else None
            parts.append(
                enc.reroute(
                    self._flat,
                    self._offsets,
                    pick[s],
                    i0[s],
                    i0[s] + span[s],
                    genes[s],
                    self.lam_range,
                    turns,
                )
            )
        flat, offsets, keys = parts[0]
        for f2, o2, k2 in parts[1:]:
            flat, offsets = enc.concat_flat(flat, offsets, f2, o2)
            keys = np.concatenate([keys, k2])
        self.n_eval += n
        self._merge(flat, offsets, keys, np.full((n, self._X.shape[1]), np.nan), np.zeros(n, bool))

    def _merge(self, flat, offsets, keys, X, genome) -> None:
        enc = self.problem.encoding
        P, L = enc.padded(flat, offsets)
        M = self.problem.path_metrics(P, L)
        ok = M[:, INTERFERING] == 0
        if len(self):
            flat, offsets = enc.concat_flat(self._flat, self._offsets, flat, offsets)
            keys = np.concatenate([self._keys, keys])
            M = np.concatenate([self._M, M])
            X = np.concatenate([self._X, X])
            genome = np.concatenate([self._genome, genome])
            ok = np.concatenate([np.ones(len(self), bool), ok])
        # one row per path (the archived copy first), then the front
        _, first = np.unique(keys, axis=0, return_index=True)
        rows = np.sort(first)
        rows = rows[ok[rows]]
        F = self.problem.objective_values(M[rows])
        keep = rows[select_front(F, M[rows])]
        self._flat, self._offsets = enc.take_flat(flat, offsets, keep)
        self._keys, self._M, self._X, self._genome = keys[keep], M[keep], X[keep], genome[keep]

    # -- the result --------------------------------------------------------------
    def paths(self) -> list[np.ndarray]:
        """The archived paths (``(m_i, 2)`` workspace cells)."""
        P, L = self.problem.encoding.padded(self._flat, self._offsets)
        return [P[i, : L[i]].copy() for i in range(len(L))]

    def front(self) -> PathFront:
        """The archive as a :class:`gapath.front.PathFront` (lexicographic
        order); its ``X`` holds the genomes when every archived path has
        one, else it is empty (``(k, 0)``)."""
        X = self._X if self._genome.all() else np.empty((len(self), 0))
        return PathFront(tuple(self.problem.objectives), self.F, self._M, X, self.paths())


def run_archive(algorithm) -> FreePathArchive | None:
    """The :class:`FreePathArchive` among the callbacks of ``algorithm``
    (as :func:`gapath.solver.solve` installs it), or None.

    Examples
    --------
    >>> from gapath import default_workspace
    >>> from gapath.solver import solve
    >>> r = solve(default_workspace(), paths="free", pop_size=10, n_gen=2)
    >>> len(run_archive(r.pymoo_result.algorithm)) == len(r.front)
    True
    """
    cb = getattr(algorithm, "callback", None)
    for c in (cb, *getattr(cb, "callbacks", ())):
        if isinstance(c, FreePathArchive):
            return c
    return None


__all__ = ["LAM_RANGE", "FreePathArchive", "run_archive"]
