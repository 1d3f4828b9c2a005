"""Mixed binary-integer encoding of column-monotone paths (Ahmed & Deb, section 2.2).

A gene is one bit and one integer ``y`` in ``[0, H]`` (``H`` the frame
height, the paper's ``[0, n]``). For the transition from column ``k-1``
into column ``k`` (gene ``k >= 1``): ``y = 0`` is a horizontal step whatever
the bit; bit 1 with ``y > 0`` a diagonal step up then ``y - 1`` cells
further up (A-D(y-1)); bit 0 with ``y > 0`` a diagonal step down then
``y - 1`` further down (B-E(y-1)). A horizontal step is never followed by a
vertical run.

Gene 0 is the start column: its integer is the vertical move inside the
start column and its bit that move's direction (1 up, towards smaller rows;
0 down). In the paper's string this bit is the trailing one (``... 1-0 1)``)
that it reads as "diagonal up into the goal column": the transition into
the goal column is end-fixed exactly like the integer encoding (one
diagonal step towards the goal row, or a horizontal one when level, then
vertically to the goal), which agrees with the paper's examples and never
produces the dominated horizontal-then-vertical last transition.

The genome is one flat int64 vector, all bits first, then all integers::

    [bit_0 ... bit_{m-1} | y_0 ... y_{m-1}]      m = n_cols - 1 genes

so ``n_var = 2 * m``, bounds ``[0, 1]`` for the bits and ``[0, H]`` for the
integers. Each gene is the signed row change ``+y`` (bit 1) or ``-y``
(bit 0) of the integer encoding, so both encodings describe the same paths;
the mixed one is redundant (``0-0`` and ``1-0``).

Decoding rounds the genes, reads a bit as 1 when it rounds to 1 or more,
clips the integers to ``[0, H]`` and clamps moves past the grid edge, so any
genome gives a valid path. :meth:`MixedEncoding.edge_fix` is Ahmed & Deb's
edge-fixing written back into the genes (start column included); afterwards
decoding never clamps.

Examples
--------
The paper's Path 1 on an 8 x 8 grid, ``(0 1-3 1-1 0-0 0-2 0-1 1-0 1)``:

>>> import numpy as np
>>> from gapath import Workspace
>>> from gapath.monotone import Frame
>>> enc = MixedEncoding(Frame.of(Workspace(np.zeros((8, 8), bool))))
>>> bits, ints = [1, 1, 1, 0, 0, 0, 1], [0, 3, 1, 0, 2, 1, 0]
>>> entries, exits = enc.decode(np.array([bits + ints]))
>>> exits.tolist()
[[7, 4, 3, 3, 5, 6, 6, 0]]
"""

from __future__ import annotations

import numpy as np

from gapath.encodings._relative import decode_moves, edge_fix_moves, relative_moves
from gapath.errors import ConfigError
from gapath.monotone import Frame, profiles_of_paths


class MixedEncoding:
    """Ahmed & Deb's mixed genes: a direction bit and an integer per column.

    Parameters
    ----------
    frame : :class:`gapath.monotone.Frame` of the workspace.

    Attributes
    ----------
    n_genes : number of (bit, integer) genes, ``n_cols - 1``.
    n_bits : number of bits, the first ``n_bits`` columns of a genome
        (equal to ``n_genes``).
    n_var : ``2 * n_genes``.
    xl, xu : 0 and 1 for the bits, 0 and ``H`` for the integers.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> enc = MixedEncoding(Frame.of(Workspace(np.zeros((8, 8), bool))))
    >>> enc.n_var, enc.xu.tolist()[6:8]
    (14, [1, 8])
    """

    name = "mixed"
    vtype = int

    def __init__(self, frame: Frame):
        self.frame = frame
        self.n_genes = frame.n_cols - 1
        self.n_bits = self.n_genes
        self.n_var = 2 * self.n_genes
        self.xl = np.zeros(self.n_var, dtype=np.int64)
        self.xu = np.concatenate(
            [np.ones(self.n_genes, np.int64), np.full(self.n_genes, frame.height, np.int64)]
        )

    def split(self, X) -> tuple[np.ndarray, np.ndarray]:
        """Bits (bool) and integers (int64, clipped to ``[0, H]``) of ``X``,
        each ``(N, n_genes)``."""
        X = np.atleast_2d(np.asarray(X))
        if X.shape[1] != self.n_var:
            raise ConfigError(f"mixed genomes need {self.n_var} genes, got {X.shape[1]}")
        X = np.rint(X)
        m = self.n_genes
        bits = X[:, :m] >= 1
        ints = np.clip(X[:, m:], 0, self.frame.height).astype(np.int64)
        return bits, ints

    def moves(self, X) -> np.ndarray:
        """Signed row changes ``(N, n_genes)`` (up positive) of the genes:
        the equivalent integer-encoding genomes."""
        bits, ints = self.split(X)
        return np.ascontiguousarray(np.where(bits, ints, -ints))

    def decode(self, X) -> tuple[np.ndarray, np.ndarray]:
        """Column profiles ``(entries, exits)``, each ``(N, n_cols)``, of the
        genomes ``X`` (N, n_var); moves past the grid edge are clamped."""
        f = self.frame
        return decode_moves(self.moves(X), f.start[0], f.goal[0], f.height)

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
        """Genomes of column profiles; a horizontal step (or no move in the
        start column) gets bit 1."""
        D = relative_moves(self.frame, entries, exits, self.name)
        return np.concatenate([(D >= 0).astype(np.int64), np.abs(D)], axis=1)

    def edge_fix(self, X, random_state: np.random.Generator) -> np.ndarray:
        """Ahmed & Deb's edge-fixing: a copy of ``X`` (rounded, within bounds)
        in which every move that would leave the grid (the start column's
        included) is replaced by a row drawn with linear probability between
        the violated edge (highest) and the current row (zero). Bits of
        horizontal steps are kept."""
        bits, ints = self.split(X)
        D = np.ascontiguousarray(np.where(bits, ints, -ints))
        U = random_state.random(D.shape)
        D = edge_fix_moves(D, U, self.frame.start[0], self.frame.height)
        bits = np.where(D != 0, D > 0, bits)
        return np.concatenate([bits.astype(np.int64), np.abs(D)], axis=1)
