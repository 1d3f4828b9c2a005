"""Absolutely positioned integer encoding (Ahmed & Deb, section 2.4).

One integer per column before the goal column (``n_cols - 1`` genes): the
exit row of that column, in ``[0, H - 1]``. Gene 0 is the exit row of the
start column (the start column runs vertically from the start row to it).
Consecutive columns are joined by the integer encoding's move rule: one
diagonal step towards the next exit row (a horizontal step when equal),
then vertically to it; the goal column is reached by the integer encoding's
end-fixing. The encoding is a one-to-one relabelling of the integer
encoding's paths (gene ``k`` of the integer genome is ``a[k-1] - a[k]``),
with the paper's caveat that neighbouring genes no longer build on each
other.

Decoding rounds and clips the genes to ``[0, H - 1]``, so any genome gives a
valid path; :meth:`AbsoluteEncoding.edge_fix` only rounds and clips (rows
are never out of the grid).

Examples
--------
The paper's Path 1 on an 8 x 8 grid (integer genes ``(0, 3, 1, 0, -2, -1, 0)``):

>>> import numpy as np
>>> from gapath import Workspace
>>> from gapath.monotone import Frame
>>> enc = AbsoluteEncoding(Frame.of(Workspace(np.zeros((8, 8), bool))))
>>> entries, exits = enc.decode(np.array([[7, 4, 3, 3, 5, 6, 6]]))
>>> entries.tolist()
[[7, 6, 3, 3, 4, 6, 6, 5]]
"""

from __future__ import annotations

import numpy as np

from gapath.encodings._relative import relative_moves
from gapath.errors import ConfigError
from gapath.monotone import Frame, profiles_of_paths


class AbsoluteEncoding:
    """Exit rows of the columns before the goal column.

    Parameters
    ----------
    frame : :class:`gapath.monotone.Frame` of the workspace.

    Attributes
    ----------
    n_var : number of genes, ``n_cols - 1``.
    xl, xu : 0 and ``H - 1``.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> enc = AbsoluteEncoding(Frame.of(Workspace(np.zeros((4, 4), bool))))
    >>> enc.decode(np.array([[2, 1, 1]]))[1].tolist()
    [[2, 1, 1, 0]]
    """

    name = "absolute"
    vtype = int

    def __init__(self, frame: Frame):
        self.frame = frame
        self.n_var = frame.n_cols - 1
        self.xl = np.zeros(self.n_var, dtype=np.int64)
        self.xu = np.full(self.n_var, frame.height - 1, dtype=np.int64)

    def _genes(self, X) -> np.ndarray:
        X = np.atleast_2d(np.asarray(X))
        if X.shape[1] != self.n_var:
            raise ConfigError(f"absolute genomes need {self.n_var} genes, got {X.shape[1]}")
        return np.clip(np.rint(X), 0, self.frame.height - 1).astype(np.int64)

    def decode(self, X) -> tuple[np.ndarray, np.ndarray]:
        """Column profiles ``(entries, exits)``, each ``(N, n_cols)``, of the
        genomes ``X`` (N, n_var); genes are rounded and clipped to the grid."""
        f = self.frame
        A = self._genes(X)
        n = len(A)
        exits = np.concatenate([A, np.full((n, 1), f.goal[0], np.int64)], axis=1)
        prev = np.concatenate([np.full((n, 1), f.start[0], np.int64), A], axis=1)
        entries = prev + np.sign(exits - prev)
        entries[:, 0] = f.start[0]
        return entries, exits

    def encode(self, paths) -> np.ndarray:
        """Genomes ``(N, n_var)`` of column-monotone paths (workspace cells).

        Raises
        ------
        ConfigError
            If a path is not column-monotone or not representable (the same
            paths as the integer encoding's).
        """
        entries, exits = profiles_of_paths(self.frame, paths)
        return self.encode_profiles(entries, exits)

    def encode_profiles(self, entries, exits) -> np.ndarray:
        """Genomes of column profiles (see :meth:`encode`)."""
        relative_moves(self.frame, entries, exits, self.name)
        return np.asarray(exits, np.int64)[:, :-1].copy()

    def edge_fix(self, X, random_state: np.random.Generator | None = None) -> np.ndarray:
        """Rounded genes clipped to ``[0, H - 1]``: every row is inside the
        grid, so there is nothing else to fix (``random_state`` is unused)."""
        return self._genes(X)
