"""The grid path problem as a vectorised pymoo ``Problem``."""

from __future__ import annotations

import warnings

import numpy as np
from pymoo.core.problem import Problem

from gapath.encodings import expand_profiles, make_encoding, split_paths
from gapath.errors import ConfigError, NoPathError
from gapath.monotone import Frame
from gapath.objectives import (
    INTERFERING,
    OBJECTIVE_NAMES,
    OBJECTIVES,
    SMOOTHNESS,
    check_objective_names,
    objective_index,
)
from gapath.planners import exact
from gapath.workspace import Workspace

CONSTRAINT_MODES = ("penalty", "constraint")

#: :meth:`GridPathProblem.pareto_front` computes the exact front on its own
#: (also when pymoo's verbose output asks for it) up to this many cells in the
#: problem's frame; a larger workspace needs ``pareto_front(force=True)``.
EXACT_FRONT_AUTO_CELLS = 32 * 32


class GenomeWarning(UserWarning):
    """Genomes given to a :class:`GridPathProblem` do not fit its encoding
    (non-integral genes for an integer encoding): stock float operators are
    probably at work. Issued once per problem."""


def problem_settings(objectives, constraints, penalty, costmap=None):
    """The checked settings of a grid path problem (monotone or free): the
    objective names, the costmap layer objectives among them, each
    objective's column in the metrics matrix (:data:`OBJECTIVES`, then the
    layers) and the penalty as a float.

    Raises
    ------
    ConfigError
        On an unknown or repeated objective, an unknown constraint mode, or a
        penalty that is not a finite number >= 0.
    """
    names = objectives.split(",") if isinstance(objectives, str) else list(objectives)
    names = [n.strip() for n in names]
    check_objective_names(
        names, () if costmap is None else costmap.objective_names + costmap.max_objective_names
    )
    # layer objectives: metrics columns 4, 5, ... (after OBJECTIVES)
    layers = tuple(n for n in names if n not in OBJECTIVE_NAMES)
    base = [n for n in names if n in OBJECTIVE_NAMES]
    if base or not names:
        objective_index(base)  # "at least one", "given twice"
    if len(set(layers)) != len(layers):
        dup = next(n for n in layers if names.count(n) > 1)
        raise ConfigError(f"objective {dup!r} is given twice")
    columns = [
        OBJECTIVES.index(n) if n in OBJECTIVE_NAMES else len(OBJECTIVES) + layers.index(n) for n in names
    ]
    if constraints not in CONSTRAINT_MODES:
        raise ConfigError(
            f"unknown constraint handling {constraints!r}; expected one of {', '.join(CONSTRAINT_MODES)}"
        )
    try:
        penalty = float(penalty)
    except (TypeError, ValueError):
        raise ConfigError(f"penalty must be a number >= 0, got {penalty!r}") from None
    if not np.isfinite(penalty) or penalty < 0:
        raise ConfigError(f"penalty must be a number >= 0, got {penalty!r}")
    return tuple(names), layers, columns, penalty


class GridPathProblem(Problem):
    """Multi-objective path planning over column-monotone paths.

    Each row of ``X`` is a genome of the chosen encoding; evaluation decodes
    the whole population at once and runs the numba objective kernel (no
    per-individual Python code).

    Parameters
    ----------
    workspace : :class:`gapath.Workspace`.
    objectives : names among ``length``, ``vulnerability``, ``smoothness``
        (a sequence or a comma-separated string) and, with ``costmap``, the
        costmap's layer objectives (``elevation``, ``solar``, ``risk``, user
        layers; see :mod:`gapath.costmap`).
    encoding : ``"integer"`` (default), ``"binary"``, ``"mixed"`` or
        ``"absolute"`` (see :data:`gapath.encodings.ENCODINGS`).
    constraints : ``"penalty"`` (Ahmed & Deb's default: every objective gets
        ``penalty * interfering`` added) or ``"constraint"`` (``interfering``
        is returned as the inequality constraint ``G``; feasible when 0).
    penalty : penalty per interfering cell (default 1000).
    costmap : :class:`gapath.costmap.Costmap`, optional. Its layer objectives
        are computed by :func:`gapath.costmap.evaluate_layer_profiles` over
        the decoded column profiles (mean over the path's cells for cell
        layers, maximum over them for ``<layer>_max``, sum over the steps
        for ``solar``); they get the same penalty
        as the other objectives.

    Raises
    ------
    ConfigError
        On an unknown objective, encoding or constraint mode, or a negative
        penalty.

    Warns
    -----
    GenomeWarning
        Once per problem, the first time genomes with non-integral genes are
        evaluated under an integer encoding (``integer``, ``mixed``,
        ``absolute``). Decoding rounds them, but it means float operators
        (pymoo's default ``FloatRandomSampling``, ``SBX``, ``PM``) are in use:
        they draw moves uniformly over the whole grid height, and nearly every
        path they make crosses obstacles. gapath's operators
        (:func:`gapath.algorithms.paper_nsga2`,
        :func:`gapath.operators.default_operators`) never trigger it.

    Notes
    -----
    Outputs: ``F`` (N, n_obj); ``G`` (N, 1) in constraint mode; per individual also
    ``smoothness`` (total turn, radians) and ``interfering`` (count), kept by
    pymoo on the individuals (``pop.get("smoothness")``).

    :meth:`pareto_front` gives the exact front of the problem's path set (see
    there), so pymoo's indicators (``IGD``, ``GD``, ``HV``) and its verbose
    output work with it.

    Examples
    --------
    >>> from gapath import default_workspace
    >>> problem = GridPathProblem(default_workspace())
    >>> problem.n_var, problem.n_obj
    (31, 2)
    """

    def __init__(
        self,
        workspace,
        objectives=("length", "vulnerability"),
        encoding="integer",
        constraints="penalty",
        penalty=1000.0,
        costmap=None,
        **kwargs,
    ):
        if not isinstance(workspace, Workspace):
            raise ConfigError(
                f"GridPathProblem expects a gapath.Workspace, got {type(workspace).__name__}; "
                f"build one from an array with gapath.loaders.from_array(array, start, goal) "
                f"(or gapath.Workspace(occ, start, goal))"
            )
        self.objectives, self.layer_objectives, self._obj_idx, penalty = problem_settings(
            objectives, constraints, penalty, costmap
        )
        self.workspace = workspace
        self.frame = Frame.of(workspace)
        self.costmap = costmap
        self._layers = (
            costmap.profile_evaluator(self.frame, self.layer_objectives) if self.layer_objectives else None
        )
        self.encoding = make_encoding(encoding, self.frame)
        self.constraints = constraints
        self.penalty = penalty
        # pymoo passes evaluate()'s keyword arguments (``profiles``) through
        kwargs.setdefault("requires_kwargs", True)
        super().__init__(
            n_var=self.encoding.n_var,
            n_obj=len(self.objectives),
            n_ieq_constr=1 if constraints == "constraint" else 0,
            xl=self.encoding.xl,
            xu=self.encoding.xu,
            vtype=self.encoding.vtype,
            **kwargs,
        )
        self._exact_front = None  # ExactFront or the NoPathError, once computed
        self._genome_warned = self.encoding.vtype is not int  # only integer genomes checked

    # -- evaluation --------------------------------------------------------
    #: :meth:`evaluate` takes ``profiles=(entries, exits)``, the decoded
    #: genomes (e.g. from :class:`gapath.algorithms.FastNSGA2`'s duplicate
    #: elimination), so that they are not decoded again.
    accepts_profiles = True

    def metrics(self, X, profiles=None) -> np.ndarray:
        """All per-path metrics ``(N, 4)`` in :data:`gapath.objectives.OBJECTIVES`
        order (length, vulnerability, smoothness, interfering), unpenalised;
        with layer objectives, ``(N, 4 + k)``: their values follow, in the
        order of :attr:`layer_objectives`.

        Parameters
        ----------
        X : (N, n_var) genomes.
        profiles : (entries, exits), optional
            ``self.encoding.decode(X)`` when the caller has it already
            (two ``(N, n_cols)`` int64 arrays); default: decode ``X``.

        Returns
        -------
        (N, 4 + k) float array.

        Raises
        ------
        ConfigError
            If ``profiles`` does not have one row of ``n_cols`` per genome.

        Examples
        --------
        >>> import numpy as np
        >>> from gapath import default_workspace
        >>> problem = GridPathProblem(default_workspace())
        >>> X = np.zeros((2, problem.n_var), int)
        >>> M = problem.metrics(X)
        >>> M.shape, np.array_equal(M, problem.metrics(X, profiles=problem.encoding.decode(X)))
        ((2, 4), True)
        """
        if profiles is None:
            entries, exits = self.encoding.decode(X)
        else:
            entries, exits = profiles
            shape = (len(X), self.frame.n_cols)
            if entries.shape != shape or exits.shape != shape:
                raise ConfigError(
                    f"profiles must be two {shape} arrays (entries, exits) of the "
                    f"genomes, got {entries.shape} and {exits.shape}"
                )
        M = self.frame.evaluate(entries, exits)
        if self._layers is not None:
            M = np.hstack([M, self._layers(entries, exits)])
        return M

    def _evaluate(self, X, out, *args, profiles=None, **kwargs):
        M = self.metrics(X, profiles)
        F = M[:, self._obj_idx]
        interfering = M[:, INTERFERING]
        if self.constraints == "penalty":
            F = F + self.penalty * interfering[:, None]
        else:
            out["G"] = interfering[:, None]
        out["F"] = F
        out["smoothness"] = M[:, SMOOTHNESS]
        out["interfering"] = interfering

    def _evaluate_vectorized(self, X, out, *args, **kwargs):
        if not self._genome_warned:
            self._check_genes(X)
        super()._evaluate_vectorized(X, out, *args, **kwargs)

    def _check_genes(self, X) -> None:
        """Warn (once) when an integer encoding gets non-integral genes."""
        X = np.asarray(X)
        if X.dtype.kind != "f":  # integer and bool genomes are integral
            return
        bad = np.rint(X) != X  # NaN is never integral either
        if not bad.any():
            return
        self._genome_warned = True
        rows = bad.any(axis=1) if bad.ndim == 2 else bad
        example = float(X[bad][0])
        warnings.warn(
            f"GridPathProblem ({self.encoding.name} encoding) evaluated {int(rows.sum())} of "
            f"{len(rows)} genomes with non-integral genes (e.g. {example:.6g}): float operators "
            "(pymoo's default FloatRandomSampling, SBX, PM) are at work; the genes are rounded, "
            "but these operators give almost only paths through obstacles. Use "
            "gapath.algorithms.paper_nsga2() or FastNSGA2(), or the operators of "
            f"gapath.operators.default_operators({self.encoding.name!r}). "
            "(Warned once per problem.)",
            GenomeWarning,
            stacklevel=2,
        )

    # -- reference front -----------------------------------------------------
    def pareto_front(self, *args, force: bool = False, **kwargs) -> np.ndarray:
        """The exact Pareto front of the problem's path set, for pymoo.

        The objective vectors ``(k, n_obj)`` of the feasible column-monotone
        paths that no other such path dominates, in the problem's objective
        order and unpenalised (feasible paths carry no penalty, so they are
        also the ``F`` pymoo sees for those paths, in either constraint mode),
        sorted by the first objective. Computed on the first call by
        :func:`gapath.planners.exact.monotone_front` and cached on the
        problem (and pickled with it); a copy is returned. pymoo's ``IGD``,
        ``GD`` and ``HV`` take it as their ``pf``, and with ``verbose=True``
        pymoo's output shows them per generation.

        The integer, mixed and absolute encodings describe exactly the
        monotone path set. The binary one also has horizontal-then-vertical
        transitions; with corner cutting allowed each of them is dominated
        by the diagonal transition to the same row (shorter, a subset of its
        cells, no larger turn), so the front is the same; without corner
        cutting it may not be, and no front is given.

        Parameters
        ----------
        force : compute it also when the frame has more than
            :data:`EXACT_FRONT_AUTO_CELLS` cells (see Notes).
        *args, **kwargs : accepted for pymoo's signature, ignored.

        Returns
        -------
        (k, n_obj) float array.

        Raises
        ------
        ConfigError
            If the problem has costmap layer objectives (the exact planners
            do not know them), if it uses the binary encoding without corner
            cutting, or if the workspace is larger than
            :data:`EXACT_FRONT_AUTO_CELLS` cells and ``force`` is not set.
            pymoo's output catches the error and shows its front-free
            columns instead.
        NoPathError
            If no feasible column-monotone path exists.

        Notes
        -----
        Cost (CPU, one core, measured on random maps; after numba's first
        compilation, about 10 s once per environment): on 32x32 grids up to
        0.01 s for two objectives and 0.3 s for three; on 64x64 grids with
        10 % obstacles up to 0.2 s for two objectives but 12-18 s for three;
        on 256x256 and 512x512 maps minutes and gigabytes. pymoo calls
        ``pareto_front()`` when ``verbose=True``; the size limit keeps that
        from running the exact planner unasked on a large map. Call
        ``problem.pareto_front(force=True)`` once before ``minimize`` to get
        the exact front (and pymoo's IGD/GD/HV columns) on a larger map.

        Examples
        --------
        >>> from pymoo.indicators.igd import IGD
        >>> from gapath import default_workspace
        >>> problem = GridPathProblem(default_workspace())
        >>> pf = problem.pareto_front()
        >>> pf.shape
        (24, 2)
        >>> float(IGD(pf)(pf))
        0.0
        """
        if self._exact_front is None:
            self._exact_front = self._compute_exact_front(force)
        if isinstance(self._exact_front, Exception):
            raise self._exact_front
        return self._exact_front.F.copy()

    def _compute_exact_front(self, force: bool):
        if self.layer_objectives:
            raise ConfigError(
                f"GridPathProblem.pareto_front: no exact front for the costmap layer "
                f"objective(s) {', '.join(self.layer_objectives)} (the exact planners minimise "
                "length, vulnerability and smoothness only)"
            )
        if self.encoding.name == "binary" and not self.workspace.corner_cutting:
            raise ConfigError(
                "GridPathProblem.pareto_front: no exact front for the binary encoding without "
                "corner cutting (its horizontal-then-vertical transitions are not in the "
                "monotone path set and may be Pareto-optimal); use the integer encoding"
            )
        cells = int(np.asarray(self.frame.occ).size)
        if cells > EXACT_FRONT_AUTO_CELLS and not force:
            h, w = self.workspace.shape
            raise ConfigError(
                f"GridPathProblem.pareto_front: the exact front of a {h}x{w} workspace may take "
                f"from seconds to minutes (the automatic limit is {EXACT_FRONT_AUTO_CELLS} "
                "cells); call problem.pareto_front(force=True) to compute it"
            )
        try:
            return exact.monotone_front(self.workspace, self.objectives)
        except NoPathError as exc:
            return exc

    # -- genomes <-> paths ---------------------------------------------------
    def decode(self, X) -> list[np.ndarray]:
        """The paths ``[(m_i, 2) int arrays]`` (workspace cells) of genomes
        ``X`` (one genome or a matrix)."""
        entries, exits = self.encoding.decode(X)
        return split_paths(*expand_profiles(self.frame, entries, exits))

    def encode(self, paths) -> np.ndarray:
        """Genomes of column-monotone paths (see the encoding's ``encode``)."""
        return self.encoding.encode(paths)

    def objective_values(self, metrics: np.ndarray) -> np.ndarray:
        """The unpenalised objective columns of a ``metrics`` matrix."""
        return metrics[:, self._obj_idx]

    def __repr__(self) -> str:
        return (
            f"GridPathProblem({self.workspace.name!r}, objectives={self.objectives}, "
            f"encoding={self.encoding.name!r}, constraints={self.constraints!r}, "
            f"penalty={self.penalty:g}, n_var={self.n_var})"
        )


__all__ = ["EXACT_FRONT_AUTO_CELLS", "GenomeWarning", "GridPathProblem", "OBJECTIVES", "OBJECTIVE_NAMES"]
