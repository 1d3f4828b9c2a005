"""Binary encoding of column-monotone paths (Ahmed & Deb, section 2.1).

A gene is one column transition: two transition bits ``(a, c)`` followed by
``b = ceil(log2 H)`` bits of a vertical run ``y`` (``H`` the frame height;
at least one bit), most significant bit first:

========  ==========================================  ===========
bits      move from exit row ``r``                    paper
========  ==========================================  ===========
``11-y``  diagonal up, then ``y`` further cells up     A-Dy
``00-y``  diagonal down, then ``y`` further down       B-Ey
``10-y``  horizontal, then ``y`` cells up              C-Dy
``01-y``  horizontal, then ``y`` cells down            C-Ey
========  ==========================================  ===========

The first bit is thus always the direction (1 up, towards smaller rows) and
the transition is diagonal when both bits agree. A-Ey and B-Dy (a diagonal
followed by a vertical run the other way) are not generated.

Genome layout (``n_var = (n_cols - 1) * (2 + b)`` booleans), exactly the
paper's string read left to right::

    [y0 (b bits)] [a1 c1 y1] ... [a_m c_m y_m] [a0 c0]      m = n_cols - 2

Gene ``k`` (1 <= k <= m) is the transition from column ``k-1`` into column
``k``. The transition into the goal column is not coded: it follows the
integer encoding's end-fixing (one diagonal step towards the goal row, or a
horizontal one when level, then vertically to the goal). The last gene is
split, as in the paper: its ``y0`` bits lead the string and code the
vertical move in the start column, its transition bits ``a0 c0`` close it
and give that move's direction (``a0``: 1 up, 0 down; ``c0`` is unused and
written equal to ``a0``). The paper reads ``a0 c0`` as the final transition
(11 diagonal up then joined to the goal); in the paper's set-up (goal in the
top row, start in the bottom row) both readings give the same paths, and
this one also lets the start move downwards and never produces a
horizontal-then-vertical or away-from-the-goal last transition (dominated).

Decoding turns any genome into a valid path: moves past the top or bottom
edge are clamped there. :meth:`BinaryEncoding.edge_fix` is Ahmed & Deb's
edge-fixing written back into the bits: a move that would leave the grid
gets a row drawn with linear probability (highest at the violated edge, zero
at the current row) and its ``y`` bits are rewritten (a diagonal at the edge
itself becomes the horizontal step of the same direction); afterwards
decoding never clamps.

The encoding is redundant (``10-0`` and ``01-0`` are both a horizontal
step, ``c0`` is free); :meth:`BinaryEncoding.encode` writes ``10-0`` for a
horizontal step and ``11`` (``00`` when the start moves down) for ``a0 c0``.

Examples
--------
The paper's Path 1 on an 8 x 8 grid:

>>> import numpy as np
>>> from gapath import Workspace
>>> from gapath.monotone import Frame
>>> enc = BinaryEncoding(Frame.of(Workspace(np.zeros((8, 8), bool))))
>>> genome = "000" "11010" "11000" "10000" "00001" "00000" "10000" "11"
>>> entries, exits = enc.decode(np.array([[c == "1" for c in genome]]))
>>> exits.tolist()
[[7, 4, 3, 3, 5, 6, 6, 0]]
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.encodings._relative import linear_draw
from gapath.errors import ConfigError
from gapath.monotone import Frame, profiles_of_paths


def y_bits(height: int) -> int:
    """Bits of the vertical run ``y``: ``ceil(log2 height)``, at least 1."""
    return max(1, int(height - 1).bit_length())


@numba.njit(cache=True, inline="always")
def _read_y(B, i, offset, n_bits):
    """Unsigned integer of bits ``offset .. offset + n_bits - 1`` of row
    ``i``, most significant first."""
    y = 0
    for j in range(n_bits):
        y = 2 * y + (1 if B[i, offset + j] else 0)
    return y


@numba.njit(cache=True, inline="always")
def _write_y(B, i, offset, n_bits, y):
    for j in range(n_bits - 1, -1, -1):
        B[i, offset + j] = (y & 1) == 1
        y >>= 1


@numba.njit(cache=True, inline="always")
def _move(up, diagonal, y, r):
    """Entry and exit row (not clamped) of a transition from exit row ``r``."""
    s = -1 if up else 1
    entry = r + s if diagonal else r
    return entry, entry + s * y


@numba.njit(cache=True)
def _decode(B, n_cols, nb, start_row, goal_row, height):
    n, n_bits = B.shape
    top = height - 1
    entries = np.empty((n, n_cols), np.int64)
    exits = np.empty((n, n_cols), np.int64)
    for i in range(n):
        # start column: y0 leads the string, its direction closes it
        y = _read_y(B, i, 0, nb)
        t = start_row - y if B[i, n_bits - 2] else start_row + y
        entries[i, 0] = start_row
        exits[i, 0] = min(max(t, 0), top)
        r = exits[i, 0]
        for k in range(1, n_cols - 1):
            o = nb + (k - 1) * (2 + nb)
            entry, t = _move(B[i, o], B[i, o] == B[i, o + 1], _read_y(B, i, o + 2, nb), r)
            entries[i, k] = min(max(entry, 0), top)
            exits[i, k] = min(max(t, 0), top)
            r = exits[i, k]
        # end-fixing: towards the goal row, then vertically to it
        entries[i, n_cols - 1] = r + np.sign(goal_row - r)
        exits[i, n_cols - 1] = goal_row
    return entries, exits


@numba.njit(cache=True)
def _edge_fix(B, U, n_cols, nb, start_row, height):
    n, n_bits = B.shape
    top = height - 1
    for i in range(n):
        y = _read_y(B, i, 0, nb)
        t = start_row - y if B[i, n_bits - 2] else start_row + y
        if t < 0 or t > top:
            t = linear_draw(start_row, 0 if t < 0 else top, U[i, 0])
            _write_y(B, i, 0, nb, abs(t - start_row))
        r = t
        for k in range(1, n_cols - 1):
            o = nb + (k - 1) * (2 + nb)
            diagonal = B[i, o] == B[i, o + 1]
            entry, t = _move(B[i, o], diagonal, _read_y(B, i, o + 2, nb), r)
            if t < 0 or t > top:
                # the drawn row lies the move's way, strictly past r unless
                # r is the violated edge itself
                t = linear_draw(r, 0 if t < 0 else top, U[i, k])
                if t == r and diagonal:
                    B[i, o + 1] = not B[i, o + 1]  # 11 -> 10, 00 -> 01: horizontal
                    entry = r
                _write_y(B, i, o + 2, nb, abs(t - entry))
            r = t
    return B


class BinaryEncoding:
    """Ahmed & Deb's binary genes: two transition bits and a vertical run per
    column (see the module documentation for the bit layout).

    Parameters
    ----------
    frame : :class:`gapath.monotone.Frame` of the workspace.

    Attributes
    ----------
    n_var : number of bits, ``(n_cols - 1) * (2 + n_y_bits)``.
    n_y_bits : bits of each vertical run, ``ceil(log2 H)`` (at least 1).
    xl, xu : 0 and 1 (booleans).

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> enc = BinaryEncoding(Frame.of(Workspace(np.zeros((8, 8), bool))))
    >>> enc.n_var, enc.n_y_bits
    (35, 3)
    """

    name = "binary"
    vtype = bool

    def __init__(self, frame: Frame):
        self.frame = frame
        self.n_y_bits = y_bits(frame.height)
        self.n_var = (frame.n_cols - 1) * (2 + self.n_y_bits)
        self.xl = np.zeros(self.n_var, dtype=np.int64)
        self.xu = np.ones(self.n_var, dtype=np.int64)

    def _bits(self, X) -> np.ndarray:
        X = np.atleast_2d(np.asarray(X))
        if X.shape[1] != self.n_var:
            raise ConfigError(f"binary genomes need {self.n_var} bits, got {X.shape[1]}")
        if X.dtype != np.bool_:
            X = X > 0.5  # a number is a 1 when it rounds to 1 or more
        return np.ascontiguousarray(X)

    def decode(self, X) -> tuple[np.ndarray, np.ndarray]:
        """Column profiles ``(entries, exits)``, each ``(N, n_cols)``, of the
        genomes ``X`` (N, n_var).

        Genes may be booleans or numbers (a number above 0.5 is a 1). Moves
        past the grid edge are clamped, so every genome gives a valid path.
        """
        f = self.frame
        return _decode(self._bits(X), f.n_cols, self.n_y_bits, f.start[0], f.goal[0], f.height)

    def encode(self, paths) -> np.ndarray:
        """Boolean genomes ``(N, n_var)`` of column-monotone paths (workspace
        cells).

        Raises
        ------
        ConfigError
            If a path is not column-monotone or not representable (a
            diagonal followed by vertical steps the other way, A-Ey or B-Dy,
            or an end that differs from the end-fixing rule).
        """
        entries, exits = profiles_of_paths(self.frame, paths)
        return self.encode_profiles(entries, exits)

    def encode_profiles(self, entries, exits) -> np.ndarray:
        """Boolean genomes of column profiles (see :meth:`encode`)."""
        f = self.frame
        entries = np.asarray(entries, np.int64)
        exits = np.asarray(exits, np.int64)
        n, n_cols = exits.shape
        sr, gr = f.start[0], f.goal[0]
        # transitions into columns 1 .. n_cols - 2
        r, e, t = exits[:, :-2], entries[:, 1:-1], exits[:, 1:-1]
        step = e - r
        diagonal = step != 0
        bad = diagonal & ((t - e) * step < 0)
        last = exits[:, -2]
        bad_end = entries[:, -1] != last + np.sign(gr - last)
        bad = np.concatenate([entries[:, :1] != sr, bad, bad_end[:, None]], axis=1)
        if bad.any():
            i, k = np.argwhere(bad)[0]
            raise ConfigError(
                f"path {i} is not representable in the binary encoding at column {k}: "
                + (
                    "a diagonal step followed by vertical steps the other way"
                    if 0 < k < n_cols - 1
                    else "the start or end differs from the encoding's rule"
                )
            )
        up = np.where(diagonal, step < 0, t <= r)
        a = up
        c = np.where(diagonal, up, ~up)
        y = np.abs(t - e)
        d0 = sr - exits[:, 0]
        up0 = d0 >= 0
        shifts = np.arange(self.n_y_bits - 1, -1, -1)

        def bits(v):
            return ((v[..., None] >> shifts) & 1).astype(bool)

        genes = np.concatenate([a[..., None], c[..., None], bits(y)], axis=2)
        return np.concatenate([bits(np.abs(d0)), genes.reshape(n, -1), up0[:, None], up0[:, None]], axis=1)

    def edge_fix(self, X, random_state: np.random.Generator) -> np.ndarray:
        """Ahmed & Deb's edge-fixing: a boolean copy of ``X`` in which every
        move that would leave the grid (the start column's included) gets a
        row drawn with linear probability between the violated edge
        (highest) and the current row (zero), written back into its ``y``
        bits; a diagonal step at the edge itself becomes the horizontal step
        of the same direction."""
        f = self.frame
        B = self._bits(X).copy()
        U = random_state.random((len(B), f.n_cols - 1))
        return _edge_fix(B, U, f.n_cols, self.n_y_bits, f.start[0], f.height)
