"""An external archive of free paths, refined by segment re-routing.

A free-path GA keeps its population at ``pop_size`` paths, and its survival
drops non-dominated paths by crowding once the first front is larger than
that (three objectives on random maps: exact fronts of 300-600 points).
:class:`FreePathArchive` is a pymoo callback that keeps, beside the run,
every feasible non-dominated path it has seen (the offspring of every
generation, the initial population included), and each generation *refines*
it: ``n_refine`` archived paths (with three or more objectives half of
them picked by crowding distance, favouring the front's sparse regions and
its extremes, the others uniformly) each have one segment (a random
stretch of the path) replaced by the optimal path between the segment's
ends under a weighting of length against the cell cost (random; with two
objectives and ``sparse > 0``, for the paths picked by crowding, between
the trade-offs to the path's neighbours on the front)
(:meth:`gapath.encodings.free.FreeEncoding.reroute`, one numba kernel for
the whole batch). A Pareto-optimal path of additive objectives is made of
sub-paths that are Pareto optimal between their ends, so splicing
weighted-sum sub-paths into front paths reaches front points that no
weighting of the whole path reaches (the non-supported points).

With smoothness as an objective, segments are shorter and many more paths
are re-routed (:data:`SEGMENT_TURNS`, :func:`default_refine`), and, unless
the faces below run, ``extremes`` whole paths per generation are re-routed
under a heavy turn weight (the smooth end of the front).

With three or more objectives the first refinement also archives the exact
*faces* of the front: for each pair of the objectives among length,
vulnerability and smoothness, every path of the exact two-objective front
(:func:`gapath.planners.exact.free_front`), within a budget of expansions
per reachable cell that they share (``faces``; the (length, smoothness)
search first, the cheapest on every map measured, except that the
(length, vulnerability) one goes first when it decides the approximate
search's epsilon, see below). A search that reaches
what is left of the budget stops there and gives the points it has found,
each on the exact front (``free_front(..., max_expansions=)``); the ones
after it do not run. Each such
path is best in its pair and, among the paths tied with it in the pair,
best in the third objective (:func:`gapath.planners.exact.free_front`), so
its objective vector is a point on the boundary of the full front; the
refinement then works inwards from them.

When the objectives are length, vulnerability and smoothness, the faces
are followed by an *approximate* three-objective search
(:func:`gapath.planners.exact.free_front` with ``epsilon=approx``, within a
budget of its own, ``approx_budget`` expansions per reachable cell, and
only when every face search finished): its points lie across the inside
of the front, which the faces bound but do not fill, and it misses the
edges, which the faces hold. Where the (length, vulnerability) face is
coarse for that epsilon (a few points within ``1 + approx`` of each other
cover most of it: ``approx_retry``), the search runs at the finer
``approx_retry_epsilon`` instead; the face is then searched first, and
decides it.

The archive is updated incrementally (each generation's ``k`` new paths
against its ``n`` paths: ``O(k n)``) and capped (:data:`CAP` paths by
default; the most crowded go first, never an extreme, and a path that a
dropped one dominates is refused).

Re-routed paths have no genome: they stay in the archive and are not fed
back to the population. :func:`gapath.solver.solve` returns the archive's
front (``PathFront.X`` is then empty) for free paths.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import numpy as np
from pymoo.core.callback import Callback

from gapath.errors import ConfigError, non_negative
from gapath.front import PathFront
from gapath.metrics import TOL, close, dedupe, hv_ratio
from gapath.objectives import INTERFERING, SMOOTHNESS

#: Default range of ``log10`` of the re-routing searches' cell-cost weight.
LAM_RANGE = (-3.0, 12.0)
#: Decades past ``lam_range``'s top that aimed re-routings reach at the safe end.
AIM_EXTRA = 2.0
#: Whole-path re-routings towards the smooth end: their weight genes are
#: drawn in ``[0, EXTREME_LAM]`` (of ``lam_range``).
EXTREME_LAM = 0.2
#: Whole-path re-routings towards the smooth end: the range of ``log10`` of
#: their turn weight (per radian, against length).
EXTREME_TURNS = (2.0, 4.0)
#: Exact stretch searches per generation with two objectives
#: (``exact_stretches``'s default; 0 with three or more).
EXACT_STRETCHES = 8
#: Share of a path's cells an exact stretch search spans (drawn uniformly).
EXACT_SPAN = (0.02, 0.1)
#: Default cap on the archive's size (see :class:`FreePathArchive`).
CAP = 5000
#: Default share of a path's cells a re-routed segment spans (drawn uniformly).
SEGMENT = (0.05, 0.5)
#: The same with smoothness as an objective: shorter segments, many more of
#: them (:func:`default_refine`). A re-routing search then runs over (cell,
#: heading) states in a window around its segment, so its cost grows with
#: the segment's square; on 256x256 maps, 16 times as many paths re-routed
#: over at most 15 % of their length reach HV 0.99 of the exact front in
#: fewer generations than twice the population over up to half of it, at a
#: lower cost per generation (docs/results/free_paths.md, sixteenth
#: session).
SEGMENT_TURNS = (0.01, 0.15)
#: With three or more objectives, the archive's first refinement adds the
#: exact front of each pair of its objectives (among length, vulnerability,
#: smoothness); the searches share a budget of this many expansions per
#: reachable cell (``faces``'s default; 0 with two objectives).
FACE_BUDGET = 200
#: The ``epsilon`` of the approximate three-objective search after the faces
#: (``approx``'s default with the objectives length, vulnerability and
#: smoothness; see ``docs/results/free_paths.md``, "Approximate
#: three-objective search").
APPROX_EPSILON = 0.1
#: Its budget in expansions per reachable cell (``approx_budget``'s default).
APPROX_BUDGET = 200
#: ``approx_retry``'s default: when the exact (length, vulnerability) face,
#: cut to its :func:`eps_cover` at the approximate search's epsilon, keeps
#: less than this share of its HV, the search runs at
#: :data:`APPROX_RETRY_EPSILON` instead (``docs/results/free_paths.md``,
#: twenty-second session). Measured on the instances of earlier sessions:
#: 0.38-0.66 on nine MovingAI 8room_000 queries (one point covers the whole
#: face there: lengths and vulnerabilities within 10 %), where generation 1
#: needs the finer search; 0.77-0.84 on eleven 256 x 256 random fields and
#: 0.81 on a 128 x 128 one, where it does not.
APPROX_RETRY_BELOW = 0.72
#: The ``epsilon`` of the finer search (``approx_retry_epsilon``'s default).
#: 0.02 was tried in the twenty-second session: better on the seen 8room_000
#: queries, not on fresh ones (one of four lost the 10x target, none gained
#: it), so 0.03 stays.
APPROX_RETRY_EPSILON = 0.03
#: The pair of objectives whose face decides the approximate search's epsilon.
LV = frozenset(("length", "vulnerability"))


def eps_cover(F, eps: float) -> np.ndarray:
    """Indices (increasing) of a smallest subset of the two-objective front
    ``F`` (minimised, non-negative, mutually non-dominated) that holds, for
    every row ``q``, a row ``p`` with ``p <= (1 + eps) q`` in both
    objectives. Greedy in the first objective's order: the first row not yet
    covered is covered by the last row within ``1 + eps`` of it in the first
    objective (the rows that cover a row are consecutive in that order, so
    the greedy choice is optimal).

    Examples
    --------
    >>> eps_cover([[10.0, 5.0], [10.5, 4.0], [11.5, 1.0], [12.0, 0.5]], 0.1).tolist()
    [1, 3]
    """
    F = np.asarray(F, float)
    order = np.lexsort((F[:, 1], F[:, 0]))
    G = F[order]
    keep = []
    i, n = 0, len(G)
    while i < n:
        j = i + int(np.searchsorted(G[i:, 0], (1.0 + eps) * G[i, 0], side="right")) - 1
        keep.append(j)
        p = G[j]
        i += 1
        while i < n and p[0] <= (1.0 + eps) * G[i, 0] and p[1] <= (1.0 + eps) * G[i, 1]:
            i += 1
    return np.sort(order[keep])


def dominated_by(B, A, tol: float = TOL) -> np.ndarray:
    """Which rows of ``B`` some row of ``A`` dominates, up to SPEC's
    tolerance (as :func:`gapath.metrics.nondominated` with ``tol``).

    Examples
    --------
    >>> dominated_by([[2.0, 2.0], [0.0, 3.0], [1.0, 1.0 + 1e-12]], [[1.0, 1.0]]).tolist()
    [True, False, False]
    """
    B, A = np.asarray(B, float), np.asarray(A, float)
    out = np.zeros(len(B), bool)
    if len(B) == 0 or len(A) == 0:
        return out
    chunk = max(1, 2_000_000 // max(1, A.size))
    for s in range(0, len(B), chunk):
        b = B[s : s + chunk, None, :]
        eq = close(A[None, :, :], b, tol)
        not_worse = ((A[None, :, :] <= b) | eq).all(axis=2)
        better = ((A[None, :, :] < b) & ~eq).any(axis=2)
        out[s : s + chunk] = (not_worse & better).any(axis=1)
    return out


def crowding(F) -> np.ndarray:
    """Crowding distance of the rows of ``F`` (a non-dominated set): per
    objective, the gap between a row's two neighbours in that objective's
    order over the objective's range, summed; ``inf`` for the best and the
    worst row of each objective (the extremes).

    Examples
    --------
    >>> crowding([[0.0, 4.0], [1.0, 2.0], [3.0, 1.0], [4.0, 0.0]]).tolist()
    [inf, 1.5, 1.25, inf]
    """
    F = np.asarray(F, float)
    n, m = F.shape
    cd = np.zeros(n)
    if n <= 2:
        cd[:] = np.inf
        return cd
    for j in range(m):
        order = np.argsort(F[:, j], kind="stable")
        f = F[order, j]
        span = f[-1] - f[0]
        if span > 0:
            cd[order[1:-1]] += (f[2:] - f[:-2]) / span
        cd[order[0]] = cd[order[-1]] = np.inf
    return cd


def crowding_truncation(F, cap: int) -> np.ndarray:
    """Indices (increasing) of the rows of the non-dominated set ``F`` kept
    when it is cut to ``cap`` rows: in rounds, the rows of smallest
    :func:`crowding` distance go, at most a tenth per round; a row best or
    worst in some objective never goes (so more than ``cap`` may stay).

    Examples
    --------
    >>> crowding_truncation([[0.0, 4.0], [1.0, 2.9], [1.1, 2.8], [4.0, 0.0]], 3).tolist()
    [0, 2, 3]
    """
    F = np.asarray(F, float)
    keep = np.arange(len(F))
    while len(keep) > cap:
        cd = crowding(F[keep])
        movable = np.flatnonzero(np.isfinite(cd))
        if len(movable) == 0:
            break
        r = min(len(keep) - cap, max(1, len(keep) // 10), len(movable))
        keep = np.delete(keep, movable[np.argsort(cd[movable], kind="stable")[:r]])
    return keep


def default_refine(objectives, pop_size: int) -> int:
    """Archived paths re-routed per generation by the archive
    :func:`gapath.solver.solve` keeps for free paths, with a population of
    ``pop_size``: ``pop_size // 2`` with two objectives, ``16 * pop_size``
    with three or more among which smoothness (each over a short segment,
    :data:`SEGMENT_TURNS`), ``2 * pop_size`` with other three or more
    (docs/results/free_paths.md).

    Examples
    --------
    >>> default_refine(["length", "vulnerability"], 200)
    100
    >>> default_refine(["length", "vulnerability", "smoothness"], 200)
    3200
    """
    objectives = list(objectives)
    if len(objectives) <= 2:
        return int(pop_size) // 2
    return (16 if "smoothness" in objectives else 2) * int(pop_size)


def face_pairs(objectives) -> list[tuple[str, str]]:
    """The pairs of ``objectives`` among length, vulnerability and smoothness
    whose exact fronts :meth:`FreePathArchive.add_faces` archives, in the
    order it searches them: (length, smoothness) first, the cheapest on
    every map measured, then the others in the objectives' order.

    Examples
    --------
    >>> face_pairs(["length", "vulnerability", "smoothness"])
    [('length', 'smoothness'), ('length', 'vulnerability'), ('vulnerability', 'smoothness')]
    """
    from itertools import combinations

    names = [n for n in objectives if n in ("length", "vulnerability", "smoothness")]
    pairs = list(combinations(names, 2))
    pairs.sort(key=lambda pair: set(pair) != {"length", "smoothness"})  # stable: the rest in order
    return pairs


class PathArchive(Callback):
    """What the run archives share (:class:`FreePathArchive`,
    :class:`gapath.operators.monotone_archive.MonotonePathArchive`): a pymoo
    callback that, after every generation, adds the generation's offspring
    (the first population at the first generation) with :meth:`add` and then,
    if it holds a path, refines itself once with :meth:`improve`.

    A subclass keeps ``self.problem`` and ``self._M``, the SPEC metric rows
    of its paths (one row a path), and defines :meth:`add`, :meth:`improve`,
    :meth:`genomes` and :meth:`paths`.
    """

    problem: Any
    _M: np.ndarray

    def __len__(self) -> int:
        return len(self._M)

    @property
    def F(self) -> np.ndarray:
        """Unpenalised objectives of the archived paths."""
        if len(self) == 0:
            return np.zeros((0, self.problem.n_obj))
        return self.problem.objective_values(self._M)

    def notify(self, algorithm):
        self.add(offspring_genomes(algorithm, self.problem.n_var))
        if len(self):
            self.improve()

    def add(self, X) -> None:
        """Add the paths of the genomes ``X`` (``(n, n_var)``)."""
        raise NotImplementedError

    def improve(self) -> None:
        """One generation's refinement of the archive."""
        raise NotImplementedError

    def genomes(self) -> np.ndarray:
        """The archived paths' genomes, or ``(k, 0)`` when some path has none."""
        raise NotImplementedError

    def paths(self) -> list[np.ndarray]:
        """The archived paths (``(m_i, 2)`` workspace cells)."""
        raise NotImplementedError

    def start(self) -> None:
        """Called by :func:`gapath.solver.solve` before the run: work that may
        start early (none here)."""

    def close(self) -> None:
        """Called by :func:`gapath.solver.solve` after the run, even when it
        was interrupted: end what :meth:`start` began (nothing here)."""

    def front(self) -> PathFront:
        """The archive as a :class:`gapath.front.PathFront` (lexicographic
        order); its ``X`` is :meth:`genomes`."""
        return PathFront(tuple(self.problem.objectives), self.F, self._M.copy(), self.genomes(), self.paths())


def offspring_genomes(algorithm, n_var: int) -> np.ndarray:
    """The genomes of ``algorithm``'s last offspring (the first population
    at the first generation): read from :class:`gapath.algorithms.FastNSGA2`'s
    arrays when it has them (no pymoo ``Population`` built), else from
    ``algorithm.off``."""
    arrays = getattr(algorithm, "_offspring", None)
    X = getattr(arrays, "X", None)
    if X is None:
        off = getattr(algorithm, "off", None)
        X = None if off is None or len(off) == 0 else off.get("X")
    return np.zeros((0, n_var)) if X is None else np.asarray(X, dtype=float)


class FreePathArchive(PathArchive):
    """Every feasible non-dominated free path seen in a run, refined each
    generation by re-routing segments (see the module docstring).

    Parameters
    ----------
    problem : :class:`gapath.problems.FreePathProblem`.
    n_refine : re-routed paths per generation (0, with ``faces=0`` and ``approx=0``: a plain
        archive).
    seed : seed of the archive's own random numbers (the GA's are untouched,
        so the population evolves as without the archive).
    segment : ``(lo, hi)``, the share of a path's cells a re-routed segment
        spans, drawn uniformly (default :data:`SEGMENT`, or
        :data:`SEGMENT_TURNS` with smoothness as an objective).
    lam_range : ``(lo, hi)``, the range of ``log10`` of the cell-cost weight
        of the re-routing searches (see :mod:`gapath.encodings.free`), drawn
        log-uniformly; wider than the genomes' by default: the last points
        of the safe end of a front trade a step for a potential of 1e-9
        (MovingAI den312d).
    shortcut : share of the refined paths straightened instead of re-routed
        (default 0.25 with smoothness as an objective, else 0).
    sparse : share of the refined paths' parents drawn with probability
        proportional to their crowding distance in the archive (isolated
        paths and the extremes of the front more often; with two
        objectives, length first, their re-routing weights are also aimed,
        see :meth:`_weight_genes`); the others are drawn uniformly.
        Default 0.5 with three or more objectives, 0 with two (measured in
        ``docs/results/free_paths.md``: no gain with two).
    cap : at most this many archived paths (None: unbounded). Past it the
        most crowded paths go, never an extreme (the best and worst path of
        each objective stay, so a cap below ``2 * n_obj`` may be exceeded);
        the objective vectors of the dropped paths are kept, and a new path
        one of them dominates is refused (see :meth:`_truncate`).
    exact_stretches : stretches per generation (default
        :data:`EXACT_STRETCHES`, 8, with two objectives, 0 with more) of
        randomly picked archived paths, each
        spanning a share :data:`EXACT_SPAN` of its path, replaced by every
        path of the exact front between the stretch's ends
        (:func:`gapath.planners.exact.free_front`): the non-supported
        sub-paths no weighted re-routing gives. Objectives with costmap
        layers: none. Counted in ``n_eval``.
    faces : with three or more objectives, the budget of the exact
        two-objective face searches (see the module docstring), shared in
        their order, in expansions per reachable cell (default
        :data:`FACE_BUDGET`, 200; 0 with two objectives, or to switch the
        faces off); the search that reaches what is left stops there and
        keeps the points it found (part of its exact front), and the ones
        after it do not run (deterministic: it depends on the map, not on
        the clock).
        The face paths are counted in ``n_eval``.
    approx : the ``epsilon`` of the approximate three-objective search run
        after the faces (default :data:`APPROX_EPSILON` when the objectives
        are length, vulnerability and smoothness; 0 switches it off; must
        be 0 with other objectives). Its paths are counted in ``n_eval``.
    approx_budget : that search's budget in expansions per reachable cell
        (default :data:`APPROX_BUDGET`); it stops there and keeps what it
        found (deterministic, as the faces). It is not run when a face
        search stopped short: on such a map it costs more than the faces.
    approx_retry : when the exact (length, vulnerability) face, cut to its
        :func:`eps_cover` at ``approx``, keeps less than this share of its
        HV, the approximate search runs at ``approx_retry_epsilon`` instead
        of ``approx`` (default :data:`APPROX_RETRY_BELOW`; 0 switches it
        off). The share is in ``approx_shortfall``; when the finer search
        ran, its front's size and whether it finished are in
        ``retry_size``.
    approx_retry_epsilon : that finer search's ``epsilon`` (default
        :data:`APPROX_RETRY_EPSILON`; must be > 0, and below ``approx`` for
        the rule to apply).
    extremes : with smoothness as an objective, whole archived paths
        re-routed per generation under a heavy turn weight
        (``log10(c / a)`` in :data:`EXTREME_TURNS`) and a light cell cost
        (weight genes up to :data:`EXTREME_LAM`): the smooth end of the
        front, whose extreme sets the HV's smoothness ideal (counted in
        ``n_eval``). Default 4, or 0 when the face searches run
        (``faces > 0``): their fronts with smoothness hold that end exactly,
        and a whole path re-routed over (cell, heading) states costs as much
        as hundreds of short segments.

    Attributes
    ----------
    n_eval : paths evaluated by the archive (re-routed ones).
    n_dropped : paths the cap dropped.

    Raises
    ------
    ConfigError
        On a problem that is not a free-path problem, a negative
        ``n_refine``, a bad ``segment``, ``lam_range``, ``shortcut``,
        ``sparse``, ``extremes``, ``exact_stretches``, ``faces``, ``approx``,
        ``approx_budget``, ``approx_retry``, ``approx_retry_epsilon`` or
        ``cap``.

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
        segment=None,
        lam_range=LAM_RANGE,
        shortcut=None,
        sparse=None,
        cap=CAP,
        extremes=None,
        exact_stretches=None,
        faces=None,
        approx=None,
        approx_budget=APPROX_BUDGET,
        approx_retry=APPROX_RETRY_BELOW,
        approx_retry_epsilon=APPROX_RETRY_EPSILON,
    ):
        super().__init__()
        if getattr(problem, "paths", None) != "free":
            raise ConfigError(f"FreePathArchive needs a FreePathProblem, got {type(problem).__name__}")
        if segment is None:
            segment = SEGMENT_TURNS if "smoothness" in problem.objectives else SEGMENT
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
        #: aim the weights at the neighbours' trade-offs (two objectives, length first)
        self._aim = problem.n_obj == 2 and problem.objectives[0] == "length" and not self.turns
        if shortcut is None:
            shortcut = 0.25 if self.turns else 0.0
        try:
            shortcut = float(shortcut)
        except (TypeError, ValueError):
            raise ConfigError(f"shortcut must be a share in [0, 1], got {shortcut!r}") from None
        if not 0.0 <= shortcut <= 1.0:
            raise ConfigError(f"shortcut must be a share in [0, 1], got {shortcut!r}")
        self.shortcut = shortcut
        if sparse is None:  # measured: helps with three objectives, not with two
            sparse = 0.5 if problem.n_obj >= 3 else 0.0
        try:
            sparse = float(sparse)
        except (TypeError, ValueError):
            raise ConfigError(f"sparse must be a share in [0, 1], got {sparse!r}") from None
        if not 0.0 <= sparse <= 1.0:
            raise ConfigError(f"sparse must be a share in [0, 1], got {sparse!r}")
        self.sparse = sparse
        if exact_stretches is None:  # measured with two objectives only
            exact_stretches = EXACT_STRETCHES if problem.n_obj == 2 else 0
        exact_stretches = _whole(exact_stretches, "exact_stretches")
        # only over the objectives the exact search has (no costmap layers)
        additive = set(problem.objectives) <= {"length", "vulnerability", "smoothness"}
        self.exact_stretches = exact_stretches if additive else 0
        if faces is None:
            faces = FACE_BUDGET if problem.n_obj >= 3 else 0
        per_cell = " (expansions per reachable cell)"
        self.faces = non_negative(faces, "faces", finite=False, what=per_cell)
        three = problem.n_obj == 3 and additive  # length, vulnerability, smoothness
        if approx is None:
            approx = APPROX_EPSILON if three else 0.0
        self.approx = non_negative(approx, "approx", what=" (an epsilon)")
        if self.approx and not three:
            raise ConfigError(
                f"approx={approx!r} needs the objectives length, vulnerability and smoothness, "
                f"got {', '.join(problem.objectives)}; use approx=0"
            )
        self.approx_budget = non_negative(approx_budget, "approx_budget", finite=False, what=per_cell)
        self.approx_retry = non_negative(approx_retry, "approx_retry", what=" (an HV ratio)")
        self.approx_retry_epsilon = non_negative(
            approx_retry_epsilon, "approx_retry_epsilon", what=" (an epsilon)"
        )
        if self.approx_retry_epsilon == 0:
            raise ConfigError(
                "approx_retry_epsilon must be an epsilon > 0, got 0 (approx_retry=0 switches the rule off)"
            )
        self.approx_shortfall: float | None = None
        self.retry_size: tuple[int | None, bool] | None = None
        if extremes is None:  # the faces with smoothness hold the smooth end exactly
            extremes = 0 if self.faces > 0 else 4
        self.extremes = _whole(extremes, "extremes")
        self._faces_done = False
        self._background: _Background | None = None
        #: the (length, vulnerability) face when :meth:`start` searched it
        self._lv: tuple | None = None
        #: the face searches, then the approximate one: ``(objectives, points kept or
        #: None when not run, whether it finished within the budget)``
        self.face_sizes: list[tuple[tuple[str, ...], int | None, bool]] = []
        if cap is not None:
            cap = _whole(cap, "cap", least=2, also=" or None")
        self.cap = cap
        self.rng = np.random.default_rng(seed)
        self.n_eval = 0
        self.n_dropped = 0
        self._shadow = np.zeros((0, problem.n_obj))
        enc = problem.encoding
        self._flat = np.zeros(0, np.int64)
        self._offsets = np.zeros(1, np.int64)
        self._keys = np.zeros((0, 3), np.int64)
        self._M = np.zeros((0, 0))
        self._X = np.zeros((0, enc.n_var))
        self._genome = np.zeros(0, bool)

    # -- the generation hook ---------------------------------------------------
    def improve(self) -> None:
        """One generation's refinement: :meth:`refine` ``n_refine`` paths,
        then :meth:`exact_refine` ``exact_stretches`` stretches (the first
        one starts with :meth:`add_faces`)."""
        if not self._faces_done:
            self._faces_done = True
            if self.faces > 0 or self.approx > 0:
                self.add_faces()
        if self.n_refine:
            self.refine(self.n_refine)
        if self.exact_stretches and len(self):
            self.exact_refine(self.exact_stretches)

    def exact_refine(self, n: int) -> None:
        """Replace one short random stretch of ``n`` randomly picked
        archived paths by each path of the exact front between the
        stretch's ends, and archive the results."""
        from gapath.operators._archive_kernels import splice
        from gapath.planners.exact import free_front

        rng = self.rng
        ws = self.problem.workspace
        pick = rng.integers(0, len(self), n)
        m = np.diff(self._offsets)[pick]
        lo, hi = EXACT_SPAN
        span = np.minimum(np.maximum(2, np.rint(rng.uniform(lo, hi, n) * (m - 1))).astype(np.int64), m - 1)
        i0 = np.floor(rng.random(n) * (m - span)).astype(np.int64)
        i1 = i0 + span
        w = ws.shape[1]
        rows, subs = [], []
        for r in range(n):  # a few exact searches per generation, each one numba search
            a = self._offsets[pick[r]]
            u, v = int(self._flat[a + i0[r]]), int(self._flat[a + i1[r]])
            if u == v:
                continue
            sub_ws = ws.replace(start=(u // w, u % w), goal=(v // w, v % w))
            sub_ws.__dict__["potential"] = ws.potential  # the same map: reuse its cached field
            for path in free_front(sub_ws, tuple(self.problem.objectives)).paths:
                rows.append(r)
                subs.append(path[:, 0].astype(np.int64) * w + path[:, 1])
        if not rows:
            return
        idx = np.asarray(rows, np.int64)
        sub_off = np.concatenate([[0], np.cumsum([len(x) for x in subs])]).astype(np.int64)
        flat, offsets, keys = splice(
            self._flat, self._offsets, pick[idx], i0[idx], i1[idx], np.concatenate(subs), sub_off, ws.occ.size
        )
        k = len(idx)
        self.n_eval += k
        self._merge(flat, offsets, keys, np.full((k, self._X.shape[1]), np.nan), np.zeros(k, bool))

    def start(self) -> None:
        """Start generation 1's approximate three-objective search in a
        second thread now, when ``GAPATH_THREADS`` asks for two threads or
        more and :meth:`add_faces` will run it beside the faces (else
        nothing): :func:`gapath.solver.solve` calls it before the first
        population is sampled, so that the search overlaps the sampling
        too. With ``approx_retry`` on, the (length, vulnerability) face is
        searched here, in this thread, while that search starts; when
        :meth:`_search_epsilon` finds the face coarse, the second thread
        turns to the finer search (the longer one) and :meth:`add_faces`
        runs the first in this thread after the other faces.
        :meth:`add_faces` takes the face and the results; :meth:`close`
        cancels what was not taken."""
        from gapath.encodings.free import wanted_threads

        if self._background is not None or self.face_sizes:
            return
        budget = self._approx_expansions()
        if not (self.approx > 0 and self.faces > 0 and budget > 0 and wanted_threads() >= 2):
            return
        ws = self.problem.workspace
        _ = ws.potential  # (computed here, not in both threads at once)
        three = tuple(self.problem.objectives)
        fine = None
        lv_pair = self._lv_pair()
        if lv_pair is not None:
            if self._lv is None:
                # the first search runs beside the face until the face has decided
                self._background = _Background(
                    lambda cancel: _budget_search(ws, three, self.approx, budget, cancel)
                )
                try:
                    self._lv = _budget_search(
                        ws, lv_pair, 0.0, self.faces * self.problem.encoding.n_reachable
                    )
                except BaseException:
                    self.close()
                    raise
            fine = self._search_epsilon(self._lv)
            if fine is None and self._background is not None:
                return  # the first search goes on
            self.close()
        eps = self.approx if fine is None else fine
        self._background = _Background(lambda cancel: _budget_search(ws, three, eps, budget, cancel))

    def _approx_expansions(self) -> float:
        """The approximate search's budget in expansions."""
        return self.approx_budget * self.problem.encoding.n_reachable

    def close(self) -> None:
        """Cancel a search started by :meth:`start` that :meth:`add_faces`
        has not taken (a run that ended before its first refinement)."""
        background, self._background = self._background, None
        if background is not None:
            background.cancel()

    def add_faces(self) -> None:
        """Archive the paths of the exact two-objective front of each pair
        of the objectives among length, vulnerability and smoothness while
        the searches stay within the ``faces`` expansions per reachable cell
        they share; then, with ``approx > 0``, those of the approximate
        three-objective front within its own ``approx_budget``, and, when
        :meth:`_search_epsilon` finds the (length, vulnerability) face
        coarse, those of the same search at ``approx_retry_epsilon`` (within
        the same budget). A search stopped by its budget gives the points it
        found (``free_front(..., max_expansions=)``).

        The faces are searched in :func:`face_pairs`'s order, except that
        with ``approx_retry`` on the (length, vulnerability) face goes first
        (it decides whether the finer search runs); their paths are archived
        in :func:`face_pairs`'s order, then the approximate searches'. When
        ``GAPATH_THREADS`` asks for two threads or more
        (:func:`gapath.encodings.free.wanted_threads`), one approximate
        search runs in a second thread while the faces run in this one (the
        kernels release the GIL), started here or already by :meth:`start`:
        the finer one when it runs (the other then runs here after the
        faces), and it is cancelled if a face stops short; the archive
        receives the same paths in the same order either way."""
        from gapath.operators._archive_kernels import keyed

        enc = self.problem.encoding
        ws = self.problem.workspace
        w = ws.shape[1]
        order = face_pairs(self.problem.objectives) if self.faces > 0 else []
        pairs = list(order)
        lv_pair = self._lv_pair()
        if lv_pair is not None:
            pairs.remove(lv_pair)
            pairs.insert(0, lv_pair)
        three = tuple(self.problem.objectives)
        self.start()
        background, self._background = self._background, None
        lv, self._lv = self._lv, None
        subs: list[np.ndarray] = []
        try:
            left = self.faces * enc.n_reachable
            sizes, found = {}, {}
            for pair in pairs:
                if pair == lv_pair and lv is not None:
                    result = lv  # searched by start()
                elif left > 0:
                    result = _budget_search(ws, pair, 0.0, left)
                else:
                    result = _NOT_RUN
                paths, kept, done, used, _ = result
                left = left - used if done else 0
                sizes[pair], found[pair] = (pair, kept, done), paths
                if pair == lv_pair:
                    lv = result
            self.face_sizes.extend(sizes[pair] for pair in order)
            subs = [path for pair in order for path in found[pair]]
            if self.approx > 0:
                # not run where a face stopped short: it costs more than the faces there
                fit = all(done for _, _, done in self.face_sizes)
                budget = self._approx_expansions()
                fine = self._search_epsilon(lv)  # recorded as start() records it
                run = fit and budget > 0
                first = second = _NOT_RUN
                if not run:
                    pass
                elif background is not None and fine is None:
                    first = background.result()
                else:
                    first = _budget_search(ws, three, self.approx, budget)
                    if fine is not None:
                        second = (
                            background.result()
                            if background is not None
                            else _budget_search(ws, three, fine, budget)
                        )
                self.face_sizes.append((three, first[1], first[2]))
                subs += first[0]
                if run and fine is not None:
                    self.retry_size = (second[1], second[2])
                    subs += second[0]
        finally:
            if background is not None:
                background.cancel()
        if not subs:
            return
        flat_paths = [p[:, 0].astype(np.int64) * w + p[:, 1] for p in subs]
        sub_off = np.concatenate([[0], np.cumsum([len(x) for x in flat_paths])]).astype(np.int64)
        flat, offsets, keys = keyed(np.concatenate(flat_paths), sub_off, ws.occ.size)
        k = len(flat_paths)
        self.n_eval += k
        self._merge(flat, offsets, keys, np.full((k, self._X.shape[1]), np.nan), np.zeros(k, bool))

    def _lv_pair(self) -> tuple[str, str] | None:
        """The (length, vulnerability) face's pair when it decides the
        approximate search's epsilon (``approx_retry`` on), else None."""
        if not (self.faces > 0 and self.approx > 0 and self.approx_retry > 0):
            return None
        if not self.approx > self.approx_retry_epsilon:
            return None
        pairs = [pair for pair in face_pairs(self.problem.objectives) if set(pair) == LV]
        return pairs[0] if pairs else None

    def _search_epsilon(self, lv) -> float | None:
        """``approx_retry_epsilon`` when the finer search runs, else None:
        when the exact (length, vulnerability) face ``lv`` (a
        :func:`_budget_search` result) is coarse for ``approx``, that is
        when its :func:`eps_cover` at ``approx`` keeps less than
        ``approx_retry`` of its HV (recorded in ``approx_shortfall``): a
        search at ``approx`` merges most of that trade-off into a few
        points. Decided from the face alone: the same on any machine and
        with any number of threads."""
        if lv is None or self._lv_pair() is None:
            return None
        _, _, done, _, F = lv
        if not done or F is None or not len(F):
            return None
        self.approx_shortfall = float(hv_ratio(F[eps_cover(F, self.approx)], F))
        return self.approx_retry_epsilon if self.approx_shortfall < self.approx_retry else None

    def add(self, X) -> None:
        """Archive the decoded paths of genomes ``X`` (those non-dominated)."""
        if len(X) == 0:
            return
        enc = self.problem.encoding
        flat, offsets, keys = enc.decode_flat(X)
        self._merge(flat, offsets, keys, X, np.ones(len(X), bool))

    def refine(self, n: int) -> None:
        """Change one random segment of ``n`` archived paths (picked by
        :meth:`_parents`) and archive the results: a share ``shortcut`` of
        them straightened
        (:meth:`~gapath.encodings.free.FreeEncoding.shortcut`), the others
        re-routed under a weight gene (:meth:`_weight_genes`,
        :meth:`~gapath.encodings.free.FreeEncoding.reroute`)."""
        rng = self.rng
        enc = self.problem.encoding
        pick, aimed = self._parents(n)
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
            lam, g = self._weight_genes(pick[s], aimed[s], genes[s])
            parts.append(
                enc.reroute(self._flat, self._offsets, pick[s], i0[s], i0[s] + span[s], g, lam, turns)
            )
        k = self.extremes if self.turns else 0
        if k:
            # whole paths re-routed under a heavy turn weight: the smooth end of
            # the front, whose extreme sets the smoothness ideal of the HV
            pe = rng.integers(0, len(self), k)
            whole = np.diff(self._offsets)[pe] - 1
            parts.append(
                enc.reroute(
                    self._flat,
                    self._offsets,
                    pe,
                    np.zeros(k, np.int64),
                    whole,
                    EXTREME_LAM * rng.random(k),
                    self.lam_range,
                    rng.random(k),
                    EXTREME_TURNS,
                )
            )
        flat, offsets, keys = parts[0]
        for f2, o2, k2 in parts[1:]:
            flat, offsets = enc.concat_flat(flat, offsets, f2, o2)
            keys = np.concatenate([keys, k2])
        self.n_eval += n + k
        self._merge(flat, offsets, keys, np.full((n + k, self._X.shape[1]), np.nan), np.zeros(n + k, bool))

    def _parents(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """``n`` archived paths to refine: a share ``sparse`` drawn with
        probability proportional to their crowding distance (isolated paths
        and the extremes more often, an extreme as often as twice the most
        isolated other path), the others uniformly, in a random order."""
        rng = self.rng
        N = len(self)
        pick = rng.integers(0, N, n)
        aimed = np.zeros(n, bool)
        n_sp = int(round(self.sparse * n))
        if n_sp and N > 1:
            w = crowding(self.F)
            fin = np.isfinite(w)
            top = w[fin].max() if fin.any() else 0.0
            w = np.where(fin, w, 2.0 * top if top > 0 else 1.0)
            pick[:n_sp] = rng.choice(N, n_sp, p=w / w.sum())
            aimed[:n_sp] = True
            order = rng.permutation(n)
            pick, aimed = pick[order], aimed[order]
        return pick, aimed

    def _weight_genes(self, pick, aimed, genes):
        """The re-routing searches' weight range and genes. Uniform rows:
        ``log10(b / a)`` uniform over ``lam_range``. With two objectives,
        length and a cell cost (the searches' trade-off), rows ``aimed`` take
        it instead, for half of them, uniform between the trade-offs to the
        parent's two neighbours on the archive's front (``log10`` of length
        gained over cost lost), widened by half a decade, and for the other
        half from that band's low end to the top; the top is
        :data:`AIM_EXTRA` decades past ``lam_range``'s (the safe end):
        splices reach the points between the parent and its neighbours."""
        lo, hi = self.lam_range
        if not self._aim or not aimed.any() or len(self) < 2:
            return self.lam_range, genes
        top = hi + AIM_EXTRA
        F = self.F  # lexicographic: length up, cost down
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = np.log10(np.diff(F[:, 0]) / -np.diff(F[:, 1]))
        slope = np.clip(np.nan_to_num(slope, nan=lo, posinf=top, neginf=lo), lo, top)
        left = np.concatenate([[lo], slope])[pick]  # to the shorter neighbour
        right = np.concatenate([slope, [top]])[pick]  # to the safer one
        a = np.clip(np.minimum(left, right) - 0.5, lo, top)
        b = np.clip(np.maximum(left, right) + 0.5, lo, top)
        # half of the aimed rows in the band, half from its low end to the top
        # (small detours that pay off only at a steeper trade-off: the
        # non-supported points between two neighbours)
        wide = genes >= 0.5
        g = np.where(wide, 2.0 * genes - 1.0, 2.0 * genes)
        b = np.where(wide, top, b)
        lam = np.where(aimed, a + (b - a) * g, lo + (hi - lo) * genes)
        return (lo, top), (lam - lo) / (top - lo)

    def _merge(self, flat, offsets, keys, X, genome) -> None:
        """Archive the feasible paths ``(flat, offsets)`` that no archived
        (or dropped) path dominates, drop the archived ones they dominate.

        Incremental: the new paths are tested against each other and the
        archive (``O(k n)`` for ``k`` new paths and ``n`` archived), which
        gives exactly the front of the archive and the new paths together
        (the archive is non-dominated and holds one path per objective
        vector, the smoothest); then the cap (:meth:`_truncate`)."""
        enc = self.problem.encoding
        P, L = enc.padded(flat, offsets)
        M = self.problem.path_metrics(P, L)
        keys = np.asarray(keys, np.int64)
        _, first = np.unique(keys, axis=0, return_index=True)  # one row per path
        rows = np.sort(first)
        rows = rows[M[rows, INTERFERING] == 0]
        n_a = len(self)
        if n_a and len(rows):
            rows = rows[~_rows_in(keys[rows], self._keys)]
        if len(rows) == 0:
            return
        Fc = self.problem.objective_values(M[rows])
        FA = self.F
        keep_a = ~dominated_by(FA, Fc)
        dom = dominated_by(Fc, Fc) | dominated_by(Fc, FA) | dominated_by(Fc, self._shadow)
        rows, Fc = rows[~dom], Fc[~dom]
        if len(rows) == 0 and keep_a.all():
            return
        a_idx = np.flatnonzero(keep_a)
        if len(rows):
            # one path per objective vector: only archived paths equal to a new one compete
            near = a_idx[_close_any(FA[a_idx], Fc)]
            Fs = np.concatenate([FA[near], Fc])
            prefer_a = self._M[near, SMOOTHNESS] if len(near) else np.zeros(0)
            prefer = np.concatenate([prefer_a, M[rows, SMOOTHNESS]])
            won = np.zeros(len(Fs), bool)
            won[dedupe(Fs, prefer=prefer)] = True
            a_idx = np.setdiff1d(a_idx, near[~won[: len(near)]])
            rows = rows[won[len(near) :]]
            Fc = Fc[won[len(near) :]]
            if len(self._shadow):
                self._shadow = self._shadow[~dominated_by(self._shadow, Fc)]
        # the kept rows of [archive; new], in lexicographic order of F
        F = np.concatenate([FA[a_idx], Fc])
        take = np.concatenate([a_idx, n_a + rows])[np.lexsort(F.T[::-1])]
        if n_a:
            flat, offsets = enc.concat_flat(self._flat, self._offsets, flat, offsets)
            keys = np.concatenate([self._keys, keys])
            M = np.concatenate([self._M, M])
            X = np.concatenate([self._X, X])
            genome = np.concatenate([self._genome, genome])
        self._flat, self._offsets = enc.take_flat(flat, offsets, take)
        self._keys, self._M, self._X, self._genome = keys[take], M[take], X[take], genome[take]
        if self.cap is not None and len(self) > self.cap:
            self._truncate()

    def _truncate(self) -> None:
        """Cut the archive to ``cap`` paths: in rounds, the most crowded
        (smallest :func:`crowding` distance) archived paths go, at most a
        tenth of the archive per round; a path best or worst in some
        objective (infinite crowding distance) never goes. Every archived
        path is non-dominated, so no dropped path dominates a kept one; the
        dropped objective vectors are remembered (``dropped``) and a new path
        one of them dominates is not archived, so the archive never holds a
        path a path it dropped dominates (up to SPEC's tolerance)."""
        enc = self.problem.encoding
        F = self.F
        keep = crowding_truncation(F, self.cap)
        gone = np.setdiff1d(np.arange(len(self)), keep)
        self._shadow = np.concatenate([self._shadow, F[gone]])
        self.n_dropped += len(gone)
        self._flat, self._offsets = enc.take_flat(self._flat, self._offsets, keep)
        self._keys, self._M, self._X, self._genome = (
            self._keys[keep],
            self._M[keep],
            self._X[keep],
            self._genome[keep],
        )

    # -- the result --------------------------------------------------------------
    def paths(self) -> list[np.ndarray]:
        """The archived paths (``(m_i, 2)`` workspace cells)."""
        P, L = self.problem.encoding.padded(self._flat, self._offsets)
        return [P[i, : L[i]].copy() for i in range(len(L))]

    def genomes(self) -> np.ndarray:
        """The archived paths' genomes when every one has one (re-routed
        paths have none), else ``(k, 0)``."""
        return self._X if self._genome.all() else np.empty((len(self), 0))


def _whole(value, name: str, least: int = 0, also: str = "") -> int:
    """``value`` as an ``int`` if it is a whole number >= ``least``, else a
    :class:`ConfigError` naming ``name`` (``also``: other values allowed,
    for the message)."""
    try:
        ok = float(value) == int(value) and int(value) >= least
    except (TypeError, ValueError, OverflowError):
        ok = False
    if not ok:
        raise ConfigError(f"{name} must be an integer >= {least}{also}, got {value!r}")
    return int(value)


def _rows_in(B, A) -> np.ndarray:
    """Which rows of the integer array ``B`` are rows of ``A``."""
    both = np.concatenate([A, B])
    _, inv = np.unique(both, axis=0, return_inverse=True)
    inv = np.asarray(inv).ravel()
    in_a = np.zeros(inv.max() + 1, bool)
    in_a[inv[: len(A)]] = True
    return in_a[inv[len(A) :]]


def _close_any(B, A, tol: float = TOL) -> np.ndarray:
    """Which rows of ``B`` equal some row of ``A`` within SPEC's tolerance."""
    out = np.zeros(len(B), bool)
    if len(B) == 0 or len(A) == 0:
        return out
    chunk = max(1, 2_000_000 // max(1, A.size))
    for s in range(0, len(B), chunk):
        out[s : s + chunk] = close(B[s : s + chunk, None, :], A[None, :, :], tol).all(axis=2).any(axis=1)
    return out


class _Cancelled(Exception):
    """Raised by a cancelled background search's progress hook."""


#: What :func:`_budget_search` gives for a search that did not run.
_NOT_RUN: tuple[list, None, bool, int, None] = ([], None, False, 0, None)


def _budget_search(ws, objectives, eps, budget, cancel=None):
    """``(paths, points kept, finished within the budget, expansions, F)`` of
    ``free_front(ws, objectives, epsilon=eps, max_expansions=budget)``;
    :data:`_NOT_RUN` when the goal cannot be reached. With a ``cancel``
    event the search ends with :class:`_Cancelled` between two kernel calls
    once it is set."""
    from gapath.errors import NoPathError
    from gapath.planners.exact import free_front

    hook = None
    if cancel is not None:

        def hook(info):
            if cancel.is_set():
                raise _Cancelled

    try:
        front = free_front(ws, objectives, epsilon=eps, max_expansions=budget, progress=hook)
    except NoPathError:
        return _NOT_RUN
    return (
        list(front.paths),
        len(front.paths),
        bool(front.stats["complete"]),
        int(front.stats["expansions"]),
        np.asarray(front.F, dtype=float),
    )


class _Background:
    """``fn(cancel)`` run in a daemon thread, which holds one of the
    ``GAPATH_THREADS`` until it ends (:func:`gapath.encodings.free.hold_thread`);
    :meth:`result` waits for it (and raises what it raised), :meth:`cancel`
    sets ``cancel`` and waits until the thread has ended (a Ctrl-C in the
    main thread then stops it within one kernel call)."""

    def __init__(self, fn: Callable[[threading.Event], Any]) -> None:
        from gapath.encodings.free import hold_thread

        self._event = threading.Event()
        self._out: Any = None
        self._error: BaseException | None = None
        release = hold_thread()  # the main thread's batches leave this core to it

        def run():
            try:
                self._out = fn(self._event)
            except BaseException as e:  # handed to the caller by result()
                self._error = e
            finally:
                release()

        self._thread = threading.Thread(target=run, name="gapath-approx-search", daemon=True)
        self._thread.start()

    def result(self):
        self._thread.join()
        if self._error is not None:
            raise self._error
        return self._out

    def cancel(self) -> None:
        self._event.set()
        self._thread.join()


def run_archive(algorithm) -> PathArchive | None:
    """The run's archive (a :class:`FreePathArchive` or a
    :class:`gapath.operators.monotone_archive.MonotonePathArchive`) among the
    callbacks of ``algorithm`` (as :func:`gapath.solver.solve` installs it),
    or None.

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
        if isinstance(c, PathArchive):
            return c
    return None


__all__ = [
    "CAP",
    "EXACT_SPAN",
    "EXACT_STRETCHES",
    "EXTREME_LAM",
    "EXTREME_TURNS",
    "APPROX_BUDGET",
    "APPROX_EPSILON",
    "FACE_BUDGET",
    "LAM_RANGE",
    "FreePathArchive",
    "PathArchive",
    "crowding",
    "crowding_truncation",
    "dominated_by",
    "eps_cover",
    "face_pairs",
    "offspring_genomes",
    "run_archive",
]
