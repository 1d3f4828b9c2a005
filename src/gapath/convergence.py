"""Convergence of a GA run towards an exact reference front.

:class:`HypervolumeRatioCallback` is a pymoo ``Callback`` that records, each
generation, the hypervolume ratio (:func:`gapath.metrics.hv_ratio`, SPEC
normalisation) of the population's feasible non-dominated unpenalised
objective vectors against a reference front, typically
:func:`gapath.planners.exact.monotone_front` (the best the column-monotone
encodings can reach) or :func:`gapath.planners.exact.free_front`.
:func:`plot_convergence` draws such a history.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from pymoo.core.callback import Callback

from gapath._convergence_kernels import dominated_by
from gapath.callbacks import population_arrays
from gapath.errors import ConfigError
from gapath.metrics import TOL, hypervolume, nondominated, normalisation_bounds
from gapath.operators.archive import run_archive

__all__ = ["HypervolumeRatioCallback", "plot_convergence"]

#: Column names of :attr:`HypervolumeRatioCallback.history` rows.
HISTORY_COLUMNS = ("n_gen", "n_eval", "hv_ratio")


def _population_front(algorithm, problem) -> np.ndarray:
    """The feasible, non-dominated (SPEC tolerance), unpenalised objective
    vectors of the algorithm's current population (read with
    :func:`gapath.callbacks.population_arrays`: no pymoo ``Population`` is
    built from :class:`gapath.algorithms.FastNSGA2`), or of the run's
    :class:`gapath.operators.archive.FreePathArchive` when it has one (the
    front :func:`gapath.solver.solve` returns)."""
    archive = run_archive(algorithm) if problem is None else None
    if archive is not None:
        return archive.F
    A = population_arrays(algorithm)
    if A is None or len(A) == 0:
        return np.zeros((0, 0))
    if problem is not None:
        from gapath.front import path_front

        return path_front(problem, A.X).F
    # penalty mode adds penalty * interfering: nothing on the feasible rows
    F = np.asarray(A.F, dtype=float)[A.feasible]
    return F[_nondominated_tol(F)] if len(F) else F


def _dominated_by(B, A, tol) -> np.ndarray:
    """For each row of ``B``: is it dominated up to ``tol`` by a row of
    ``A``? The test of :func:`gapath.metrics.nondominated`, pair by pair
    (a numba loop; ``B`` and ``A`` finite)."""
    B = np.ascontiguousarray(B, dtype=float)
    A = np.ascontiguousarray(A, dtype=float)
    if len(A) == 0 or len(B) == 0:
        return np.zeros(len(B), bool)
    return dominated_by(B, A, float(tol))


def _nondominated_tol(F, tol: float = TOL) -> np.ndarray:
    """``nondominated(F, tol=tol)`` (the same indices) without comparing
    every pair: a row not dominated by any row is in particular not
    dominated by a row of the exact front, so the rows that survive the
    exact front are the only candidates, each then checked against all
    rows. About n x (front + candidates) comparisons instead of n x n (a
    population of 500 every generation)."""
    F = np.asarray(F, dtype=float)
    if len(F) <= 64 or not np.isfinite(F).all():
        return nondominated(F, tol=tol)
    candidates = np.flatnonzero(~_dominated_by(F, F[nondominated(F)], tol))
    return candidates[~_dominated_by(F[candidates], F, tol)]


class HypervolumeRatioCallback(Callback):
    """Record the hypervolume ratio of the population against a reference
    front, every generation.

    Each generation (pymoo calls the callback after the initial population
    and after every survival) the callback takes the current population's
    feasible individuals (``interfering == 0``), their unpenalised objective
    vectors and the non-dominated ones among them (SPEC tolerance), and
    appends ``(n_gen, n_eval, hv_ratio)`` to :attr:`history`, ``hv_ratio``
    being :func:`gapath.metrics.hv_ratio` against the reference front (0.0
    while no individual is feasible).

    Parameters
    ----------
    reference : (k, m) array_like or ExactFront
        The reference front (e.g. :func:`gapath.planners.exact.monotone_front`).
        An object with ``objectives`` (an :class:`~gapath.planners.exact.ExactFront`)
        has its columns reordered to the problem's objective order.
    problem : GridPathProblem, optional
        When given, the population's genomes are decoded and re-evaluated
        with :func:`gapath.front.path_front` (exact, slower). By default the
        population's own columns are used
        (:func:`gapath.callbacks.population_arrays`: the engine's arrays
        for :class:`~gapath.algorithms.FastNSGA2`, the individuals' values
        for stock pymoo algorithms): ``F`` and ``interfering`` (``F`` minus
        ``penalty * interfering`` in penalty mode, which is ``F`` itself on
        feasible individuals); without an ``interfering`` column,
        ``CV <= 0`` marks the feasible ones.

    Attributes
    ----------
    history : list of (int, int, float)
        ``(n_gen, n_eval, hv_ratio)`` rows, one per generation.
    ideal, nadir : (m,) float arrays
        The reference front's normalisation bounds.

    Raises
    ------
    ConfigError
        If the reference front is empty, or its objectives do not match the
        problem's (checked when the run starts).

    See Also
    --------
    plot_convergence : draws :attr:`history`.
    gapath.metrics.hv_ratio : the indicator.

    Examples
    --------
    >>> from pymoo.optimize import minimize
    >>> from gapath import default_workspace
    >>> from gapath.algorithms import paper_nsga2
    >>> from gapath.planners.exact import monotone_front
    >>> from gapath.problems import GridPathProblem
    >>> ws = default_workspace()
    >>> cb = HypervolumeRatioCallback(monotone_front(ws))
    >>> res = minimize(GridPathProblem(ws), paper_nsga2(40), ("n_gen", 3), seed=1,
    ...                callback=cb)
    >>> [row[0] for row in cb.history]
    [1, 2, 3]
    >>> all(0.0 <= row[2] <= 1.0 + 1e-9 for row in cb.history)
    True
    """

    def __init__(self, reference, problem=None):
        super().__init__()
        self.reference = reference
        self.problem = problem
        self.history: list[tuple[int, int, float]] = []
        self._last = None  # (front, ratio) of the last generation
        R = np.asarray(getattr(reference, "F", reference), dtype=float)
        if R.ndim != 2 or len(R) == 0:
            raise ConfigError(f"the reference front must be a non-empty (k, m) array, got shape {R.shape}")
        self._R = R
        self._set_bounds()

    def _set_bounds(self):
        self.ideal, self.nadir = normalisation_bounds(self._R)
        self._hv_ref = hypervolume(self._R, self.ideal, self.nadir)
        self._last = None

    def initialize(self, algorithm):
        problem = self.problem if self.problem is not None else algorithm.problem
        names = getattr(problem, "objectives", None)
        ref_names = getattr(self.reference, "objectives", None)
        if names is not None and ref_names is not None and tuple(ref_names) != tuple(names):
            if sorted(ref_names) != sorted(names):
                raise ConfigError(
                    f"the reference front's objectives {tuple(ref_names)} differ "
                    f"from the problem's {tuple(names)}"
                )
            self._R = self._R[:, [list(ref_names).index(n) for n in names]]
            self._set_bounds()
        n_obj = getattr(problem, "n_obj", self._R.shape[1])
        if n_obj != self._R.shape[1]:
            raise ConfigError(f"the reference front has {self._R.shape[1]} objectives, the problem {n_obj}")

    def notify(self, algorithm):
        F = _population_front(algorithm, self.problem)
        last = self._last
        if last is not None and last[0].shape == F.shape and np.array_equal(last[0], F):
            ratio = last[1]  # the same front as last generation (elitism): same value
        else:
            ratio = hypervolume(F, self.ideal, self.nadir) / self._hv_ref if len(F) else 0.0
            self._last = (F.copy(), ratio)
        self.history.append((int(algorithm.n_gen), int(algorithm.evaluator.n_eval), float(ratio)))

    def to_array(self) -> np.ndarray:
        """:attr:`history` as an ``(n, 3)`` float array (columns
        :data:`HISTORY_COLUMNS`)."""
        return np.array(self.history, dtype=float).reshape(-1, 3)


def plot_convergence(history, path_or_ax, *, x="n_eval", label=None, title=None):
    """Plot a hypervolume-ratio history.

    Parameters
    ----------
    history : HypervolumeRatioCallback, or (n, 3) array_like
        ``(n_gen, n_eval, hv_ratio)`` rows.
    path_or_ax : str, path-like or matplotlib Axes
        A file to write (any format matplotlib knows from the extension,
        rendered with the Agg backend, no screen needed) or an Axes to draw
        on (e.g. to overlay several runs).
    x : {"n_eval", "n_gen"}, optional
        The horizontal axis (default evaluations).
    label : str, optional
        Legend label of the curve.
    title : str, optional
        Title (default "convergence"); only used when writing a file.

    Returns
    -------
    pathlib.Path or Axes
        The file written, or the Axes drawn on.

    Raises
    ------
    ConfigError
        If ``x`` is not one of the two names or the history is not ``(n, 3)``.

    Examples
    --------
    >>> plot_convergence([(1, 40, 0.5), (2, 80, 0.8)], "convergence.png")  # doctest: +SKIP
    PosixPath('convergence.png')
    """
    if x not in ("n_gen", "n_eval"):
        raise ConfigError(f"x must be 'n_gen' or 'n_eval', got {x!r}")
    H = history.to_array() if hasattr(history, "to_array") else np.asarray(history, dtype=float)
    if H.size == 0:
        H = H.reshape(0, 3)
    if H.ndim != 2 or H.shape[1] != 3:
        raise ConfigError(f"history must be (n_gen, n_eval, hv_ratio) rows, got shape {H.shape}")
    xs = H[:, HISTORY_COLUMNS.index(x)]

    def draw(ax):
        ax.plot(xs, H[:, 2], marker="." if len(H) < 60 else None, label=label)
        ax.axhline(1.0, color="0.5", lw=0.8, ls="--")
        ax.set_xlabel("evaluations" if x == "n_eval" else "generation")
        ax.set_ylabel("hypervolume ratio")
        ax.set_ylim(bottom=0.0)
        if label is not None:
            ax.legend(fontsize=8)

    if hasattr(path_or_ax, "plot"):
        draw(path_or_ax)
        return path_or_ax
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(5.5, 3.8))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    draw(ax)
    ax.set_title(title or "convergence")
    fig.tight_layout()
    path = Path(path_or_ax)
    fig.savefig(path)
    return path
