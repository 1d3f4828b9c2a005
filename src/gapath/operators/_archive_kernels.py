"""Numba kernels of :mod:`gapath.operators.archive` (private)."""

from __future__ import annotations

import numba
import numpy as np

from gapath.encodings._free_kernels import _append, _store


@numba.njit(cache=True)
def splice(flat, offsets, pick, i0, i1, sub_flat, sub_off, n_cells):
    """Row ``r``: path ``pick[r]`` of ``(flat, offsets)`` with its cells
    between positions ``i0[r] <= i1[r]`` replaced by sub-path ``r`` of
    ``(sub_flat, sub_off)`` (which runs from the cell at ``i0[r]`` to the
    one at ``i1[r]``), loops cut; returns ``(flat, offsets, keys)`` as the
    free encodings' decoders (same identity keys)."""
    n = len(pick)
    out = np.empty(max(1, len(sub_flat) + n * 8), np.int64)
    off = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    pos = np.full(n_cells, -1, np.int64)
    cur = np.empty(n_cells, np.int64)
    for r in range(n):
        a, b = offsets[pick[r]], offsets[pick[r] + 1]
        m = 0
        for j in range(a, a + i0[r]):
            m = _append(flat[j], cur, pos, m)
        for j in range(sub_off[r], sub_off[r + 1]):
            m = _append(sub_flat[j], cur, pos, m)
        for j in range(a + i1[r] + 1, b):
            m = _append(flat[j], cur, pos, m)
        out = _store(cur, m, r, out, off, keys)
        for q in range(m):
            pos[cur[q]] = -1
    return out[: off[n]], off, keys


@numba.njit(cache=True)
def keyed(sub_flat, sub_off, n_cells):
    """The paths ``(sub_flat, sub_off)`` with loops cut, as ``(flat,
    offsets, keys)`` of the free encodings' decoders (same identity keys)."""
    n = len(sub_off) - 1
    out = np.empty(max(1, len(sub_flat)), np.int64)
    off = np.zeros(n + 1, np.int64)
    keys = np.empty((n, 3), np.int64)
    pos = np.full(n_cells, -1, np.int64)
    cur = np.empty(n_cells, np.int64)
    for r in range(n):
        m = 0
        for j in range(sub_off[r], sub_off[r + 1]):
            m = _append(sub_flat[j], cur, pos, m)
        out = _store(cur, m, r, out, off, keys)
        for q in range(m):
            pos[cur[q]] = -1
    return out[: off[n]], off, keys
