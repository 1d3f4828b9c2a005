"""A vectorised NSGA-II engine inside pymoo.

:class:`FastNSGA2` runs the NSGA-II of :func:`gapath.algorithms.paper_nsga2`
(Ahmed & Deb's configuration) on whole arrays instead of pymoo ``Individual``
objects. It is a pymoo :class:`~pymoo.core.algorithm.Algorithm`: it runs
through :func:`pymoo.optimize.minimize`, honours pymoo's terminations,
callbacks, display and ``save_history``, and returns a normal pymoo
``Result``.

One generation, as in the paper::

    repeat until n_offsprings new paths (at most n_max_iterations rounds):
        parents   = binary_tournament(population)    # CV, rank, smoothness, crowding, coin
        children  = mutation(crossover(parents))     # discrete SBX, discrete PM
        children  = repair(children)                 # edge-fixing
        offspring += children whose path is new      # not in population or offspring
    evaluate(offspring)
    population = survival(population + offspring)   # CV, rank, smoothness, crowding

Equivalence with pymoo's NSGA2
    The engine draws its random numbers from ``algorithm.random_state`` in the
    same calls and order as pymoo's ``NSGA2`` with the same operators, and its
    tournament, survival and duplicate elimination compute exactly what
    :class:`gapath.operators.SmoothnessTournament`,
    :class:`gapath.operators.RankAndSmoothnessSurvival` and
    :class:`gapath.operators.PathDuplicateElimination` compute. For a seed it
    therefore returns the same population as ``paper_nsga2`` run through
    ``minimize`` (tested bit for bit), only faster.

Populations
    The state is a :class:`PathArrays` (genomes, objectives, constraints,
    per-path metrics, rank, crowding). ``algorithm.pop``, ``algorithm.opt`` and
    ``algorithm.off`` are pymoo ``Population`` objects built from it on first
    access in a generation, so a run that nobody looks at builds none until
    the ``Result``. gapath's callbacks (progress bar, hypervolume ratio,
    first feasible generation) read the arrays
    (:func:`gapath.callbacks.population_arrays`), and the evaluation gets
    the paths decoded for duplicate elimination (each path is decoded once).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from moocore import pareto_rank
from pymoo.core.algorithm import Algorithm
from pymoo.core.individual import Individual
from pymoo.core.population import Population
from pymoo.core.repair import Repair
from pymoo.core.sampling import Sampling
from pymoo.core.variable import Variable, get
from pymoo.util.display.multi import MultiObjectiveOutput
from pymoo.util.display.single import SingleObjectiveOutput
from pymoo.util.misc import random_permutations

from gapath.algorithms._kernels import (
    accept_new_rows,
    binary_tournament,
    order_survivors,
    pareto_rank_2d,
    path_table,
    profile_keys,
    repeated_rows,
    row_hashes,
    take_rows,
    take_values,
)
from gapath.algorithms._variation import (
    discrete_supported,
    discrete_variation,
    pm_mutation,
    pm_supported,
    sbx_crossover,
    sbx_supported,
)
from gapath.errors import ConfigError
from gapath.operators import EdgeFixingRepair, default_operators

__all__ = ["FastNSGA2", "PathArrays", "PHASES", "fast_survival_order", "pareto_ranks", "path_duplicate_mask"]

#: Phases of a generation timed in :attr:`FastNSGA2.timings` (seconds, summed
#: over the run).
PHASES = ("selection", "variation", "repair", "dedupe", "evaluation", "sorting", "survival")

#: Outputs of ``Problem.evaluate`` that are not per-individual data.
_CORE_OUTPUTS = ("F", "G", "H")


# ---------------------------------------------------------------------------
# array-level building blocks
# ---------------------------------------------------------------------------


def path_duplicate_mask(keys: np.ndarray, *others: np.ndarray) -> np.ndarray:
    """Rows of ``keys`` that repeat an earlier row of ``keys`` or any row of
    ``others``.

    The same answer as :func:`gapath.operators.duplicates.duplicate_mask`
    applied to ``keys`` alone and then against each of ``others`` (what
    pymoo's ``DuplicateElimination.do(off, pop, off_so_far)`` computes), by
    hashing rows instead of sorting them as void scalars (over ten times
    faster at 1,000 rows).

    Parameters
    ----------
    keys : (n, m) int array (e.g. decoded column profiles).
    *others : (k_i, m) int arrays.

    Returns
    -------
    (n,) bool array.

    Examples
    --------
    >>> import numpy as np
    >>> path_duplicate_mask(np.array([[1, 2], [1, 2], [3, 4]]), np.array([[3, 4]])).tolist()
    [False, True, True]
    """
    keys = np.ascontiguousarray(keys, dtype=np.int64).reshape(len(keys), -1)
    others = [np.asarray(o, dtype=np.int64).reshape(len(o), -1) for o in others if len(o)]
    old = np.ascontiguousarray(np.concatenate(others)) if others else np.zeros((0, keys.shape[1]), np.int64)
    h_old = row_hashes(old)
    return repeated_rows(row_hashes(keys), keys, h_old, old, np.argsort(h_old, kind="stable"))


def fast_survival_order(F, smoothness=None, CV=None, n_survive=None):
    """:func:`gapath.operators.survival_order` with the crowding distances
    of all fronts in one numba pass.

    Same arguments and the same result, bit for bit: the ``n_survive`` best
    rows, best first; feasible rows (``CV <= 0``) by non-dominated rank
    (:func:`pareto_ranks`), inside a rank by smaller ``smoothness`` then
    larger crowding distance (pymoo's) then index; infeasible rows after
    them by smaller ``CV``. The ordering is one numba pass
    (:func:`gapath.algorithms._kernels.order_survivors`).

    Returns
    -------
    order, rank, crowding : (n_survive,) arrays.

    Examples
    --------
    >>> import numpy as np
    >>> order, rank, _ = fast_survival_order(np.array([[1., 2.], [2., 1.], [2., 2.]]), [3., 1., 0.])
    >>> order.tolist(), rank.tolist()
    ([1, 0, 2], [0, 0, 1])
    """
    F = np.ascontiguousarray(F, dtype=float)
    n = len(F)
    n_survive = n if n_survive is None else min(int(n_survive), n)
    cv = np.zeros(n) if CV is None else np.asarray(CV, dtype=float).reshape(n, -1)[:, 0]
    smooth = np.zeros(n) if smoothness is None else np.asarray(smoothness, dtype=float)
    feasible = np.flatnonzero(cv <= 0)
    return order_survivors(F, smooth, cv, feasible, pareto_ranks(F[feasible]), n_survive)


def pareto_ranks(F) -> np.ndarray:
    """Non-dominated rank of every row of ``F`` (minimised): a numba sweep
    for two objectives, moocore's ``pareto_rank`` (what pymoo's
    ``NonDominatedSorting`` uses) otherwise; the same ranks either way.

    Examples
    --------
    >>> pareto_ranks(np.array([[1., 2.], [2., 1.], [2., 2.], [1., 2.]])).tolist()
    [0, 0, 1, 0]
    """
    F = np.ascontiguousarray(F, dtype=float)
    if len(F) == 0:
        return np.zeros(0, np.int64)
    if F.shape[1] == 2:  # NumPy's sort (its SIMD one, where the CPU has it): ties in any order
        return pareto_rank_2d(F, np.argsort(F[:, 0]))
    return np.asarray(pareto_rank(F), np.int64)


def _constraint_violation(G, H):
    """pymoo's default constraint violation (``Individual.default_config``):
    the sum of positive inequality values plus the sum of equality
    violations beyond 1e-4."""
    cv = np.zeros(len(G))
    if G.shape[1]:
        cv = cv + np.sum(np.maximum(0.0, G), axis=1)
    if H.shape[1]:
        cv = cv + np.sum(np.maximum(0.0, np.abs(H) - 1e-4), axis=1)
    return cv


def _split_keys(keys):
    """``(entries, exits)`` of path keys ``[entries | exits]`` (contiguous int64)."""
    c = keys.shape[1] // 2
    return np.ascontiguousarray(keys[:, :c]), np.ascontiguousarray(keys[:, c:])


def _scalar(v, size):
    """A pymoo operator parameter as a scalar (an array when it varies per row)."""
    value = v.get() if isinstance(v, Variable) else v
    return value if np.ndim(value) == 0 else get(v, size=size)


def _repair_do(repair, problem, X, **kwargs) -> np.ndarray:
    """pymoo's ``Repair.do`` on an array."""
    if repair is None:
        return X
    if repair.vtype is not None:
        X = X.astype(repair.vtype)
    if type(repair)._do is Repair._do:  # NoRepair
        return X
    return np.asarray(repair._do(problem, X, **kwargs))


# ---------------------------------------------------------------------------
# the population as arrays
# ---------------------------------------------------------------------------


@dataclass
class PathArrays:
    """A population as arrays, one row per individual.

    Attributes
    ----------
    X : (n, n_var) genomes.
    F, G, H : objectives, inequality and equality constraints (as pymoo's
        ``Problem.evaluate`` returns them, float64).
    CV : (n,) constraint violation (pymoo's default definition).
    n_gen : (n,) generation in which each individual was created.
    data : other per-individual outputs of the problem (``smoothness``,
        ``interfering``), each (n,).
    rank, crowding : (n,) set by the survival; None before it.
    keys, hashes : the decoded paths as int64 rows ``[entries | exits]``
        (see :mod:`gapath.monotone`) and their hashes, kept for
        duplicate elimination; None when not known.
    """

    X: np.ndarray
    F: np.ndarray
    G: np.ndarray
    H: np.ndarray
    CV: np.ndarray
    n_gen: np.ndarray
    data: dict = field(default_factory=dict)
    rank: np.ndarray | None = None
    crowding: np.ndarray | None = None
    keys: np.ndarray | None = None
    hashes: np.ndarray | None = None

    _ROWS = ("X", "F", "G", "H", "CV", "n_gen")

    def __len__(self) -> int:
        return len(self.X)

    def take(self, idx) -> PathArrays:
        """The rows ``idx`` (any NumPy index)."""
        out = PathArrays(
            *(getattr(self, k)[idx] for k in self._ROWS), data={k: v[idx] for k, v in self.data.items()}
        )
        if self.rank is not None:
            out.rank, out.crowding = self.rank[idx], self.crowding[idx]
        if self.keys is not None:
            out.keys, out.hashes = self.keys[idx], self.hashes[idx]
        return out

    def concat(self, other: PathArrays) -> PathArrays:
        """This population followed by ``other`` (without rank and crowding;
        ``data`` keeps the keys both have)."""
        out = PathArrays(
            *(np.concatenate([getattr(self, k), getattr(other, k)]) for k in self._ROWS),
            data={k: np.concatenate([v, other.data[k]]) for k, v in self.data.items() if k in other.data},
        )
        if self.keys is not None and other.keys is not None:
            out.keys = np.concatenate([self.keys, other.keys])
            out.hashes = np.concatenate([self.hashes, other.hashes])
        return out

    def take_merged(self, other: PathArrays, idx) -> PathArrays:
        """``self.concat(other).take(idx)`` (``idx`` an integer array),
        without building the concatenation."""
        out = PathArrays(
            *(_take2(getattr(self, k), getattr(other, k), idx) for k in self._ROWS),
            data={k: _take2(v, other.data[k], idx) for k, v in self.data.items() if k in other.data},
        )
        if self.keys is not None and other.keys is not None:
            out.keys = _take2(self.keys, other.keys, idx)
            out.hashes = _take2(self.hashes, other.hashes, idx)
        return out

    def to_population(self) -> Population:
        """A pymoo ``Population`` of evaluated individuals with the same
        values (``rank``, ``crowding``, the problem's extra outputs and
        ``n_gen`` in each individual's data)."""
        data = dict(self.data)
        if self.rank is not None:
            data["rank"], data["crowding"] = self.rank, self.crowding
        individuals = []
        for i in range(len(self)):
            ind = Individual()
            ind._X, ind._F, ind._G, ind._H = (a[i].copy() for a in (self.X, self.F, self.G, self.H))
            ind._CV = np.array([self.CV[i]], dtype=float)
            ind.evaluated = set(_CORE_OUTPUTS)
            ind.data = {k: v[i] for k, v in data.items()}
            ind.data["n_gen"] = ind.data["n_iter"] = int(self.n_gen[i])
            individuals.append(ind)
        if not individuals:
            return Population.empty(0)
        return np.array(individuals, dtype=object).view(Population)


def _take2(a: np.ndarray, b: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """``np.concatenate([a, b])[idx]``, by a numba gather when ``a`` and
    ``b`` are plain arrays of one dtype (and width)."""
    if a.dtype == b.dtype and a.dtype.kind in "biuf" and a.ndim == b.ndim and a.shape[1:] == b.shape[1:]:
        if a.ndim == 1:
            return take_values(np.ascontiguousarray(a), np.ascontiguousarray(b), idx)
        if a.ndim == 2:
            return take_rows(np.ascontiguousarray(a), np.ascontiguousarray(b), idx)
    return np.concatenate([a, b])[idx]


class _SeenPaths:
    """The paths of the population and of the offspring accepted so far in
    a generation: their keys (the offspring's in preallocated buffers) and
    one hash table over both.

    A path is identified by its decoded column profile (entries then exits,
    see :mod:`gapath.monotone`), as in
    :class:`gapath.operators.PathDuplicateElimination`."""

    def __init__(self, pop_keys, pop_hashes, capacity: int, check: bool = True):
        self.pop_keys, self.pop_hashes = pop_keys, pop_hashes
        self.table, self.mask = path_table(pop_hashes, len(pop_hashes) + capacity)
        self.keys = np.empty((capacity, pop_keys.shape[1]), np.int64)
        self.hashes = np.empty(capacity, np.int64)
        self.n, self.check = 0, check

    def accept(self, keys, hashes, n_max: int) -> np.ndarray:
        """Indices of the first ``n_max`` rows whose path is new (not seen,
        not repeated inside ``keys``); they become seen."""
        idx = accept_new_rows(
            keys,
            hashes,
            self.pop_keys,
            self.pop_hashes,
            self.table,
            self.mask,
            self.keys,
            self.hashes,
            self.n,
            n_max,
            self.check,
        )
        self.n += len(idx)
        return idx


# ---------------------------------------------------------------------------
# the algorithm
# ---------------------------------------------------------------------------


def _check_problem(problem) -> None:
    encoding = getattr(problem, "encoding", None)
    if (
        encoding is None
        or not callable(getattr(encoding, "decode", None))
        or not callable(getattr(problem, "metrics", None))
    ):
        raise ConfigError(
            f"FastNSGA2 needs a gapath path problem (an `encoding` that decodes genomes into "
            f"paths and a `metrics` method, e.g. gapath.problems.GridPathProblem), got "
            f"{type(problem).__name__}; use gapath.algorithms.paper_nsga2 or pymoo's NSGA2 for "
            f"other problems"
        )


class FastNSGA2(Algorithm):
    """Ahmed & Deb's NSGA-II (:func:`gapath.algorithms.paper_nsga2`) on arrays.

    Per generation: binary tournaments (smaller constraint violation, then
    smaller rank, then smaller smoothness when the tie-break is on, then
    larger crowding distance, then a coin), crossover and mutation (each
    operator's array-level ``_do``, its mating probability ``prob`` and its
    own rounding repair applied as pymoo's ``Crossover.do``/``Mutation.do``
    apply them), the repair, duplicate elimination by decoded path (mating
    rounds repeated until ``n_offsprings`` new distinct paths or
    ``n_max_iterations`` rounds, as pymoo's mating loop), one vectorised
    evaluation, and elitist rank-and-smoothness (or crowding) survival
    (:func:`fast_survival_order`). No pymoo ``Individual`` is created during
    the run unless something reads ``pop``, ``opt`` or ``off``.

    For a seed, the result equals that of ``paper_nsga2`` with the same
    settings (the same random draws in the same order); only the bookkeeping
    is faster.

    Parameters
    ----------
    pop_size : population size (seeds: 500).
    tiebreak : ``"smoothness"`` (Ahmed & Deb's two-objective mode) or ``None``
        (plain rank and crowding, e.g. for three objectives).
    sampling : initial population: a pymoo ``Sampling``, an array of genomes
        or a ``Population``; default uniform random integers. As in pymoo,
        genomes not yet evaluated are repaired and duplicate paths dropped
        (the population may start below ``pop_size`` and fills up with the
        first offspring); evaluated individuals are not repaired nor counted
        as evaluations (their objectives are recomputed).
    crossover, mutation : pymoo operators; default the encoding's
        (:func:`gapath.operators.default_operators`: for the integer encoding
        :class:`~gapath.operators.DiscreteSBX` and
        :class:`~gapath.operators.DiscretePM` with ``sbx_prob``, ``sbx_eta``,
        ``pm_eta``, ``pm_prob_var``).
    repair : default :class:`~gapath.operators.EdgeFixingRepair`; pass
        ``pymoo.core.repair.NoRepair()`` for none.
    encoding : the encoding the default operators are for; the problem must
        use it. Default None: the problem's own encoding, read at setup
        (operators not given are then created there).
    sbx_prob, sbx_eta, pm_eta, pm_prob_var : settings of the default
        operators (as in :func:`~gapath.algorithms.paper_nsga2`).
    n_offsprings : offspring per generation (default ``pop_size``).
    eliminate_duplicates : drop offspring whose decoded path is already in
        the population or the offspring (default True).
    n_max_iterations : mating rounds per generation at most (pymoo: 100).
    fast_operators : compute pymoo's SBX and polynomial mutation (hence
        DiscreteSBX and DiscretePM) with numba twins that return bit-identical
        children from the same random draws (default True); other operators,
        or False, go through the operator's own ``_do``.
    constraint_handling : None (default: feasible first, by ``CV``, as
        pymoo's NSGA-II) or a :class:`gapath.constraints.AdaptivePenalty`:
        survival and tournament then rank every individual on
        ``F + penalty * CV`` (no feasibility-first rule) with a penalty that
        adapts to the share of feasible survivors. Use it with a problem in
        constraint mode (``G`` = interfering cells).
    **kwargs : passed to :class:`pymoo.core.algorithm.Algorithm`
        (``termination``, ``output``, ``callback``, ``save_history``, ...).
        Unlike pymoo's NSGA2, a ``termination`` given here is kept; default:
        pymoo's default termination for the problem.

    Attributes
    ----------
    pop, opt, off : pymoo ``Population`` views of the current population,
        its optimum (feasible rank 0, or the least infeasible) and the last
        offspring, built on first access in a generation.
    arrays : :class:`PathArrays`, the current population.
    timings : dict phase -> seconds spent in it so far (see :data:`PHASES`),
        measured with :attr:`clock`.
    clock : the clock of ``timings`` (default ``time.perf_counter``; e.g.
        ``time.thread_time`` for CPU time on a busy machine).

    Raises
    ------
    ConfigError
        On a population size below 2, an unknown tie-break or encoding; at
        setup (``minimize``), on a problem that is not a gapath path problem
        or uses another encoding than ``encoding``.

    Examples
    --------
    >>> from pymoo.optimize import minimize
    >>> from gapath import default_workspace
    >>> from gapath.problems import GridPathProblem
    >>> res = minimize(GridPathProblem(default_workspace()), FastNSGA2(20), ("n_gen", 3), seed=1)
    >>> len(res.pop), res.F.shape[1]
    (20, 2)
    """

    clock = staticmethod(time.perf_counter)

    def __init__(
        self,
        pop_size: int = 500,
        *,
        tiebreak: str | None = "smoothness",
        sampling=None,
        crossover=None,
        mutation=None,
        repair=None,
        encoding=None,
        sbx_prob: float = 0.9,
        sbx_eta: float = 10,
        pm_eta: float = 20,
        pm_prob_var: float | None = None,
        n_offsprings: int | None = None,
        eliminate_duplicates: bool = True,
        n_max_iterations: int = 100,
        fast_operators: bool = True,
        constraint_handling=None,
        **kwargs,
    ):
        # state behind the pymoo views (set before Algorithm.__init__ assigns them)
        self._arrays = self._offspring = None
        self._pop = self._opt = self._off = self._opt_idx = None
        super().__init__(**kwargs)
        try:
            pop_size = int(pop_size)
        except (TypeError, ValueError):
            raise ConfigError(f"pop_size must be an integer >= 2, got {pop_size!r}") from None
        if pop_size < 2:
            raise ConfigError(f"pop_size must be an integer >= 2, got {pop_size!r}")
        if tiebreak not in ("smoothness", None):
            raise ConfigError(f"tiebreak must be 'smoothness' or None, got {tiebreak!r}")
        n_offsprings = pop_size if n_offsprings is None else int(n_offsprings)
        if n_offsprings < 1:
            raise ConfigError(f"n_offsprings must be >= 1, got {n_offsprings!r}")
        if int(n_max_iterations) < 1:
            raise ConfigError(f"n_max_iterations must be >= 1, got {n_max_iterations!r}")
        self.pop_size = pop_size
        self.n_offsprings = n_offsprings
        self.tiebreak = tiebreak
        self.encoding = encoding
        self.operator_settings = dict(
            sbx_prob=sbx_prob, sbx_eta=sbx_eta, pm_eta=pm_eta, pm_prob_var=pm_prob_var
        )
        self.sampling, self.crossover, self.mutation = sampling, crossover, mutation
        if encoding is not None:
            self._default_operators(encoding)
        self.repair = repair if repair is not None else EdgeFixingRepair()
        self.eliminate_duplicates = bool(eliminate_duplicates)
        self.n_max_iterations = int(n_max_iterations)
        self.fast_operators = bool(fast_operators)
        if constraint_handling is not None and not callable(getattr(constraint_handling, "penalise", None)):
            raise ConfigError(
                "constraint_handling must be None or a gapath.constraints.AdaptivePenalty, "
                f"got {type(constraint_handling).__name__}"
            )
        self.constraint_handling = constraint_handling
        self.timings = dict.fromkeys(PHASES, 0.0)

    # == the generation loop ==================================================
    def next(self):
        """One generation of NSGA-II (pymoo's ``run``/``minimize`` calls this
        until the termination says stop)."""
        if not self.is_initialized:
            self._initialize()
            offspring = self._initial_population()
            survivors = self._survival(offspring, len(offspring))
            self.is_initialized = True
        else:
            offspring = self._offspring_population()
            survivors = self._survival(self._arrays, self.pop_size, offspring)
        self._set_arrays(survivors, offspring)
        self._post_advance()  # optimum, termination, display, history, callback
        if self.termination.has_terminated():
            self.finalize()
        if self.archive is not None and offspring is not None:
            self.archive = self.archive.add(self.off)

    def _offspring_population(self) -> PathArrays | None:
        """Evaluated offspring of ``n_offsprings`` new distinct paths (fewer
        if ``n_max_iterations`` mating rounds did not find enough; None,
        which ends the run as in pymoo, if they found none)."""
        X, keys, hashes = self._mating(self.n_offsprings)
        if len(X) == 0:
            self.termination.force_termination = True
            return None
        return self._evaluate(X, keys, hashes)

    def _mating(self, n_offsprings: int):
        """Mating rounds until ``n_offsprings`` new distinct paths (pymoo's
        ``InfillCriterion.do``): their genomes, path keys and hashes."""
        t0 = self.clock()
        A = self._arrays
        pop_keys = (A.keys, A.hashes) if A.keys is not None else self._keys(A.X)
        seen = _SeenPaths(*pop_keys, n_offsprings, self.eliminate_duplicates)
        t0 = self._tick("dedupe", t0)
        criteria = self._tournament_criteria()
        offspring = []
        n_off = n_rounds = 0
        while n_off < n_offsprings:
            n_remaining = n_offsprings - n_off
            n_matings = math.ceil(n_remaining / self.crossover.n_offsprings)
            parents = self._selection(n_matings, criteria)
            t0 = self._tick("selection", t0)
            X, draws = self._variation(parents)
            t0 = self._tick("variation", t0)
            X = self._repair(X, draws)
            t0 = self._tick("repair", t0)
            X = self._new_paths(X, seen, n_remaining)
            t0 = self._tick("dedupe", t0)
            offspring.append(X)
            n_off += len(X)
            n_rounds += 1
            if n_rounds >= self.n_max_iterations:
                break
        if n_off < n_offsprings and self.verbose:
            print("WARNING: Mating could not produce the required number of (unique) offsprings!")
        return np.concatenate(offspring), seen.keys[: seen.n], seen.hashes[: seen.n]

    # == NSGA-II steps ========================================================
    def _tournament_criteria(self):
        """The arrays the tournament compares: CV, rank, smoothness (and
        whether to use it), crowding."""
        A = self._arrays
        smooth = A.data.get("smoothness")
        use_smooth = self.tiebreak is not None and smooth is not None
        # a penalty handling ranks infeasible rows among the feasible ones
        cv = A.CV if self.constraint_handling is None else np.zeros(len(A))
        return (
            cv.astype(float),
            A.rank.astype(float),
            np.asarray(smooth if use_smooth else A.CV, dtype=float),
            A.crowding.astype(float),
            use_smooth,
        )

    def _selection(self, n_matings: int, criteria) -> np.ndarray:
        """Binary tournaments: ``(n_matings, n_parents)`` row indices
        (pymoo's ``TournamentSelection`` with Ahmed & Deb's comparison)."""
        n, n_parents = len(self._arrays), self.crossover.n_parents
        n_random = n_matings * n_parents * 2
        P = random_permutations(math.ceil(n_random / n), n, random_state=self.random_state)
        P = np.ascontiguousarray(P[:n_random].reshape(-1, 2))
        coin = self.random_state.random(len(P))
        return binary_tournament(P, *criteria, coin).reshape(n_matings, n_parents)

    def _variation(self, parents: np.ndarray):
        """Crossover, then mutation, of the parents' genomes (for gapath's
        DiscreteSBX and DiscretePM in one numba twin, see ``fast_operators``):
        ``(X, draws)``, ``draws`` the repair's uniform draws when they were
        made with the mutation's (an edge-fixing repair of an encoding with
        ``edge_fix_drawn``), else None."""
        if self._fast_discrete:
            X = self._arrays.X[parents.T]  # (n_parents, n_matings, n_var)
            then = self.problem.n_var if self._drawn_repair else None
            out = discrete_variation(
                self.crossover, self.mutation, self.problem, X, self.random_state, self._bounds, then
            )
            return out if self._drawn_repair else (out, None)
        return self._mutation(self._crossover(parents)), None

    def _crossover(self, parents: np.ndarray) -> np.ndarray:
        """pymoo's ``Crossover.do`` on arrays: each mating is crossed with
        probability ``prob``, the others pass their parents on."""
        op = self.crossover
        X = self._arrays.X[parents.T]  # (n_parents, n_matings, n_var)
        if op.vtype is not None:
            X = X.astype(op.vtype)
        if self._fast_sbx:
            children = sbx_crossover(op, self.problem, X, self.random_state, self._bounds)
        else:
            children = self._crossover_do(op, X)
        return self._after_operator(op, children)

    def _crossover_do(self, op, X) -> np.ndarray:
        rng = self.random_state
        n_par, n_matings, n_var = X.shape
        n_off = op.n_offsprings
        Xp = np.empty((n_off, n_matings, n_var), dtype=X.dtype)
        cross = rng.random(n_matings) < _scalar(op.prob, n_matings)
        if cross.any():
            Q = op._do(self.problem, X, random_state=rng, algorithm=self)
            Xp[:, cross] = Q[:, cross]
        if n_off == n_par:
            Xp[:, ~cross] = X[:, ~cross]
        else:  # pymoo's per-mating draws, in order
            for k in np.flatnonzero(~cross):
                if n_off < n_par:
                    s = rng.choice(np.arange(n_par), size=n_off, replace=False)
                else:
                    s = []
                    while len(s) < n_off:
                        s.extend(rng.permutation(n_par))
                    s = s[:n_off]
                Xp[:, k] = X[s, k]
        return Xp.reshape(-1, n_var)

    def _mutation(self, X: np.ndarray) -> np.ndarray:
        """pymoo's ``Mutation.do`` on arrays: each individual is mutated with
        probability ``prob``."""
        op, rng = self.mutation, self.random_state
        if self._fast_pm:
            return self._after_operator(op, pm_mutation(op, self.problem, X, rng, self._bounds))
        Xm = op._do(self.problem, X, random_state=rng, algorithm=self)
        mut = rng.random(size=len(X)) <= _scalar(op.prob, len(X))
        out = X.astype(np.result_type(X.dtype, Xm.dtype))
        out[mut] = Xm[mut]
        return self._after_operator(op, out)

    def _repair(self, X: np.ndarray, draws=None) -> np.ndarray:
        """The algorithm's repair, called as pymoo's GA calls it (with the
        random state and the algorithm); given its ``draws`` (see
        :meth:`_variation`), the edge-fixing with them."""
        if draws is not None:
            return self.problem.encoding.edge_fix_drawn(X, draws)
        X = _repair_do(self.repair, self.problem, X, random_state=self.random_state, algorithm=self)
        return self._after_operator(self.repair, X)

    def _new_paths(self, X, seen: _SeenPaths, n_max: int):
        """The first ``n_max`` rows of ``X`` whose decoded path is new (not
        seen, not repeated inside ``X``); adds them to ``seen``."""
        return X[seen.accept(*self._keys(X), n_max)]

    def _evaluate(self, X: np.ndarray, keys=None, hashes=None) -> PathArrays:
        """One vectorised ``problem.evaluate``; counts the evaluations in
        ``algorithm.evaluator.n_eval``. The path ``keys`` of ``X``, when
        known, are given to a problem that ``accepts_profiles`` (see
        :meth:`gapath.problems.GridPathProblem.metrics`), so that each
        path is decoded once."""
        t0 = self.clock()
        kwargs = {}
        if (
            keys is not None
            and getattr(self.problem, "accepts_profiles", False)
            and getattr(self.problem, "requires_kwargs", False)
        ):
            # the paths were decoded for duplicate elimination: not again
            kwargs["profiles"] = _split_keys(keys)
        out = self.problem.evaluate(
            X, return_values_of=list(_CORE_OUTPUTS), return_as_dictionary=True, algorithm=self, **kwargs
        )
        self.evaluator.n_eval += len(X)
        F, G, H = (np.asarray(out[k], dtype=float).reshape(len(X), -1) for k in _CORE_OUTPUTS)
        data = {k: np.asarray(v) for k, v in out.items() if k not in _CORE_OUTPUTS and v is not None}
        arrays = PathArrays(
            X,
            F,
            G,
            H,
            _constraint_violation(G, H),
            np.full(len(X), self.n_iter, np.int64),
            data,
            keys=keys,
            hashes=hashes,
        )
        self._tick("evaluation", t0)
        return arrays

    def _survival(
        self, arrays: PathArrays, n_survive: int, offspring: PathArrays | None = None
    ) -> PathArrays:
        """Elitist survival: the ``n_survive`` best of ``arrays`` (followed
        by ``offspring``, if given) by feasibility, rank, smoothness (when
        the tie-break is on) and crowding, best first, with ``rank`` and
        ``crowding`` set."""
        t0 = self.clock()
        handling = self.constraint_handling
        if offspring is None:
            F, CV, data = arrays.F, arrays.CV, arrays.data
        else:
            F, CV = np.concatenate([arrays.F, offspring.F]), np.concatenate([arrays.CV, offspring.CV])
            data = {
                k: np.concatenate([v, offspring.data[k]])
                for k, v in arrays.data.items()
                if k == "smoothness" and k in offspring.data
            }
        if handling is not None:  # every row ranked on its penalised objectives
            F, CV = handling.penalise(F, CV), np.zeros(len(F))
        feasible = np.flatnonzero(CV <= 0)
        ranks = pareto_ranks(F[feasible])
        t0 = self._tick("sorting", t0)
        smooth = data.get("smoothness") if self.tiebreak is not None else None
        smooth = np.zeros(len(F)) if smooth is None else np.asarray(smooth, dtype=float)
        F = np.ascontiguousarray(F)  # a penalised F may be F-ordered: one kernel specialization
        order, rank, crowding = order_survivors(F, smooth, CV, feasible, ranks, n_survive)
        survivors = arrays.take(order) if offspring is None else arrays.take_merged(offspring, order)
        survivors.rank, survivors.crowding = rank, crowding
        if handling is not None and len(survivors):
            handling.update(float(np.mean(survivors.CV <= 0)))
        self._tick("survival", t0)
        return survivors

    # == initial population ===================================================
    def _sample(self):
        """Initial genomes: sampled, repaired (those not yet evaluated),
        duplicate paths dropped. Returns ``(X, keys, hashes, n_given)``,
        ``n_given`` the number of kept rows that came evaluated in a
        ``Population``."""
        problem, rng, s = self.problem, self.random_state, self.sampling
        if isinstance(s, Population):
            X = s.get("X")
            given = np.array([len(ind.evaluated) > 0 for ind in s], dtype=bool)
        elif isinstance(s, np.ndarray):
            X, given = np.atleast_2d(s), None
        elif isinstance(s, Sampling):
            X = s(problem, self.pop_size, random_state=rng, algorithm=self, to_numpy=True)
            given = None
        else:
            raise ConfigError(
                f"sampling must be a pymoo Sampling, an array or a Population, got {type(s).__name__}"
            )
        t0 = self.clock()
        if given is None:
            X = self._repair(X)
        elif not given.all():
            todo = np.flatnonzero(~given)
            fixed = self._repair(X[todo])
            X = X.astype(np.result_type(X.dtype, fixed.dtype))
            X[todo] = fixed
        t0 = self._tick("repair", t0)
        K, H = self._keys(X)
        keep = ~path_duplicate_mask(K) if self.eliminate_duplicates else np.ones(len(X), bool)
        self._tick("dedupe", t0)
        n_given = 0 if given is None else int(given[keep].sum())
        return X[keep], K[keep], H[keep], n_given

    def _initial_population(self) -> PathArrays:
        X, keys, hashes, n_given = self._sample()
        arrays = self._evaluate(X, keys, hashes)
        self.evaluator.n_eval -= n_given
        return arrays

    # == helpers ==============================================================
    def _tick(self, phase: str, t0: float) -> float:
        t = self.clock()
        self.timings[phase] += t - t0
        return t

    def _keys(self, X):
        """Decoded column profiles of ``X`` (the identity of each path) and
        their hashes."""
        if hasattr(self.problem, "path_keys"):  # free paths: identity rows
            K = np.ascontiguousarray(self.problem.path_keys(X), dtype=np.int64)
            return K, row_hashes(K)
        encoding = self.problem.encoding
        if hasattr(encoding, "decode_keys"):  # the keys in one pass
            K = encoding.decode_keys(X)
            return K, row_hashes(K)
        entries, exits = encoding.decode(X)
        return profile_keys(np.asarray(entries, np.int64), np.asarray(exits, np.int64))

    def _after_operator(self, op, X) -> np.ndarray:
        """What pymoo's ``Operator.__call__`` does after ``do``: cast to the
        operator's ``vtype``, then apply its own repair (e.g. rounding)."""
        if op.vtype is not None:
            X = X.astype(op.vtype, copy=False)
        if op.repair is not None:
            X = _repair_do(op.repair, self.problem, X)
        return X

    def _from_population(self, pop) -> PathArrays:
        """:class:`PathArrays` of an evaluated pymoo population."""
        X = pop.get("X")
        F, G, H, CV = (
            np.asarray(pop.get(k), dtype=float).reshape(len(pop), -1) for k in ("F", "G", "H", "CV")
        )
        skip = ("rank", "crowding", "n_gen", "n_iter")
        names = [k for k in (pop[0].data if len(pop) else ()) if k not in skip]
        data = {k: np.array([ind.data[k] for ind in pop]) for k in names if all(k in ind.data for ind in pop)}
        n_gen = np.array([ind.data.get("n_gen") or self.n_iter or 1 for ind in pop], np.int64)
        return PathArrays(X, F, G, H, CV[:, 0], n_gen, data)

    # == pymoo plumbing =======================================================
    @property
    def arrays(self) -> PathArrays | None:
        """The current population as :class:`PathArrays` (no copy, nothing
        built: what a callback should read, e.g. through
        :func:`gapath.callbacks.population_arrays`, instead of ``pop``)."""
        return self._arrays

    @property
    def pop(self) -> Population | None:
        """The current population as a pymoo ``Population`` (built on first
        access after each generation). Assigning one replaces this view until
        the next generation; the engine keeps working on its arrays."""
        if self._pop is None and self._arrays is not None:
            self._pop = self._arrays.to_population()
        return self._pop

    @pop.setter
    def pop(self, value):
        self._pop = value

    @property
    def opt(self) -> Population | None:
        """The feasible rank-0 individuals (or the least infeasible one)."""
        if self._opt is None and self._opt_idx is not None:
            if self._pop is not None:
                self._opt = self._pop[self._opt_idx]
            else:
                self._opt = self._arrays.take(self._opt_idx).to_population()
        return self._opt

    @opt.setter
    def opt(self, value):
        self._opt = value
        if value is None:
            self._opt_idx = None

    @property
    def off(self) -> Population | None:
        """The offspring of the last generation."""
        if self._off is None and self._offspring is not None:
            self._off = self._offspring.to_population()
        return self._off

    @off.setter
    def off(self, value):
        self._off = value

    def _set_arrays(self, arrays: PathArrays | None, offspring: PathArrays | None) -> None:
        self._arrays, self._offspring = arrays, offspring
        self._pop = self._opt = self._off = None

    def _default_operators(self, encoding: str) -> None:
        """Fill the operators not given with ``encoding``'s defaults."""
        ops = default_operators(encoding, **self.operator_settings)
        for name in ("sampling", "crossover", "mutation"):
            if getattr(self, name) is None:
                setattr(self, name, ops[name])

    def setup(self, problem, **kwargs):
        """pymoo's ``setup``, after checking that ``problem`` is a gapath path
        problem (of the algorithm's encoding, when one was given), taking
        the operators not given from its encoding, and choosing the output
        (multi- or single-objective)."""
        _check_problem(problem)
        used = getattr(problem.encoding, "name", None)
        if self.encoding is not None and used is not None and used != self.encoding:
            raise ConfigError(
                f"FastNSGA2 was configured for the {self.encoding!r} encoding but the problem "
                f"uses {used!r}; pass FastNSGA2(..., encoding={used!r})"
            )
        self._default_operators(used or self.encoding or "integer")
        if self.output is None:
            self.output = MultiObjectiveOutput() if problem.n_obj > 1 else SingleObjectiveOutput()
        return super().setup(problem, **kwargs)

    def _setup(self, problem, **kwargs):
        self.timings = dict.fromkeys(PHASES, 0.0)
        if self.constraint_handling is not None:
            self.constraint_handling.reset()
        self._fast_sbx = self.fast_operators and sbx_supported(self.crossover)
        self._fast_pm = self.fast_operators and pm_supported(self.mutation, problem)
        self._fast_discrete = self.fast_operators and discrete_supported(
            self.crossover, self.mutation, problem
        )
        self._bounds = (np.asarray(problem.xl, dtype=float), np.asarray(problem.xu, dtype=float))
        # EdgeFixingRepair's first act is encoding.edge_fix's draw of one
        # number per gene: drawn with the mutation's last, in one call
        self._drawn_repair = (
            self._fast_discrete
            and type(self.repair) is EdgeFixingRepair
            and self.repair.vtype is None
            and getattr(self.repair, "repair", None) is None
            and hasattr(getattr(problem, "encoding", None), "edge_fix_drawn")
        )

    def _initialize(self):
        super()._initialize()
        self._set_arrays(None, None)
        self._opt_idx = None

    def _set_optimum(self):
        A = self._arrays
        self._opt = None
        if A is None or len(A) == 0:
            self._opt_idx = None
        elif (A.CV <= 0).any():
            if self.constraint_handling is None:
                self._opt_idx = np.flatnonzero(A.rank == 0)
            else:  # ranks mix feasible and infeasible rows: the feasible non-dominated
                feasible = np.flatnonzero(A.CV <= 0)
                self._opt_idx = feasible[pareto_ranks(A.F[feasible]) == 0]
        else:
            self._opt_idx = np.array([np.argmin(A.CV)])

    # ask-and-tell: pymoo's Algorithm.next/ask/tell evaluate Populations
    def _initialize_infill(self):
        return Population.new("X", self._sample()[0])

    def _initialize_advance(self, infills=None, **kwargs):
        offspring = self._from_population(infills)
        self._set_arrays(self._survival(offspring, len(offspring)), offspring)

    def _infill(self):
        X = self._mating(self.n_offsprings)[0]
        if len(X) == 0:
            self.termination.force_termination = True
            return None
        return Population.new("X", X)

    def _advance(self, infills=None, **kwargs):
        offspring = None if infills is None else self._from_population(infills)
        self._set_arrays(self._survival(self._arrays, self.pop_size, offspring), offspring)
