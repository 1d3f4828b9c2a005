"""Integer encoding of column-monotone paths (Ahmed & Deb, section 2.3).

A genome has one integer per column transition except the last (``n_cols - 1``
genes). Gene 0 is the vertical move inside the start column (positive = up,
towards smaller rows); gene ``k >= 1`` is the transition from column ``k-1``
to column ``k``: ``0`` a horizontal step, ``y > 0`` a diagonal step up and
``y - 1`` further cells up, ``y < 0`` the same downwards. Every gene is thus
the signed row change between the exit rows of two consecutive columns.

End-fixing: the transition into the goal column is not coded; one diagonal
step towards the goal row (or a horizontal step when already on it), then
vertical steps to the goal.

Decoding clamps a move that would leave the grid at the edge, so any genome
decodes to a valid path. Ahmed & Deb's edge-fixing is a repair
(:class:`gapath.operators.EdgeFixingRepair`) that replaces such a move by a
row drawn with linear probability and writes the fixed gene back; after it,
decoding never clamps.

Examples
--------
>>> import numpy as np
>>> from gapath import Workspace
>>> from gapath.monotone import Frame
>>> enc = IntegerEncoding(Frame.of(Workspace(np.zeros((4, 4), bool))))
>>> entries, exits = enc.decode(np.array([[1, 1, 0]]))
>>> exits.tolist()
[[2, 1, 1, 0]]
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.encodings._relative import decode_move_keys, decode_moves, linear_draw, relative_moves
from gapath.errors import ConfigError
from gapath.monotone import Frame, profiles_of_paths


@numba.njit(cache=True)
def _edge_fix(G, U, xl, xu, start_row, height):
    """Edge-fixed copy of the integer genes ``G`` (clipped to ``xl``/``xu``
    first), with the draws ``U`` (one per gene)."""
    n, n_var = G.shape
    X = np.empty((n, n_var), np.int64)
    for i in range(n):
        for k in range(n_var):
            X[i, k] = min(max(G[i, k], xl[k]), xu[k])
    for i in range(n):
        r = start_row - X[i, 0]
        for k in range(1, n_var):
            t = r - X[i, k]
            if t < 0:
                t = linear_draw(r, 0, U[i, k])
                X[i, k] = r - t
            elif t > height - 1:
                t = linear_draw(r, height - 1, U[i, k])
                X[i, k] = r - t
            r = t
    return X


class IntegerEncoding:
    """Relative integer genes (Ahmed & Deb's best scheme).

    Parameters
    ----------
    frame : :class:`gapath.monotone.Frame` of the workspace.

    Attributes
    ----------
    n_var : number of genes, ``n_cols - 1``.
    xl, xu : integer bounds: gene 0 in ``[-(H-1-start_row), start_row]`` (only
        moves that stay inside the start column), others in ``[-(H-1), H-1]``.
    """

    name = "integer"
    vtype = int

    def __init__(self, frame: Frame):
        self.frame = frame
        h = frame.height
        sr = frame.start[0]
        self.n_var = frame.n_cols - 1
        self.xl = np.full(self.n_var, -(h - 1), dtype=np.int64)
        self.xu = np.full(self.n_var, h - 1, dtype=np.int64)
        self.xl[0] = -(h - 1 - sr)
        self.xu[0] = sr

    def _genes(self, X) -> np.ndarray:
        X = np.atleast_2d(np.asarray(X))
        if X.shape[1] != self.n_var:
            raise ConfigError(f"integer genomes need {self.n_var} genes, got {X.shape[1]}")
        if X.dtype.kind in "iub":  # already integers: no rounding pass
            return np.ascontiguousarray(X, dtype=np.int64)
        return np.ascontiguousarray(np.rint(X).astype(np.int64))

    def decode(self, X) -> tuple[np.ndarray, np.ndarray]:
        """Column profiles ``(entries, exits)``, each ``(N, n_cols)``, of the
        genomes ``X`` (N, n_var); values are rounded, moves past the grid
        edge are clamped."""
        f = self.frame
        return decode_moves(self._genes(X), f.start[0], f.goal[0], f.height)

    def decode_keys(self, X) -> np.ndarray:
        """The column profiles as one ``(N, 2 n_cols)`` int64 array,
        ``[entries | exits]`` (the path keys of duplicate elimination)."""
        f = self.frame
        return decode_move_keys(self._genes(X), f.start[0], f.goal[0], f.height)

    def encode(self, paths) -> np.ndarray:
        """Genomes ``(N, n_var)`` of column-monotone paths (workspace cells).

        Raises
        ------
        ConfigError
            If a path is not column-monotone, or not representable (a
            horizontal step followed by vertical steps, a diagonal followed
            by vertical steps the other way, or an end that differs from the
            end-fixing rule).
        """
        entries, exits = profiles_of_paths(self.frame, paths)
        return self.encode_profiles(entries, exits)

    def encode_profiles(self, entries, exits) -> np.ndarray:
        """Genes of column profiles: the signed row changes between exit rows."""
        return relative_moves(self.frame, entries, exits, self.name)

    def edge_fix(self, X, random_state: np.random.Generator) -> np.ndarray:
        """Ahmed & Deb's edge-fixing: a copy of ``X`` (rounded, within bounds)
        in which every move that would leave the grid is replaced by a row
        drawn with linear probability between the violated edge (highest)
        and the current row (zero)."""
        G = self._genes(X)
        return self.edge_fix_drawn(G, random_state.random(G.shape))

    def edge_fix_drawn(self, X, U) -> np.ndarray:
        """:meth:`edge_fix` given its draws: ``U`` (N, n_var), the uniform
        numbers ``edge_fix`` would draw (``random_state.random(X.shape)``),
        e.g. drawn in one call with an operator's (see
        :class:`gapath.algorithms.FastNSGA2`)."""
        G = self._genes(X)
        U = np.ascontiguousarray(U, dtype=float)
        if U.shape != G.shape:
            raise ConfigError(f"edge_fix_drawn needs one draw per gene, {G.shape}, got {U.shape}")
        return _edge_fix(G, U, self.xl, self.xu, self.frame.start[0], self.frame.height)
