"""Feasibility-preserving variation: a repair that moves exit rows off obstacles.

Ahmed & Deb handle obstacles with a penalty only; gapath's default keeps
that (``docs/results/penalty.md`` shows how the penalty then decides the
unseeded GA). :class:`FeasibleStepRepair` is an alternative, an option:
after the edge-fixing, the path of (a share of) the offspring is decoded
and, column by column, every column step that touches an obstacle gets the
exit row nearest to the one the genes asked for from which the step is
free; the repaired path is written back into the genes (Lamarckian), so
the population holds what it is evaluated on.

Modes (:data:`REPAIRS` names them):

``local``
    Each column looks only at itself, plus the encoding's end-fix for the
    column before the goal column (its exit row must let the fixed last
    step be free). Where no exit row of a column is free from the previous
    one (a dead end) the column is kept, so a repaired path can still touch
    obstacles; the penalty handles those.
``reach``
    Exit rows are chosen among those from which a feasible path of the
    relative moves still reaches the goal (a backward reachability table
    computed once per map). Every repaired path is feasible whenever the map
    has a feasible column-monotone path of those moves; it uses the whole
    map, so a run that repairs everything solves Table 1's question (is
    there a feasible path?) in its first generation.
"""

from __future__ import annotations

import zlib
from typing import Any

import numpy as np
from pymoo.core.repair import Repair

from gapath.errors import ConfigError
from gapath.operators.repair._kernels import exit_rows_allowed, repair_profiles

__all__ = ["REPAIRS", "FeasibleStepRepair", "make_repair"]

#: Named repairs (:func:`make_repair`): the :class:`FeasibleStepRepair`
#: keywords of each. ``edge``: Ahmed & Deb's edge-fixing alone (gapath's
#: default).
REPAIRS = {
    "edge": None,
    "feasible-local": {"mode": "local", "share": 1.0},
    "feasible-local-half": {"mode": "local", "share": 0.5},
    "feasible-reach": {"mode": "reach", "share": 1.0},
    "feasible-reach-half": {"mode": "reach", "share": 0.5},
}

MODES = ("local", "reach")


class FeasibleStepRepair(Repair):
    """Edge-fixing, then the nearest free exit row for every column step
    that touches an obstacle, written back into the genes.

    Parameters
    ----------
    mode : ``"local"`` (default) or ``"reach"`` (see the module docstring).
    share : the probability that an offspring is repaired beyond the
        edge-fixing, in [0, 1] (default 1); the others keep their genes
        (edge-fixed) and are left to the constraint handling.

    Notes
    -----
    The problem must expose an ``encoding`` with ``decode``,
    ``encode_profiles`` and ``edge_fix`` (the integer, mixed, binary and
    absolute encodings do). Randomness (the edge-fixing's draws, which rows
    are repaired, ties between two equally near rows) comes from the
    ``random_state`` pymoo passes; without one, from a generator seeded by
    the genes. Only rows whose path changes are re-encoded; a binary genome
    that is re-encoded loses its horizontal-then-vertical transitions
    (written as the diagonal ones of the same rows, which dominate them with
    corner cutting allowed).

    Raises
    ------
    ConfigError
        On an unknown ``mode``, a ``share`` outside [0, 1], or a problem
        without such an encoding.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import default_workspace
    >>> from gapath.problems import GridPathProblem
    >>> p = GridPathProblem(default_workspace())
    >>> X = np.random.default_rng(1).integers(-3, 4, (50, p.n_var))
    >>> Y = FeasibleStepRepair("reach")._do(p, X, random_state=np.random.default_rng(2))
    >>> int(p.metrics(Y)[:, 3].max())  # interfering cells
    0
    """

    def __init__(self, mode: str = "local", share: float = 1.0):
        super().__init__()
        if mode not in MODES:
            raise ConfigError(
                f"FeasibleStepRepair: unknown mode {mode!r}; expected one of {', '.join(MODES)}"
            )
        try:
            share = float(share)
        except (TypeError, ValueError):
            share = float("nan")
        if not 0.0 <= share <= 1.0:
            raise ConfigError(f"FeasibleStepRepair: share must be in [0, 1], got {share!r}")
        self.mode, self.share = mode, share
        self._allowed: dict[int, tuple[Any, np.ndarray]] = {}  # id(frame) -> (frame, table)

    def allowed(self, frame) -> np.ndarray:
        """``(n_cols, H)`` bool: the exit rows the repair may choose per
        column (see :func:`gapath.operators.repair._kernels.exit_rows_allowed`),
        computed once per frame."""
        hit = self._allowed.get(id(frame))
        if hit is None or hit[0] is not frame:
            ws = frame.workspace
            table = exit_rows_allowed(
                np.ascontiguousarray(frame.occ, np.bool_),
                frame.col0,
                frame.n_cols,
                frame.start[0],
                frame.goal[0],
                bool(ws.corner_cutting),
                self.mode == "reach",
            )
            hit = self._allowed[id(frame)] = (frame, table)
        return hit[1]

    def _do(self, problem, X, random_state=None, **kwargs):
        encoding = getattr(problem, "encoding", None)
        if encoding is None or not all(
            hasattr(encoding, a) for a in ("decode", "encode_profiles", "edge_fix", "frame")
        ):
            raise ConfigError(
                f"FeasibleStepRepair needs a gapath column-monotone path problem, got {type(problem).__name__}"
            )
        X = np.asarray(X)
        if len(X) == 0:
            return X
        if random_state is None:
            random_state = np.random.default_rng(zlib.crc32(np.ascontiguousarray(X).tobytes()))
        Y = encoding.edge_fix(X, random_state)
        frame = encoding.frame
        entries, exits = (np.ascontiguousarray(a, np.int64) for a in encoding.decode(Y))
        draws = random_state.random(len(Y) * (1 + frame.n_cols))
        todo = draws[: len(Y)] < self.share
        U = draws[len(Y) :].reshape(len(Y), frame.n_cols)
        changed = repair_profiles(
            entries,
            exits,
            todo,
            np.ascontiguousarray(frame.occ, np.bool_),
            frame.col0,
            frame.start[0],
            frame.goal[0],
            self.allowed(frame),
            bool(frame.workspace.corner_cutting),
            U,
        )
        if changed.any():
            Y = Y.copy()
            Y[changed] = encoding.encode_profiles(entries[changed], exits[changed]).astype(Y.dtype)
        return Y

    def __repr__(self) -> str:
        return f"FeasibleStepRepair(mode={self.mode!r}, share={self.share:g})"


def make_repair(name):
    """The repair called ``name`` in :data:`REPAIRS` (None for ``"edge"``:
    the engine's default edge-fixing), or ``name`` itself when it is a
    pymoo ``Repair``.

    Raises
    ------
    ConfigError
        If ``name`` is neither.

    Examples
    --------
    >>> make_repair("feasible-local")
    FeasibleStepRepair(mode='local', share=1)
    >>> make_repair("edge") is None
    True
    """
    if isinstance(name, Repair):
        return name
    if name not in REPAIRS:
        raise ConfigError(f"unknown repair {name!r}; expected one of {', '.join(REPAIRS)}")
    kw = REPAIRS[name]
    return None if kw is None else FeasibleStepRepair(**kw)
