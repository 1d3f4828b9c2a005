"""What the per-generation callbacks read, and the progress bar.

A pymoo callback is called after every generation. What gapath's callbacks
(:class:`ProgressBar`, :class:`gapath.convergence.HypervolumeRatioCallback`,
:class:`gapath.experiments.runner.FirstFeasible`) need from the population
is a few columns: objectives, constraint violation, rank, the ``smoothness``
and ``interfering`` of each path. :func:`population_arrays` is the one place
that reads them:

* from :class:`gapath.algorithms.FastNSGA2`, the engine's own arrays
  (:attr:`~gapath.algorithms.FastNSGA2.arrays`): no pymoo ``Population``
  nor ``Individual`` is built (``algorithm.pop`` would build one of 500
  individuals every generation, which costs more than the generation);
* from any other pymoo algorithm, its ``pop`` (which pymoo keeps anyway),
  one column at a time and only the columns asked for.
"""

from __future__ import annotations

import numpy as np
from pymoo.core.callback import Callback
from tqdm import tqdm  # the text bar (tqdm.auto warns in kernels without ipywidgets)

from gapath.algorithms.fast_nsga2 import PathArrays
from gapath.operators.columns import column

__all__ = ["Callbacks", "PopulationArrays", "ProgressBar", "population_arrays", "population_status"]


class PopulationArrays:
    """Columns of an algorithm's current population as NumPy arrays, one
    row per individual (see :func:`population_arrays`).

    Each column is read on first access and kept; a column the population
    does not have is None. From :class:`gapath.algorithms.FastNSGA2` the
    columns are the engine's own arrays, not copies: read them, do not
    write to them.

    Attributes
    ----------
    X : (n, n_var) genomes.
    F : (n, n_obj) objectives (penalised in penalty mode, as the algorithm
        sees them).
    G : (n, n_ieq) inequality constraints (may have 0 columns).
    CV : (n,) constraint violation.
    rank : (n,) non-dominated rank set by the survival, or None.
    smoothness, interfering : (n,) per-path outputs of a
        :class:`gapath.problems.GridPathProblem`, or None.
    feasible : (n,) bool: no interfering cell (``interfering == 0``), or
        ``CV <= 0`` for a problem without ``interfering``.
    """

    def __init__(self, n: int, read):
        self._n = int(n)
        self._read = read
        self._columns: dict = {}

    def __len__(self) -> int:
        return self._n

    def _get(self, name: str):
        if name not in self._columns:
            self._columns[name] = self._read(name) if self._n else None
        return self._columns[name]

    X = property(lambda self: self._get("X"))
    F = property(lambda self: self._get("F"))
    G = property(lambda self: self._get("G"))
    CV = property(lambda self: self._get("CV"))
    rank = property(lambda self: self._get("rank"))
    smoothness = property(lambda self: self._get("smoothness"))
    interfering = property(lambda self: self._get("interfering"))

    @property
    def feasible(self) -> np.ndarray:
        if self._n == 0:
            return np.zeros(0, bool)
        interfering = self.interfering
        if interfering is not None:
            return np.asarray(interfering) == 0
        return np.asarray(self.CV) <= 0


def _engine_reader(A: PathArrays):
    def read(name):
        if name in ("X", "F", "G", "CV"):
            return getattr(A, name)
        if name == "rank":
            return A.rank
        return A.data.get(name)

    return read


def _population_reader(pop):
    def read(name):
        values = column(pop, name)
        if values is None:
            return None
        if name == "CV":
            return np.asarray(values, dtype=float).reshape(len(pop), -1)[:, 0]
        if name in ("F", "G"):
            return np.asarray(values, dtype=float).reshape(len(pop), -1)
        return values

    return read


def population_arrays(algorithm) -> PopulationArrays | None:
    """The current population of ``algorithm`` as arrays.

    For :class:`gapath.algorithms.FastNSGA2` the columns are the engine's
    arrays (no pymoo ``Population`` is built); for other pymoo algorithms
    they are read from ``algorithm.pop``, only those asked for.

    Parameters
    ----------
    algorithm : a pymoo ``Algorithm`` (as passed to a callback).

    Returns
    -------
    PopulationArrays or None
        None before the first population.

    Examples
    --------
    >>> from pymoo.optimize import minimize
    >>> from gapath import default_workspace
    >>> from gapath.algorithms import FastNSGA2
    >>> from gapath.problems import GridPathProblem
    >>> res = minimize(GridPathProblem(default_workspace()), FastNSGA2(20), ("n_gen", 2), seed=1)
    >>> A = population_arrays(res.algorithm)
    >>> len(A), A.F.shape, A.feasible.dtype
    (20, (20, 2), dtype('bool'))
    """
    A = getattr(algorithm, "arrays", None)
    if isinstance(A, PathArrays):
        return PopulationArrays(len(A), _engine_reader(A))
    pop = getattr(algorithm, "pop", None)
    if pop is None:
        return None
    return PopulationArrays(len(pop), _population_reader(pop))


def population_status(algorithm, arrays: PopulationArrays | None = None) -> dict:
    """Generation, feasible count, front size and best unpenalised value
    per objective of the algorithm's current population.

    Parameters
    ----------
    algorithm : a pymoo ``Algorithm``.
    arrays : its :func:`population_arrays`, when already read.

    Returns
    -------
    dict
        ``gen``, ``feasible`` (paths without interfering cells), ``front``
        (feasible paths of rank 0) and, when a path is feasible, one entry
        per objective of the problem: the smallest value among the feasible
        paths (unpenalised: a feasible path has no penalty).

    Examples
    --------
    >>> from gapath import default_workspace
    >>> from gapath.solver import solve
    >>> r = solve(default_workspace(), pop_size=20, n_gen=2)
    >>> sorted(population_status(r.pymoo_result.algorithm))
    ['feasible', 'front', 'gen', 'length', 'vulnerability']
    """
    A = population_arrays(algorithm) if arrays is None else arrays
    status = {"gen": int(algorithm.n_gen), "feasible": 0, "front": 0}
    if A is None or len(A) == 0:
        return status
    feasible = A.feasible
    status["feasible"] = int(feasible.sum())
    rank = A.rank
    status["front"] = int(((np.asarray(rank) == 0) & feasible).sum()) if rank is not None else 0
    if feasible.any():
        names = getattr(algorithm.problem, "objectives", None)
        F = np.asarray(A.F)[feasible]
        if names is None:
            names = [f"f{i + 1}" for i in range(F.shape[1])]
        for name, v in zip(names, F.min(axis=0)):
            status[name] = float(v)
    return status


class Callbacks(Callback):
    """Several pymoo callbacks called in turn, each in full (``notify`` and
    ``update``; pymoo's ``CallbackCollection`` only calls ``update``)."""

    def __init__(self, *callbacks: Callback):
        super().__init__()
        self.callbacks = tuple(cb for cb in callbacks if cb is not None)

    def notify(self, algorithm):
        for cb in self.callbacks:
            cb(algorithm)


def _redraw_due(bar, n: int) -> bool:
    """Whether tqdm will redraw ``bar`` when its count becomes ``n`` (its
    own test in ``tqdm.update``: ``miniters`` steps and ``mininterval``
    seconds since the last drawing)."""
    try:
        return n - bar.last_print_n >= bar.miniters and bar._time() - bar.last_print_t >= bar.mininterval
    except AttributeError:  # another tqdm: read the status every time
        return True


class ProgressBar(Callback):
    """tqdm bar over generations showing :func:`population_status`.

    The status is read (from the engine's arrays, see
    :func:`population_arrays`) only when the bar is about to be redrawn
    (tqdm's ``mininterval``, 0.25 s) and at the last generation, so the bar
    costs next to nothing per generation.

    Parameters
    ----------
    n_gen : total number of generations (the bar's length).
    disable : no output at all (still tracks the generation).
    **tqdm_kwargs : passed to ``tqdm`` (e.g. ``file``, ``mininterval``).

    Attributes
    ----------
    last_gen : the last generation notified.
    status : the last :func:`population_status` shown (None before the
        first); after :meth:`close`, that of the last generation.

    Examples
    --------
    >>> import io
    >>> from gapath import default_workspace
    >>> from gapath.solver import solve
    >>> bar = ProgressBar(3, file=io.StringIO())
    >>> r = solve(default_workspace(), pop_size=20, n_gen=3, callback=bar)
    >>> bar.close()
    >>> bar.last_gen, bar.status["gen"]
    (3, 3)
    """

    def __init__(self, n_gen: int, disable: bool = False, **tqdm_kwargs):
        super().__init__()
        self.n_gen = n_gen
        self.disable = disable
        self.tqdm_kwargs = dict(mininterval=0.25, unit="gen", dynamic_ncols=True)
        self.tqdm_kwargs.update(tqdm_kwargs)
        self.bar = None
        self.last_gen = 0
        self.status = None
        self._algorithm = None

    def _show(self, algorithm) -> None:
        s = self.status = population_status(algorithm)
        s["gen"] = self.last_gen  # pymoo counts on after the last notification
        self.bar.set_postfix_str(
            f"feasible={s['feasible']} front={s['front']}"
            + "".join(f" {k}={v:.4g}" for k, v in s.items() if k not in ("gen", "feasible", "front")),
            refresh=False,
        )

    def notify(self, algorithm):
        self.last_gen = int(algorithm.n_gen)
        if self.disable:
            return
        bar = self.bar
        if bar is None:
            bar = self.bar = tqdm(total=self.n_gen, **self.tqdm_kwargs)
            self._show(algorithm)
        elif not bar.disable and (self.last_gen >= self.n_gen or _redraw_due(bar, self.last_gen)):
            self._show(algorithm)
        self._algorithm = algorithm
        bar.update(self.last_gen - bar.n)

    def close(self):
        """Show the last generation's status and close the bar."""
        if self.bar is not None:
            if self._algorithm is not None and (self.status is None or self.status["gen"] != self.last_gen):
                self._show(self._algorithm)
            self.bar.close()
            self.bar = None
        self._algorithm = None
