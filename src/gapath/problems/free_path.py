"""The grid path problem over free paths (SPEC "Free path set")."""

from __future__ import annotations

import numpy as np
from pymoo.core.problem import Problem

from gapath.costmap import STEP_SUM, evaluate_layer_paths
from gapath.encodings.free import DEFAULT_FREE_ENCODING, FREE_ENCODINGS, make_free_encoding
from gapath.errors import ConfigError
from gapath.objectives import INTERFERING, SMOOTHNESS, evaluate_paths
from gapath.problems.grid_path import GridPathProblem, problem_settings


class FreePathProblem(Problem):
    """Multi-objective path planning over free (any simple 8-connected) paths.

    The sibling of :class:`gapath.problems.GridPathProblem` with the same
    interface (``objectives``, ``metrics``, ``decode``, ``encode``,
    ``objective_values``, outputs ``F``, ``smoothness`` and ``interfering``):
    each row of ``X`` is a genome of a free-path encoding
    (:mod:`gapath.encodings.free`); evaluation decodes the whole population
    in one numba kernel and evaluates the paths with
    :func:`gapath.objectives.evaluate_paths`.

    Parameters
    ----------
    workspace : :class:`gapath.Workspace`.
    objectives : names among ``length``, ``vulnerability``, ``smoothness``
        and, with ``costmap``, its layer objectives (a sequence or a
        comma-separated string).
    encoding : ``"field"`` (default: a coarse cost field decoded by one
        search) or ``"via"`` (via points joined by weighted segments), see
        :data:`gapath.encodings.free.FREE_ENCODINGS` and
        ``docs/results/free_paths.md`` for why the field is the default.
    constraints : ``"penalty"`` or ``"constraint"``, as for
        :class:`~gapath.problems.GridPathProblem`. Every genome of a free
        encoding decodes to a feasible path, so neither ever applies; the
        outputs keep the same shape.
    penalty : penalty per interfering cell (default 1000).
    costmap : :class:`gapath.costmap.Costmap`, optional: layer objectives
        (mean of a cell layer over the path's cells, ``<layer>_max`` its
        maximum over them, ``solar`` summed over the steps).
    **options : passed to the encoding (``n_via``, ``field_shape``, ``beta``,
        ``lam_range``).

    The decoders weigh the length against a per-cell cost: the potential
    field when ``vulnerability`` is an objective, plus every cell layer that
    is an objective, a worst-case ``<layer>_max`` weighed by its layer
    (layers are normalised to [0, 1]); the potential field
    when no objective is a cell cost.

    Raises
    ------
    ConfigError
        On an unknown objective, encoding or constraint mode, a negative
        penalty, or a bad encoding option (``n_via < 0``, a field finer than
        the map).
    NoPathError
        If the goal cannot be reached from the start.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> occ = np.zeros((8, 8), bool); occ[2:8, 3] = True
    >>> problem = FreePathProblem(Workspace(occ), encoding="via", n_via=2)
    >>> problem.n_var, problem.n_obj
    (7, 2)
    >>> out = problem.evaluate(np.full((1, 7), 0.5), return_as_dictionary=True)
    >>> out["interfering"].tolist()
    [0.0]
    """

    paths = "free"

    def __init__(
        self,
        workspace,
        objectives=("length", "vulnerability"),
        encoding=DEFAULT_FREE_ENCODING,
        constraints="penalty",
        penalty=1000.0,
        costmap=None,
        **options,
    ):
        self.objectives, self.layer_objectives, self._obj_idx, penalty = problem_settings(
            objectives, constraints, penalty, costmap
        )
        if encoding not in FREE_ENCODINGS:
            raise ConfigError(
                f"unknown encoding {encoding!r} for free paths; expected one of "
                f"{', '.join(FREE_ENCODINGS)} (integer, binary, mixed and absolute "
                f"describe monotone paths)"
            )
        self.workspace = workspace
        self.costmap = costmap
        self._layer_stack = self._layer_agg = None
        extra = None
        if self.layer_objectives:
            costmap.check_objectives(self.layer_objectives, maxima=True)
            if tuple(costmap.shape) != tuple(workspace.shape):
                raise ConfigError(
                    f"the costmap's grid {costmap.shape} differs from the workspace's {workspace.shape}"
                )
            h, w = workspace.shape
            stack = np.zeros((len(self.layer_objectives), h, w))
            agg = np.empty(len(self.layer_objectives), np.int64)
            for j, n in enumerate(self.layer_objectives):
                agg[j] = costmap.aggregation(n)
                if n != "solar":
                    stack[j] = costmap.layer(costmap.base_layer(n))
            self._layer_stack, self._layer_agg = np.ascontiguousarray(stack), agg
            cell_layers = [stack[j] for j in range(len(agg)) if agg[j] != STEP_SUM]
            if cell_layers:
                extra = np.sum(cell_layers, axis=0)
                if "vulnerability" in self.objectives:
                    extra = extra + workspace.potential
        self.encoding = make_free_encoding(encoding, workspace, extra=extra, **options)
        self.constraints = constraints
        self.penalty = penalty
        super().__init__(
            n_var=self.encoding.n_var,
            n_obj=len(self.objectives),
            n_ieq_constr=1 if constraints == "constraint" else 0,
            xl=self.encoding.xl,
            xu=self.encoding.xu,
            vtype=float,
        )

    # -- evaluation --------------------------------------------------------
    def padded_paths(self, X):
        """Decoded paths as padded ``(N, L, 2)`` cells and lengths ``(N,)``."""
        return self.encoding.decode(X)

    def metrics(self, X) -> np.ndarray:
        """All per-path metrics ``(N, 4)`` in :data:`gapath.objectives.OBJECTIVES`
        order, unpenalised, computed by :func:`gapath.objectives.evaluate_paths`
        on the decoded paths; with layer objectives ``(N, 4 + k)``."""
        return self.path_metrics(*self.encoding.decode(X))

    def path_metrics(self, P, L) -> np.ndarray:
        """:meth:`metrics` of padded paths ``P`` (N, L, 2) with lengths ``L``
        (N,) (e.g. paths that no genome decodes to, such as the re-routed
        paths of :class:`gapath.operators.archive.FreePathArchive`)."""
        ws = self.workspace
        M = evaluate_paths(P, L, ws.occ, ws.potential, ws.cell_size, ws.corner_cutting)
        if self._layer_stack is not None:
            cm = self.costmap
            M = np.hstack(
                [
                    M,
                    evaluate_layer_paths(
                        P, L, self._layer_stack, self._layer_agg, cm.solar_angle0, cm.solar_rate
                    ),
                ]
            )
        return M

    def _evaluate(self, X, out, *args, **kwargs):
        M = self.metrics(X)
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
        """The paths ``[(m_i, 2) int arrays]`` (workspace cells) of genomes ``X``."""
        P, L = self.encoding.decode(X)
        return [P[i, : L[i]].copy() for i in range(len(L))]

    def path_keys(self, X) -> np.ndarray:
        """Identity rows of the decoded paths (see
        :meth:`gapath.encodings.free.FreeEncoding.path_keys`)."""
        return self.encoding.path_keys(X)

    def encode(self, paths, weights=None) -> np.ndarray:
        """Genomes of paths (see the encoding's ``encode``)."""
        return self.encoding.encode(paths, weights)

    def objective_values(self, metrics: np.ndarray) -> np.ndarray:
        """The unpenalised objective columns of a ``metrics`` matrix."""
        return metrics[:, self._obj_idx]

    def __repr__(self) -> str:
        return (
            f"FreePathProblem({self.workspace.name!r}, objectives={self.objectives}, "
            f"encoding={self.encoding!r}, constraints={self.constraints!r}, "
            f"penalty={self.penalty:g}, n_var={self.n_var})"
        )


def path_problem(
    workspace, objectives=("length", "vulnerability"), *, paths="monotone", encoding=None, **kwargs
):
    """The path problem over the path set ``paths``: ``"monotone"``
    (:class:`~gapath.problems.GridPathProblem`, default encoding
    ``"integer"``) or ``"free"`` (:class:`FreePathProblem`, default encoding
    ``"field"``).

    Raises
    ------
    ConfigError
        If ``paths`` is neither, or the problem's own checks fail.

    Examples
    --------
    >>> from gapath import default_workspace
    >>> type(path_problem(default_workspace(), paths="free")).__name__
    'FreePathProblem'
    """
    if paths == "free":
        return FreePathProblem(workspace, objectives, encoding=encoding or DEFAULT_FREE_ENCODING, **kwargs)
    if paths == "monotone":
        return GridPathProblem(workspace, objectives, encoding=encoding or "integer", **kwargs)
    raise ConfigError(f"unknown path set {paths!r}; expected 'free' or 'monotone'")


__all__ = ["FreePathProblem", "path_problem"]
