"""The grid path problem as a vectorised pymoo ``Problem``."""

from __future__ import annotations

import numpy as np
from pymoo.core.problem import Problem

from gapath.encodings import expand_profiles, make_encoding, split_paths
from gapath.encodings.base import Frame
from gapath.errors import ConfigError
from gapath.objectives import INTERFERING, OBJECTIVES, SMOOTHNESS, objective_index

#: Metrics that may be objectives (``interfering`` is the constraint).
OBJECTIVE_NAMES = ("length", "vulnerability", "smoothness")
CONSTRAINT_MODES = ("penalty", "constraint")


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
    constraints : ``"penalty"`` (the seeds' default: every objective gets
        ``penalty * interfering`` added) or ``"constraint"`` (``interfering``
        is returned as the inequality constraint ``G``; feasible when 0).
    penalty : penalty per interfering cell (default 1000).
    costmap : :class:`gapath.costmap.Costmap`, optional. Its layer objectives
        are computed by :func:`gapath.costmap.evaluate_layer_profiles` over
        the decoded column profiles (mean over the path's cells for cell
        layers, sum over the steps for ``solar``); they get the same penalty
        as the other objectives.

    Outputs
    -------
    ``F`` (N, n_obj); ``G`` (N, 1) in constraint mode; per individual also
    ``smoothness`` (total turn, radians) and ``interfering`` (count), kept by
    pymoo on the individuals (``pop.get("smoothness")``).

    Raises
    ------
    ConfigError
        On an unknown objective, encoding or constraint mode, or a negative
        penalty.

    Examples
    --------
    >>> from gapath import default_workspace
    >>> problem = GridPathProblem(default_workspace())
    >>> problem.n_var, problem.n_obj
    (31, 2)
    """

    def __init__(self, workspace, objectives=("length", "vulnerability"), encoding="integer",
                 constraints="penalty", penalty=1000.0, costmap=None, **kwargs):
        names = objectives.split(",") if isinstance(objectives, str) else list(objectives)
        names = [n.strip() for n in names]
        layer_names = () if costmap is None else costmap.objective_names
        for n in names:
            if n not in OBJECTIVE_NAMES and n not in layer_names:
                expected = OBJECTIVE_NAMES + tuple(x for x in layer_names if x not in OBJECTIVE_NAMES)
                raise ConfigError(
                    f"unknown objective {n!r}; expected some of {', '.join(expected)}")
        self.objectives = tuple(names)
        # layer objectives: metrics columns 4, 5, ... (after OBJECTIVES)
        self.layer_objectives = tuple(n for n in names if n not in OBJECTIVE_NAMES)
        base = [n for n in names if n in OBJECTIVE_NAMES]
        if base or not names:
            objective_index(base)                    # "at least one", "given twice"
        if len(set(self.layer_objectives)) != len(self.layer_objectives):
            dup = next(n for n in self.layer_objectives if names.count(n) > 1)
            raise ConfigError(f"objective {dup!r} is given twice")
        self._obj_idx = [OBJECTIVES.index(n) if n in OBJECTIVE_NAMES
                         else len(OBJECTIVES) + self.layer_objectives.index(n) for n in names]
        if constraints not in CONSTRAINT_MODES:
            raise ConfigError(
                f"unknown constraint handling {constraints!r}; expected one of {', '.join(CONSTRAINT_MODES)}")
        try:
            penalty = float(penalty)
        except (TypeError, ValueError):
            raise ConfigError(f"penalty must be a number >= 0, got {penalty!r}") from None
        if not np.isfinite(penalty) or penalty < 0:
            raise ConfigError(f"penalty must be a number >= 0, got {penalty!r}")
        self.workspace = workspace
        self.frame = Frame.of(workspace)
        self.costmap = costmap
        self._layers = (costmap.profile_evaluator(self.frame, self.layer_objectives)
                        if self.layer_objectives else None)
        self.encoding = make_encoding(encoding, self.frame)
        self.constraints = constraints
        self.penalty = penalty
        # pymoo passes evaluate()'s keyword arguments (``profiles``) through
        kwargs.setdefault("requires_kwargs", True)
        super().__init__(n_var=self.encoding.n_var, n_obj=len(self.objectives),
                         n_ieq_constr=1 if constraints == "constraint" else 0,
                         xl=self.encoding.xl, xu=self.encoding.xu,
                         vtype=self.encoding.vtype, **kwargs)

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
                raise ConfigError(f"profiles must be two {shape} arrays (entries, exits) of the "
                                  f"genomes, got {entries.shape} and {exits.shape}")
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
        return (f"GridPathProblem({self.workspace.name!r}, objectives={self.objectives}, "
                f"encoding={self.encoding.name!r}, constraints={self.constraints!r}, "
                f"penalty={self.penalty:g}, n_var={self.n_var})")


__all__ = ["GridPathProblem", "OBJECTIVES", "OBJECTIVE_NAMES"]
