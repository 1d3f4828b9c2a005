"""An external archive of column-monotone paths, refined by re-routing a
stretch of columns.

:class:`MonotonePathArchive` is the column-monotone sibling of
:class:`gapath.operators.archive.FreePathArchive`: a pymoo callback that
keeps, beside a GA run over column-monotone paths
(:class:`gapath.problems.GridPathProblem`), every feasible non-dominated
path the run has met (the offspring of every generation, the first
population included), and each generation *refines* it: ``n_refine`` archived paths, picked at
random, are each re-routed from a random column under a random weighting
of length against vulnerability (:meth:`MonotonePathArchive.weights`):
one forward sweep of a dynamic programme over the columns
(:func:`~gapath.operators._monotone_archive_kernels.reroute_sweep`, one
numba kernel for the whole batch, O(rows) per column) gives, for every end
column, the optimal stretch between the path's exit rows at both ends, so
each sweep yields up to one new path per end column. Since a
Pareto-optimal path is made of stretches that are Pareto optimal between
their ends, splicing weighted-sum stretches into front paths reaches the
non-supported points that no weighting of the whole path reaches.

Some non-supported points are reachable that way only through a narrow
window of weights. So each generation ``n_pareto`` more archived paths
(default :data:`N_PARETO`) have a random stretch (up to the whole path)
replaced by **every** Pareto-optimal (length, vulnerability) stretch
between the same ends
(:func:`~gapath.operators._monotone_archive_kernels.pareto_stretches`: a
bi-objective label programme over the stretch's columns, at most
:data:`PARETO_CAP` labels per exit row, one numba kernel for the batch).

Every re-routed path is again a path of the encodings' path set (the
relative moves of :mod:`gapath.encodings`), so it has a genome: the archive
returns a full :class:`gapath.front.PathFront` (``X`` included). The
population is left alone (the archive draws from its own generator), so a
run evolves exactly as without it and the archive's front weakly
dominates the last population's.
"""

from __future__ import annotations

import numpy as np

from gapath.errors import ConfigError
from gapath.front import select_front
from gapath.monotone import expand_profiles, split_paths
from gapath.objectives import INTERFERING, LENGTH, VULNERABILITY
from gapath.operators._monotone_archive_kernels import entries_of, pareto_stretches, reroute_sweep
from gapath.operators.archive import PathArchive

#: Default range of ``log10`` of the re-routing weight of vulnerability
#: against length, around the ratio of the archive's spans.
WEIGHT_RANGE = (-4.0, 8.0)
#: Default range of the share of a path's columns a re-routed stretch spans.
SEGMENT = (0.05, 1.0)
#: Default range of the number of columns a Pareto stretch spans (its
#: first and last columns kept, the start cell counting as one), see
#: :meth:`MonotonePathArchive.pareto`; a larger ``hi`` than the path is
#: the whole path.
PARETO_SPAN = (3, 10**6)
#: Default Pareto stretches per generation (``n_pareto=None`` with
#: ``n_refine > 0``; docs/results/monotone_lift.md, "Pareto stretches").
N_PARETO = 2
#: Default cap on the non-dominated partial stretches kept per exit row.
PARETO_CAP = 32


def default_refine(pop_size: int) -> int:
    """Re-routed paths per generation that ``solve(..., refine=True)`` (and
    ``gapath solve --paths monotone``) use with a population of
    ``pop_size`` (docs/results/monotone_lift.md).

    Examples
    --------
    On the tuning maps of docs/results/monotone_lift.md, 100 and 250
    re-routed paths per generation at pop 500 found every exact point in
    all 50 runs; the cheaper one was kept.

    >>> default_refine(500)
    100
    """
    return max(1, int(pop_size) // 5)


def _pair(value, name, lo_bound=None, hi_bound=None):
    try:
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ConfigError(f"{name} must be two numbers (lo, hi), got {value!r}") from None
    ok = np.isfinite(lo) and np.isfinite(hi) and lo <= hi
    if lo_bound is not None:
        ok = ok and lo_bound <= lo and hi <= hi_bound
    if not ok:
        bounds = "" if lo_bound is None else f" in [{lo_bound:g}, {hi_bound:g}]"
        raise ConfigError(f"{name} must be two finite numbers lo <= hi{bounds}, got {value!r}")
    return lo, hi


class MonotonePathArchive(PathArchive):
    """Every feasible non-dominated column-monotone path of a run, refined
    each generation by re-routing stretches of columns (see the module
    docstring).

    Parameters
    ----------
    problem : :class:`gapath.problems.GridPathProblem`.
    n_refine : re-routed paths per generation (0: a plain archive).
    seed : seed of the archive's own random numbers.
    segment : ``(lo, hi)``, the share of the path's columns a stretch
        spans, drawn uniformly (at least two columns); default
        :data:`SEGMENT`.
    weight_range : ``(lo, hi)``, default :data:`WEIGHT_RANGE`: the range of ``log10`` of the weight of
        vulnerability against length in the re-routing, drawn uniformly,
        relative to the ratio of the archive's length and vulnerability
        spans (so 0 weighs both normalised objectives alike).

    n_pareto : Pareto stretches per generation (0: none; default
        :data:`N_PARETO`, 0 if ``n_refine`` is 0):
        each replaces a stretch of an archived path by every
        Pareto-optimal stretch between the same ends
        (:meth:`pareto`).
    pareto_span : ``(lo, hi)`` columns a Pareto stretch spans, default
        :data:`PARETO_SPAN`.
    pareto_cap : non-dominated partial stretches kept per exit row,
        default :data:`PARETO_CAP`.

    Attributes
    ----------
    n_eval : paths evaluated by the archive (the re-routed ones that differ
        from their source path).

    Raises
    ------
    ConfigError
        On a problem that is not a column-monotone path problem, a negative
        ``n_refine``, a bad ``segment`` or ``weight_range``.

    Examples
    --------
    >>> from pymoo.optimize import minimize
    >>> from gapath import default_workspace
    >>> from gapath.algorithms import FastNSGA2
    >>> from gapath.operators import PlannerSampling
    >>> from gapath.problems import GridPathProblem
    >>> p = GridPathProblem(default_workspace())
    >>> archive = MonotonePathArchive(p, n_refine=20)
    >>> algorithm = FastNSGA2(20, sampling=PlannerSampling())
    >>> _ = minimize(p, algorithm, ("n_gen", 3), seed=1, callback=archive)
    >>> front = archive.front()
    >>> len(front) > 0 and front.X.shape == (len(front), p.n_var), archive.n_eval > 0
    (True, True)
    """

    def __init__(
        self,
        problem,
        n_refine: int = 100,
        seed: int = 1,
        segment=None,
        weight_range=None,
        n_pareto: int | None = None,
        pareto_span=None,
        pareto_cap: int | None = None,
    ):
        super().__init__()
        frame = getattr(problem, "frame", None)
        if getattr(problem, "paths", "monotone") != "monotone" or frame is None:
            raise ConfigError(f"MonotonePathArchive needs a GridPathProblem, got {type(problem).__name__}")
        try:
            n_refine = int(n_refine)
        except (TypeError, ValueError):
            raise ConfigError(f"n_refine must be an integer >= 0, got {n_refine!r}") from None
        if n_refine < 0:
            raise ConfigError(f"n_refine must be an integer >= 0, got {n_refine!r}")
        try:
            n_pareto = (N_PARETO if n_refine else 0) if n_pareto is None else int(n_pareto)
            pareto_cap = PARETO_CAP if pareto_cap is None else int(pareto_cap)
        except (TypeError, ValueError):
            raise ConfigError(
                f"n_pareto and pareto_cap must be integers, got {n_pareto!r}, {pareto_cap!r}"
            ) from None
        if n_pareto < 0 or pareto_cap < 1:
            raise ConfigError(f"need n_pareto >= 0 and pareto_cap >= 1, got {n_pareto!r}, {pareto_cap!r}")
        span = _pair(PARETO_SPAN if pareto_span is None else pareto_span, "pareto_span", 2, np.inf)
        self.n_pareto = n_pareto
        self.pareto_span = (int(span[0]), int(min(span[1], frame.n_cols + 1)))
        self.pareto_cap = pareto_cap
        self.problem = problem
        self.frame = frame
        self.n_refine = n_refine
        self.segment = _pair(SEGMENT if segment is None else segment, "segment", 0.0, 1.0)
        self.weight_range = _pair(WEIGHT_RANGE if weight_range is None else weight_range, "weight_range")
        self.rng = np.random.default_rng(seed)
        self.n_eval = 0
        self._exits = np.zeros((0, frame.n_cols), np.int64)
        self._M = np.zeros((0, 4))

    # -- the generation hook ---------------------------------------------------
    def improve(self) -> None:
        """One generation's refinement: :meth:`refine` ``n_refine`` paths,
        then :meth:`pareto` ``n_pareto`` stretches."""
        if self.n_refine:
            self.refine(self.n_refine)
        if self.n_pareto and len(self):
            self.pareto(self.n_pareto)

    def add(self, X) -> None:
        """Archive the decoded paths of genomes ``X`` (those feasible and
        non-dominated)."""
        if len(X) == 0:
            return
        _, exits = self.problem.encoding.decode(X)
        self._merge(np.asarray(exits, np.int64))

    def add_exits(self, exits) -> None:
        """Archive column-monotone paths given by their exit rows (``(N,
        n_cols)`` frame rows, the last one the goal row)."""
        exits = np.atleast_2d(np.asarray(exits, np.int64))
        if exits.shape[1] != self.frame.n_cols:
            raise ConfigError(f"exit rows need {self.frame.n_cols} columns, got {exits.shape[1]}")
        if len(exits):
            self._merge(exits)

    def weights(self, n: int) -> np.ndarray:
        """``n`` random weights of vulnerability against length (length
        weighs 1): half drawn around the trade-offs between neighbouring
        archived points (the weight at which two neighbours tie, times
        ``10 ** U(-0.5, 0.5)``), the others log-uniform over
        :attr:`weight_range` around the ratio of the archive's spans."""
        rng = self.rng
        L, V = self._M[:, LENGTH], self._M[:, VULNERABILITY]
        span_len, span_vul = np.ptp(L) if len(L) > 1 else 0.0, np.ptp(V) if len(V) > 1 else 0.0
        ratio = (span_len if span_len > 0 else 1.0) / (span_vul if span_vul > 0 else 1.0)
        lo, hi = self.weight_range
        w = ratio * 10.0 ** rng.uniform(lo, hi, n)
        order = np.argsort(L, kind="stable")
        dl, dv = np.diff(L[order]), -np.diff(V[order])
        ties = dl[(dl > 0) & (dv > 0)] / dv[(dl > 0) & (dv > 0)]
        local = rng.random(n) < 0.5
        if len(ties) and local.any():
            w[local] = ties[rng.integers(0, len(ties), local.sum())] * 10.0 ** rng.uniform(
                -0.5, 0.5, local.sum()
            )
        return w

    def refine(self, n: int) -> np.ndarray:
        """Re-route ``n`` randomly picked archived paths from a random
        column under random weights (:meth:`weights`), to every end column
        the ``segment`` shares allow (one sweep of the programme per path),
        archive the results and return their exit rows ``(R, n_cols)``."""
        rng, f = self.rng, self.frame
        n_cols = f.n_cols
        pick = rng.integers(0, len(self), n)
        lo = max(2, int(round(self.segment[0] * n_cols)))
        hi = max(lo, int(round(self.segment[1] * n_cols)))
        # stretches k0 .. k1 (k0 = -1: from the start cell), lo <= k1 - k0 <= hi
        k0 = rng.integers(-1, max(0, n_cols - lo), n)
        exits, _ = reroute_sweep(
            self._exits,
            pick,
            k0,
            np.full(n, lo),
            np.full(n, hi),
            np.ones(n),
            self.weights(n),
            *self._grid(),
        )
        return self._keep(exits)

    def pareto(self, n: int) -> np.ndarray:
        """Replace a random stretch of ``n`` randomly picked archived paths
        by every Pareto-optimal (length, vulnerability) stretch between the
        same ends (:func:`~gapath.operators._monotone_archive_kernels.pareto_stretches`,
        one kernel call), archive the results and return their exit rows
        ``(R, n_cols)``. A stretch spans ``pareto_span`` columns, its end
        columns kept (``k0 = -1``: from the start cell)."""
        rng, f = self.rng, self.frame
        n_cols = f.n_cols
        pick = rng.integers(0, len(self), n)
        lo, hi = self.pareto_span
        hi = min(hi, n_cols + 1)
        lo = min(lo, hi)
        width = rng.integers(lo, hi + 1, n) - 1  # k1 - k0
        k0 = np.minimum(rng.integers(-1, n_cols - 1, n), n_cols - 1 - width)
        k1 = k0 + width
        exits, _ = pareto_stretches(
            self._exits,
            pick,
            k0,
            k1,
            *self._grid(),
            self.pareto_cap,
            True,
        )
        return self._keep(exits)

    def _grid(self) -> tuple:
        """The frame's arrays and settings the re-routing kernels take last."""
        f = self.frame
        ws = f.workspace
        return f.occ, f.potential, f.start[0], f.col0, float(ws.cell_size), bool(ws.corner_cutting)

    def _keep(self, exits) -> np.ndarray:
        """Count and archive re-routed paths (exit rows); return them."""
        self.n_eval += len(exits)
        if len(exits):
            self._merge(exits)
        return exits

    def _merge(self, exits) -> None:
        f = self.frame
        entries = entries_of(exits, f.start[0])
        M = self.problem.metrics(np.empty((len(exits), 0)), profiles=(entries, exits))
        ok = M[:, INTERFERING] == 0
        if len(self) and ok.any():
            # drop what an archived path beats in every objective by far more
            # than the tolerance (select_front would drop it too): keeps the
            # front selection below small
            A = self.problem.objective_values(self._M)
            C = self.problem.objective_values(M[ok])
            margin = 1e-6 * np.maximum(np.abs(C), 1.0)
            beaten = (A[None, :, :] < (C - margin)[:, None, :]).all(axis=2).any(axis=1)
            ok[np.flatnonzero(ok)[beaten]] = False
        exits, M = exits[ok], M[ok]
        if len(self):
            exits = np.concatenate([self._exits, exits])
            M = np.concatenate([self._M, M])
        _, first = np.unique(exits, axis=0, return_index=True)
        rows = np.sort(first)
        F = self.problem.objective_values(M[rows])
        keep = rows[select_front(F, M[rows])]
        self._exits, self._M = exits[keep], M[keep]

    # -- the result --------------------------------------------------------------
    def profiles(self) -> tuple[np.ndarray, np.ndarray]:
        """Column profiles ``(entries, exits)`` of the archived paths."""
        return entries_of(self._exits, self.frame.start[0]), self._exits.copy()

    def genomes(self) -> np.ndarray:
        """The archived paths' genomes in the problem's encoding (``(k,
        0)`` if the encoding cannot represent one of them)."""
        try:
            return np.asarray(self.problem.encoding.encode_profiles(*self.profiles()))
        except ConfigError:
            return np.empty((len(self), 0))

    def paths(self) -> list[np.ndarray]:
        """The archived paths (``(m_i, 2)`` workspace cells)."""
        return split_paths(*expand_profiles(self.frame, *self.profiles()))


__all__ = [
    "N_PARETO",
    "PARETO_CAP",
    "PARETO_SPAN",
    "SEGMENT",
    "WEIGHT_RANGE",
    "MonotonePathArchive",
    "default_refine",
]
