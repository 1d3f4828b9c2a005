"""Fixed-length genomes of free paths (SPEC "Free path set").

A free path is any simple 8-connected path from the start to the goal that
obeys the workspace's corner rule. Two encodings describe such paths with
real genes in ``[0, 1]``, so that every pymoo operator and algorithm can run
them; both decode a whole population in one numba kernel
(:mod:`gapath.encodings._free_kernels`) and every genome decodes to a
feasible simple path (no penalty is ever needed).

Step cost
    Both decoders search shortest paths under the step cost
    ``a * step * m(v) + b * extra(v)`` of a step into cell ``v``: ``step`` is
    1 or sqrt(2), ``extra`` a non-negative per-cell cost (the potential field
    for vulnerability, plus the costmap's cell layers when they are
    objectives), ``m`` a cost multiplier (1 for via points). A *weight gene*
    ``x`` in [0, 1] sets ``b / a = lam = 10 ** (lo + (hi - lo) x)``,
    ``a + b = 1``; ``(lo, hi) = (-3, 5)`` by default (``lam_range``).

Via points (``"via"``, :class:`ViaPointEncoding`)
    ``K`` via points and ``K + 1`` segment weights: genes ``2k, 2k + 1``
    (``k < K``) are the row and column of via point ``k`` as fractions of the
    map's height and width, snapped to the nearest cell reachable from the
    start; genes ``2K .. 3K`` are the weight genes of the segments start ->
    via 0 -> ... -> via K-1 -> goal. Each segment is one A* search under its
    own weight; loops are cut where segments cross. ``K`` defaults to
    ``clip(round(max(H, W) / 16) + 1, 2, 12)``.

Cost field (``"field"``, :class:`FieldEncoding`)
    ``gy x gx`` control genes of a cost multiplier field and one weight gene:
    the field is the bilinear interpolation of the control genes over the map
    (control point ``(i, j)`` at row ``i (H - 1) / (gy - 1)``, column
    ``j (W - 1) / (gx - 1)``), ``m(v) = exp(beta (2 f(v) - 1))`` (``beta =
    ln 4``: multipliers between 1/4 and 4). One A* search from start to goal
    per genome; its paths are simple without any loop cutting.

Identity
    ``path_keys(X)`` gives one int64 row per genome (number of cells and two
    64-bit hashes of the cell sequence): equal rows mean equal decoded paths
    (up to a hash collision, about 2**-128), which is what duplicate
    elimination compares (SPEC "Duplicates and ties").

Examples
--------
>>> import numpy as np
>>> from gapath import Workspace
>>> occ = np.zeros((5, 5), bool); occ[1:4, 2] = True
>>> enc = ViaPointEncoding(Workspace(occ), n_via=1)
>>> enc.n_var
4
>>> paths, lengths = enc.decode(np.array([[0.9, 0.9, 0.0, 0.0]]))
>>> paths[0, :lengths[0]].tolist()
[[4, 0], [4, 1], [4, 2], [4, 3], [4, 4], [3, 4], [2, 4], [1, 4], [0, 4]]
"""

from __future__ import annotations

import math
import os
import threading
from collections.abc import Callable

import numba
import numpy as np

from gapath.encodings import _free_kernels as K
from gapath.errors import ConfigError, NoPathError
from gapath.workspace import read_only

#: Default range of ``log10`` of the cell-cost weight (see the module docstring).
LAM_RANGE = (-3.0, 5.0)
#: Candidate weight genes tried when fitting segments of a given path.
FIT_CANDIDATES = np.linspace(0.0, 1.0, 33)
#: Re-routing searches stay within this many cells (or the stretch's own
#: extent, if larger) of the box around the stretch's ends (see
#: :meth:`FreeEncoding.reroute`); 64 leaves every search on maps up to
#: 65 x 65 unbounded.
REROUTE_MARGIN = 64
#: Most threads a batch of searches uses (numba ``prange``, one genome or
#: re-routed path per thread at a time, with its own scratch arrays).
MAX_THREADS = 4
#: Environment variable that switches the parallel searches on: a number of
#: threads, or ``auto`` (numba's thread count); unset or 1: serial.
THREADS_ENV = "GAPATH_THREADS"


def wanted_threads() -> int:
    """Threads the environment variable ``GAPATH_THREADS`` asks for (1,
    serial, when unset; ``auto``: numba's thread count), at most
    :data:`MAX_THREADS` and numba's count; 1 outside the main thread.

    Raises
    ------
    ConfigError
        When ``GAPATH_THREADS`` is neither a number nor ``auto``.
    """
    want = os.environ.get(THREADS_ENV, "1").strip().lower()
    nt = numba.get_num_threads()
    if want != "auto":
        try:
            nt = min(nt, int(want))
        except ValueError:
            raise ConfigError(f"{THREADS_ENV} must be a number of threads or 'auto', got {want!r}") from None
    if threading.current_thread() is not threading.main_thread():
        return 1
    return max(1, min(nt, MAX_THREADS))


#: Threads of :func:`wanted_threads` that background searches hold (see
#: :func:`hold_thread`).
_held = 0
_held_lock = threading.Lock()


def hold_thread() -> Callable[[], None]:
    """Count one of the :func:`wanted_threads` as busy until the returned
    function is called (the first call releases it, later ones nothing). A
    search running in a background thread (generation 1's approximate
    search, :class:`gapath.operators.archive.FreePathArchive`) holds one, so
    that the batches of :func:`search_threads` leave its core to it instead
    of waiting for a thread that shares that core."""
    global _held
    with _held_lock:
        _held += 1
    held = True

    def release() -> None:
        global _held
        nonlocal held
        with _held_lock:
            if held:
                held = False
                _held -= 1

    return release


def search_threads(n: int) -> int:
    """Threads for a batch of ``n`` searches: 0 (the serial kernels) unless
    :func:`wanted_threads`, less those a background search holds
    (:func:`hold_thread`), is more than one, and also with fewer than two
    searches per thread or outside the main thread (numba's ``workqueue``
    threading layer must not be entered from two threads at once). The
    paths do not depend on it.

    Serial is the default because the parallel batches wait for their
    slowest thread: on a machine whose cores are all busy (several runs at
    once, ``gapath multirun`` workers) they lost wall time in
    docs/results/free_paths.md ("Large maps"); on two idle cores two
    threads gave 1.5-1.7x the paths per second and 1.5x per generation
    (same file, "Parallel batches on idle cores").
    """
    nt = wanted_threads() - _held
    if nt < 2 or n < 2 * nt:
        return 0
    return nt


def default_n_via(shape) -> int:
    """Default number of via points for a map of ``shape`` ``(H, W)``."""
    return int(np.clip(round(max(shape) / 16) + 1, 2, 12))


def default_field_shape(shape) -> tuple[int, int]:
    """Default control grid ``(gy, gx)`` of the cost field for ``shape``."""
    h, w = shape
    return (
        min(int(np.clip(round(h / 6), 4, 12)), max(h, 2)),
        min(int(np.clip(round(w / 6), 4, 12)), max(w, 2)),
    )


def _check_int(value, name: str, lo: int) -> int:
    try:
        v = int(value)
        if isinstance(value, bool) or v != float(value):
            raise ValueError
    except (TypeError, ValueError, OverflowError):
        raise ConfigError(f"{name} must be an integer >= {lo}, got {value!r}") from None
    if v < lo:
        raise ConfigError(f"{name} must be an integer >= {lo}, got {value!r}")
    return v


class _RowCache:
    """Decoded paths of recently seen genomes, matched row by row (hashes
    sorted once per insertion, rows confirmed value by value), so the keys
    computed by duplicate elimination and the evaluation of the same rows
    decode them once."""

    def __init__(self, capacity: int = 8192):
        self.capacity = capacity
        self.clear()

    def clear(self):
        self.X = None
        self.hashes = self.order = None
        self.flat = np.zeros(0, np.int64)
        self.offsets = np.zeros(1, np.int64)
        self.keys = np.zeros((0, 3), np.int64)

    def lookup(self, X, hashes):
        """Index into the cache of every row of ``X`` (-1 when absent)."""
        idx = np.full(len(X), -1, np.int64)
        if self.X is None or len(X) == 0:
            return idx
        sh = self.hashes[self.order]
        p = np.minimum(np.searchsorted(sh, hashes), len(sh) - 1)
        cand = self.order[p]
        hit = (sh[p] == hashes) & (self.X[cand] == X).all(axis=1)
        idx[hit] = cand[hit]
        return idx

    def add(self, X, hashes, flat, offsets, keys):
        if self.X is not None and len(self.X) + len(X) > self.capacity:
            self.clear()
        if self.X is None:
            self.X, self.hashes = X.copy(), hashes.copy()
            self.flat, self.offsets, self.keys = flat, offsets, keys
        else:
            self.X = np.concatenate([self.X, X])
            self.hashes = np.concatenate([self.hashes, hashes])
            self.flat = np.concatenate([self.flat, flat])
            self.offsets = np.concatenate([self.offsets, offsets[1:] + self.offsets[-1]])
            self.keys = np.concatenate([self.keys, keys])
        self.order = np.argsort(self.hashes, kind="stable")


class FreeEncoding:
    """What the free-path encodings share (see the module docstring).

    Parameters
    ----------
    workspace : :class:`gapath.Workspace`.
    extra : (H, W) non-negative cell cost weighed against the length by the
        weight genes; default the workspace's potential field.
    lam_range : ``(lo, hi)``, the range of ``log10(b / a)`` of the weight
        genes.

    Raises
    ------
    NoPathError
        If the goal cannot be reached from the start.
    ConfigError
        On a bad ``extra`` layer or ``lam_range``.
    """

    name: str
    n_var: int

    name = "free"
    vtype = float

    def __init__(self, workspace, extra=None, lam_range=LAM_RANGE):
        self.workspace = workspace
        occ = read_only(workspace.occ)
        h, w = occ.shape
        self.shape = (h, w)
        self._occ = occ
        self._s = workspace.start[0] * w + workspace.start[1]
        self._t = workspace.goal[0] * w + workspace.goal[1]
        self._cc = bool(workspace.corner_cutting)
        comp = K.component(occ, self._s, self._cc)
        if not comp[self._t]:
            rule = "allowed" if self._cc else "not allowed"
            raise NoPathError(
                f"no feasible path from start {workspace.start} to goal {workspace.goal} in "
                f"{workspace.name!r} ({h}x{w}, 8-connected, corner cutting {rule}; "
                f"{int(comp.sum())} {'cell is' if int(comp.sum()) == 1 else 'cells are'} reachable from the start)"
            )
        self.n_reachable = int(comp.sum())
        self._snap = K.snap_table(comp, h, w)
        if extra is None:
            extra = workspace.potential
        extra = np.asarray(extra, dtype=np.float64)
        if extra.shape != (h, w) or not np.isfinite(extra).all() or (extra < 0).any():
            raise ConfigError(
                f"the cell cost of a free-path encoding must be a finite, "
                f"non-negative ({h}, {w}) array, got shape {extra.shape}"
            )
        self._extra = read_only(extra.ravel().copy())
        # exact costs-to-go to the goal (heuristics of searches that end there)
        self._hlen, self._hext = K.goal_heuristics(occ, self._extra, self._t, self._cc, False)
        self._pmin = float(self._extra[comp].min())
        self._flen, self._fext = K.goal_heuristics(occ, self._extra, self._s, self._cc, True)
        try:
            lo, hi = (float(v) for v in lam_range)
        except (TypeError, ValueError):
            raise ConfigError(f"lam_range must be two numbers (lo, hi), got {lam_range!r}") from None
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise ConfigError(f"lam_range must be two finite numbers lo < hi, got {lam_range!r}")
        self.lam_range = (lo, hi)
        self._cache = _RowCache()

    def __setstate__(self, state):
        # a copy or an unpickled encoding keeps its map arrays read-only, so
        # that its kernels are not compiled a second time (see read_only)
        self.__dict__.update(state)
        self._occ, self._extra = read_only(self._occ), read_only(self._extra)

    # -- the genome ------------------------------------------------------------
    def _setup_bounds(self):
        self.xl = np.zeros(self.n_var)
        self.xu = np.ones(self.n_var)

    def _genes(self, X) -> np.ndarray:
        X = np.atleast_2d(np.asarray(X, dtype=np.float64))
        if X.ndim != 2 or X.shape[1] != self.n_var:
            raise ConfigError(f"{self.name} genomes need {self.n_var} genes, got shape {X.shape}")
        if not np.isfinite(X).all():
            raise ConfigError(f"{self.name} genomes must be finite numbers")
        return np.ascontiguousarray(X)

    def _decode_kernel(self, X):
        raise NotImplementedError

    def decode_flat(self, X):
        """``(flat, offsets, keys)``: path ``i`` is
        ``flat[offsets[i]:offsets[i + 1]]`` (row-major cell indices),
        ``keys[i]`` its identity (see :meth:`path_keys`)."""
        X = self._genes(X)
        hashes = K.row_hash(X)
        idx = self._cache.lookup(X, hashes)
        miss = np.flatnonzero(idx < 0)
        if len(miss) == len(X):
            flat, offsets, keys = self._decode_kernel(X)
            self._cache.add(X, hashes, flat, offsets, keys)
            return flat, offsets, keys
        c = self._cache
        if len(miss) == 0:
            flat, offsets = K.gather(c.flat, c.offsets, c.flat, c.offsets, np.zeros(len(X), np.int64), idx)
            return flat, offsets, c.keys[idx]
        mflat, moff, mkeys = self._decode_kernel(X[miss])
        src = (idx < 0).astype(np.int64)
        pick = idx.copy()
        pick[miss] = np.arange(len(miss))
        flat, offsets = K.gather(c.flat, c.offsets, mflat, moff, src, pick)
        keys = np.empty((len(X), 3), np.int64)
        keys[miss] = mkeys
        hit = np.flatnonzero(idx >= 0)
        keys[hit] = c.keys[idx[hit]]
        self._cache.add(X[miss], hashes[miss], mflat, moff, mkeys)
        return flat, offsets, keys

    def decode(self, X) -> tuple[np.ndarray, np.ndarray]:
        """Padded paths ``(N, L, 2)`` (workspace cells, zeros past each
        length) and their lengths ``(N,)`` of the genomes ``X`` (N, n_var);
        genes outside [0, 1] act as the nearest bound.

        Raises
        ------
        ConfigError
            If ``X`` does not have ``n_var`` columns or holds NaN or infinite
            values.
        """
        flat, offsets, _ = self.decode_flat(X)
        return K.to_padded(flat, offsets, self.shape[1])

    def path_keys(self, X) -> np.ndarray:
        """``(N, 3)`` int64 identity rows of the decoded paths: number of
        cells and two 64-bit hashes of the cell sequence."""
        return self.decode_flat(X)[2]

    def edge_fix(self, X, random_state=None) -> np.ndarray:
        """Genes clipped to [0, 1] (the repair gapath's GA engines call)."""
        return np.clip(np.asarray(X, dtype=np.float64), 0.0, 1.0)

    # -- paths -> genomes --------------------------------------------------------
    def weight_gene(self, lam: float) -> float:
        """The weight gene whose cell-cost weight ``b / a`` is ``lam``."""
        lo, hi = self.lam_range
        return float(np.clip((math.log10(lam) - lo) / (hi - lo), 0.0, 1.0))

    def weighted_paths(self, genes) -> list[np.ndarray]:
        """The optimal paths under the step cost of each weight gene in
        ``genes`` with a neutral field (what a genome of the field encoding
        with all control genes 0.5 decodes to)."""
        genes = np.ascontiguousarray(np.atleast_1d(np.asarray(genes, dtype=np.float64)))
        flat, offsets, _ = K.weighted_paths(
            self._occ, self._extra, self._s, self._t, self._cc, genes, *self.lam_range, self._hlen, self._hext
        )
        P, L = K.to_padded(flat, offsets, self.shape[1])
        return [P[i, : L[i]].copy() for i in range(len(L))]

    def padded(self, flat, offsets) -> tuple[np.ndarray, np.ndarray]:
        """Flat paths ``(flat, offsets)`` as padded ``(N, L, 2)`` cells and
        lengths ``(N,)`` (what :meth:`decode` returns)."""
        return K.to_padded(np.asarray(flat, np.int64), np.asarray(offsets, np.int64), self.shape[1])

    @staticmethod
    def take_flat(flat, offsets, idx) -> tuple[np.ndarray, np.ndarray]:
        """The flat paths ``idx`` (an integer array) of ``(flat, offsets)``."""
        idx = np.ascontiguousarray(idx, np.int64)
        return K.gather(flat, offsets, flat, offsets, np.zeros(len(idx), np.int64), idx)

    @staticmethod
    def concat_flat(flat_a, off_a, flat_b, off_b) -> tuple[np.ndarray, np.ndarray]:
        """Flat paths ``a`` followed by flat paths ``b``."""
        return np.concatenate([flat_a, flat_b]), np.concatenate([off_a, off_b[1:] + off_a[-1]])

    def reroute(
        self,
        flat,
        offsets,
        pick,
        i0,
        i1,
        genes,
        lam_range=None,
        turn_genes=None,
        turn_range=(-2.0, 2.0),
        margin=REROUTE_MARGIN,
    ):
        """Paths made by re-routing one segment of given paths.

        Row ``r`` takes path ``pick[r]`` of the flat paths ``(flat,
        offsets)`` (row-major cell indices, as :meth:`decode_flat` returns
        them), replaces its cells between positions ``i0[r] < i1[r]`` by the
        optimal path between those two cells under the weight gene
        ``genes[r]`` (the step cost of :meth:`weighted_paths`) and cuts the
        loops the splice makes: every result is a simple path from the start
        to the goal that obeys the corner rule. Positions are clipped to the
        path. ``lam_range`` (default the encoding's) maps the weight genes
        to ``log10(b / a)`` as in the module docstring. With ``turn_genes``
        (one per row in [0, 1]) the searches run over (cell, last move)
        states and also weigh turns: ``c`` per radian of turn, ``log10(c /
        a)`` spread over ``turn_range`` by the gene, the turns where the
        segment meets the rest of the path included. Each search stays
        inside the box around the stretch's two ends widened by ``max(margin,
        extent)`` cells on every side (``extent`` the larger side of that
        box; ``margin < 0``: the whole map), which bounds its cost on large
        maps; the result is the optimal path inside that box.

        Returns
        -------
        flat, offsets, keys : as :meth:`decode_flat`.

        Examples
        --------
        >>> import numpy as np
        >>> from gapath import Workspace
        >>> enc = FieldEncoding(Workspace(np.zeros((4, 4), bool)))
        >>> flat, off, _ = enc.decode_flat(np.full((1, enc.n_var), 0.5))
        >>> f2, o2, _ = enc.reroute(flat, off, np.array([0]), np.array([0]), np.array([99]), np.array([0.0]))
        >>> (f2[0], f2[-1]) == (flat[0], flat[-1])
        True
        """
        i = lambda a: np.ascontiguousarray(a, np.int64)  # noqa: E731
        lo, hi = self.lam_range if lam_range is None else (float(v) for v in lam_range)
        margin = int(margin)
        nt = search_threads(len(pick))
        if turn_genes is not None:
            args = (
                i(flat),
                i(offsets),
                i(pick),
                i(i0),
                i(i1),
                np.ascontiguousarray(genes, np.float64),
                np.ascontiguousarray(turn_genes, np.float64),
                self._occ,
                self._extra,
                self._cc,
                lo,
                hi,
                float(turn_range[0]),
                float(turn_range[1]),
                margin,
                self._pmin,
                self._hlen,
                self._hext,
                self._flen,
                self._fext,
            )
            return K.reroute_turns_par(*args, nt) if nt else K.reroute_turns(*args)
        args = (
            i(flat),
            i(offsets),
            i(pick),
            i(i0),
            i(i1),
            np.ascontiguousarray(genes, np.float64),
            self._occ,
            self._extra,
            self._cc,
            lo,
            hi,
            self._t,
            self._hlen,
            self._hext,
            self._pmin,
            self._flen,
            self._fext,
            margin,
        )
        return K.reroute_par(*args, nt) if nt else K.reroute(*args)

    def shortcut(self, flat, offsets, pick, i0, i1, diagonal_first):
        """Paths made by straightening one segment of given paths: as
        :meth:`reroute`, but the cells between positions ``i0[r] < i1[r]``
        become the octile path with one bend between their ends (diagonal
        steps first where ``diagonal_first[r]``), the shortest path between
        them with at most one turn, when it is free and obeys the corner
        rule (else the row keeps its path).

        Returns
        -------
        flat, offsets, keys : as :meth:`decode_flat`.

        Examples
        --------
        >>> import numpy as np
        >>> from gapath import Workspace
        >>> enc = FieldEncoding(Workspace(np.zeros((3, 3), bool)))
        >>> flat = np.array([6, 3, 4, 1, 2]); off = np.array([0, 5])
        >>> f2, o2, _ = enc.shortcut(flat, off, [0], [0], [4], [True])
        >>> f2.tolist()
        [6, 4, 2]
        """
        i = lambda a: np.ascontiguousarray(a, np.int64)  # noqa: E731
        return K.shortcut(
            i(flat),
            i(offsets),
            i(pick),
            i(i0),
            i(i1),
            np.ascontiguousarray(diagonal_first, np.bool_),
            self._occ,
            self._cc,
        )

    def _flat_paths(self, paths):
        h, w = self.shape
        cells, lengths = [], []
        for i, p in enumerate(paths):
            p = np.asarray(p, dtype=np.int64).reshape(-1, 2)
            if len(p) < 2 or tuple(p[0]) != self.workspace.start or tuple(p[-1]) != self.workspace.goal:
                raise ConfigError(
                    f"path {i} does not run from start {self.workspace.start} to goal {self.workspace.goal}"
                )
            if (p < 0).any() or (p[:, 0] >= h).any() or (p[:, 1] >= w).any():
                raise ConfigError(f"path {i} leaves the {h}x{w} grid")
            if (np.abs(np.diff(p, axis=0)).max(axis=1) != 1).any():
                raise ConfigError(f"path {i} has a step that is not 8-adjacent")
            cells.append(p[:, 0] * w + p[:, 1])
            lengths.append(len(p))
        offsets = np.concatenate([[0], np.cumsum(lengths)]).astype(np.int64)
        flat = np.concatenate(cells).astype(np.int64) if cells else np.zeros(0, np.int64)
        return flat, offsets

    def _fit(self, flat, offsets, via_idx):
        return K.fit_segment_weights(
            flat,
            offsets,
            np.ascontiguousarray(via_idx, np.int64),
            self._occ,
            self._extra,
            self._cc,
            FIT_CANDIDATES,
            *self.lam_range,
            self._t,
            self._hlen,
            self._hext,
            self._pmin,
            self._flen,
            self._fext,
        )


class ViaPointEncoding(FreeEncoding):
    """Via points joined by shortest segments, one weight per segment.

    Parameters
    ----------
    workspace, extra, lam_range : see :class:`FreeEncoding`.
    n_via : number of via points ``K >= 0`` (default
        :func:`default_n_via`); ``n_var = 3 K + 1``.

    Raises
    ------
    ConfigError
        If ``n_via`` is not an integer >= 0.
    NoPathError
        If the goal cannot be reached from the start.
    """

    name = "via"

    def __init__(self, workspace, n_via=None, extra=None, lam_range=LAM_RANGE):
        n_via = default_n_via(workspace.shape) if n_via is None else _check_int(n_via, "n_via", 0)
        super().__init__(workspace, extra, lam_range)
        self.n_via = n_via
        self.n_var = 3 * n_via + 1
        self._setup_bounds()

    def _decode_kernel(self, X):
        args = (
            X,
            self.n_via,
            self._occ,
            self._extra,
            self._snap,
            self._s,
            self._t,
            self._cc,
            *self.lam_range,
            self._hlen,
            self._hext,
            self._pmin,
            self._flen,
            self._fext,
        )
        nt = search_threads(len(X))
        return K.decode_via_par(*args, nt) if nt else K.decode_via(*args)

    def encode(self, paths, weights=None) -> np.ndarray:
        """Genomes of paths (workspace cells, start to goal).

        The via points are spread evenly along each path (by cell count); the
        segment weights are ``weights`` (one weight gene per path, e.g. the
        one a weighted planner used) or, by default, fitted: for each segment
        the candidate weight gene whose search reproduces the sub-path best.
        A genome reproduces its path exactly when every segment search does.

        Raises
        ------
        ConfigError
            If a path does not run from start to goal in 8-adjacent steps.
        """
        flat, offsets = self._flat_paths(paths)
        n, k = len(offsets) - 1, self.n_via
        h, w = self.shape
        X = np.zeros((n, self.n_var))
        lengths = np.diff(offsets)
        frac = np.arange(k + 2) / (k + 1)
        via_idx = np.rint(frac[None, :] * (lengths[:, None] - 1)).astype(np.int64)
        cells = flat[offsets[:-1, None] + via_idx[:, 1:-1]]
        X[:, 0 : 2 * k : 2] = (cells // w + 0.5) / h
        X[:, 1 : 2 * k : 2] = (cells % w + 0.5) / w
        if weights is None:
            X[:, 2 * k :] = self._fit(flat, offsets, via_idx)
        else:
            X[:, 2 * k :] = np.asarray(weights, dtype=float).reshape(-1, 1)
        return X

    def __repr__(self) -> str:
        return f"ViaPointEncoding(n_via={self.n_via}, n_var={self.n_var})"


class FieldEncoding(FreeEncoding):
    """A coarse cost-multiplier field decoded by one shortest-path search.

    Parameters
    ----------
    workspace, extra, lam_range : see :class:`FreeEncoding`.
    field_shape : ``(gy, gx)`` control points (default
        :func:`default_field_shape`), each between 2 and the map's size on
        its axis; ``n_var = gy * gx + 1``.
    beta : log of the largest multiplier (default ln 4).

    Raises
    ------
    ConfigError
        If the field has fewer than 2 or more control points than the map has
        cells on an axis, or ``beta`` is not a positive number.
    NoPathError
        If the goal cannot be reached from the start.
    """

    name = "field"

    def __init__(self, workspace, field_shape=None, beta=math.log(4.0), extra=None, lam_range=LAM_RANGE):
        h, w = workspace.shape
        if field_shape is None:
            field_shape = default_field_shape((h, w))
        try:
            gy, gx = field_shape
        except (TypeError, ValueError):
            raise ConfigError(f"field_shape must be a pair (rows, cols), got {field_shape!r}") from None
        gy = _check_int(gy, "field_shape rows", 2)
        gx = _check_int(gx, "field_shape cols", 2)
        if gy > max(h, 2) or gx > max(w, 2):
            raise ConfigError(
                f"field_shape {(gy, gx)} is finer than the {h}x{w} map: at most "
                f"one control point per cell on each axis"
            )
        try:
            beta = float(beta)
        except (TypeError, ValueError):
            raise ConfigError(f"beta must be a positive number, got {beta!r}") from None
        if not (math.isfinite(beta) and beta > 0):
            raise ConfigError(f"beta must be a positive number, got {beta!r}")
        super().__init__(workspace, extra, lam_range)
        self.field_shape = (gy, gx)
        self.beta = beta
        self.n_var = gy * gx + 1
        self._setup_bounds()

    def _decode_kernel(self, X):
        gy, gx = self.field_shape
        args = (
            X,
            gy,
            gx,
            self.beta,
            self._occ,
            self._extra,
            self._s,
            self._t,
            self._cc,
            *self.lam_range,
            self._hlen,
            self._hext,
        )
        nt = search_threads(len(X))
        return K.decode_field_par(*args, nt) if nt else K.decode_field(*args)

    def encode(self, paths, weights=None) -> np.ndarray:
        """Genomes of paths: a neutral field (control genes 0.5) and the
        weight gene ``weights`` (one per path) or, by default, the candidate
        weight gene whose search reproduces the path best. Exact for the
        paths of :meth:`weighted_paths`.

        Raises
        ------
        ConfigError
            If a path does not run from start to goal in 8-adjacent steps.
        """
        flat, offsets = self._flat_paths(paths)
        n = len(offsets) - 1
        X = np.full((n, self.n_var), 0.5)
        if weights is None:
            via_idx = np.stack([np.zeros(n, np.int64), np.diff(offsets) - 1], axis=1)
            X[:, -1] = self._fit(flat, offsets, via_idx)[:, 0]
        else:
            X[:, -1] = np.asarray(weights, dtype=float).reshape(-1)
        return X

    def __repr__(self) -> str:
        return f"FieldEncoding(field_shape={self.field_shape}, n_var={self.n_var})"


#: Free-path encodings by name.
FREE_ENCODINGS = {"via": ViaPointEncoding, "field": FieldEncoding}
#: The default free-path encoding (see docs/results/free_paths.md).
DEFAULT_FREE_ENCODING = "field"


def make_free_encoding(name: str, workspace, **options):
    """The free-path encoding called ``name`` over ``workspace``.

    Raises
    ------
    ConfigError
        If ``name`` is not one of :data:`FREE_ENCODINGS` or an option is bad.
    NoPathError
        If the goal cannot be reached from the start.
    """
    try:
        cls = FREE_ENCODINGS[name]
    except (KeyError, TypeError):
        raise ConfigError(
            f"unknown encoding {name!r} for free paths; expected one of {', '.join(FREE_ENCODINGS)}"
        ) from None
    import inspect

    allowed = set(inspect.signature(cls).parameters) - {"workspace"}
    unknown = sorted(set(options) - allowed)
    if unknown:
        raise ConfigError(
            f"option {unknown[0]!r} does not apply to the {name!r} encoding; "
            f"its options are {', '.join(sorted(allowed))}"
        )
    return cls(workspace, **options)


__all__ = [
    "DEFAULT_FREE_ENCODING",
    "FREE_ENCODINGS",
    "MAX_THREADS",
    "REROUTE_MARGIN",
    "THREADS_ENV",
    "FieldEncoding",
    "FreeEncoding",
    "ViaPointEncoding",
    "default_field_shape",
    "default_n_via",
    "make_free_encoding",
    "hold_thread",
    "search_threads",
    "wanted_threads",
]
