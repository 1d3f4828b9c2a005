"""Numba helpers shared by the grid searches (:mod:`.astar`, :mod:`.dstar_lite`,
:mod:`.hybrid_astar`, the free encodings' decoders).

The move rules themselves (moves, corner rule, octile distance, cell checks)
are :mod:`gapath.grid`'s; here are

* the heuristics of the searches (:data:`HEURISTICS`, :func:`heuristic`),
* an *indexed* binary min-heap kept in preallocated arrays (cells and their
  two keys in heap order, and ``pos[cell]``, the cell's slot), ordered by
  ``(key1, key2, cell index)`` lexicographically, so ties are broken
  deterministically,
* (the open list of one-shot searches, shared with the free encodings'
  decoders, is :mod:`gapath.openlist`),
* the cost of a finished path under a cost layer.

Everything here works in cell units; callers scale by ``cell_size``.
"""

from __future__ import annotations

import math

import numba

from gapath.grid import SQRT2, ZERO, octile

# ---------------------------------------------------------------------------
# heuristics
# ---------------------------------------------------------------------------

#: Heuristic codes of the kernels.
HEURISTICS = {"octile": 0, "euclidean": 1, "chebyshev": 2, "zero": 3}


@numba.njit(cache=True, inline="always")
def heuristic(kind, r1, c1, r2, c2):
    """Heuristic code ``kind`` (see :data:`HEURISTICS`) between two cells."""
    if kind == 0:
        return octile(r1, c1, r2, c2)
    dr = abs(r1 - r2)
    dc = abs(c1 - c2)
    if kind == 1:
        return math.sqrt(dr * dr + dc * dc)
    if kind == 2:
        return float(max(dr, dc))
    return 0.0


# ---------------------------------------------------------------------------
# indexed binary heap on (key1, key2, node)
# ---------------------------------------------------------------------------
# The heap is three arrays in heap order -- ``hnode`` (cell index), ``hk1``,
# ``hk2`` (its keys) -- so that sifting reads contiguous memory, plus
# ``pos[node]``, the node's slot (callers mark nodes that are not in the heap
# with negative values; pop and remove set -1). Keys compare
# lexicographically, then the smaller node index wins: ties are deterministic.


@numba.njit(cache=True, inline="always")
def _before(a1, a2, an, b1, b2, bn):
    if a1 != b1:
        return a1 < b1
    if a2 != b2:
        return a2 < b2
    return an < bn


@numba.njit(cache=True)
def heap_sift_up(hnode, hk1, hk2, pos, i):
    node = hnode[i]
    k1 = hk1[i]
    k2 = hk2[i]
    while i > 0:
        parent = (i - 1) >> 1
        if not _before(k1, k2, node, hk1[parent], hk2[parent], hnode[parent]):
            break
        hnode[i] = hnode[parent]
        hk1[i] = hk1[parent]
        hk2[i] = hk2[parent]
        pos[hnode[i]] = i
        i = parent
    hnode[i] = node
    hk1[i] = k1
    hk2[i] = k2
    pos[node] = i


@numba.njit(cache=True)
def heap_sift_down(hnode, hk1, hk2, pos, i, size):
    node = hnode[i]
    k1 = hk1[i]
    k2 = hk2[i]
    while True:
        child = 2 * i + 1
        if child >= size:
            break
        right = child + 1
        if right < size and _before(
            hk1[right], hk2[right], hnode[right], hk1[child], hk2[child], hnode[child]
        ):
            child = right
        if not _before(hk1[child], hk2[child], hnode[child], k1, k2, node):
            break
        hnode[i] = hnode[child]
        hk1[i] = hk1[child]
        hk2[i] = hk2[child]
        pos[hnode[i]] = i
        i = child
    hnode[i] = node
    hk1[i] = k1
    hk2[i] = k2
    pos[node] = i


@numba.njit(cache=True)
def heap_push(hnode, hk1, hk2, pos, size, node, k1, k2):
    """Insert ``node`` with key ``(k1, k2)``; return the new size."""
    hnode[size] = node
    hk1[size] = k1
    hk2[size] = k2
    heap_sift_up(hnode, hk1, hk2, pos, size)
    return size + 1


@numba.njit(cache=True)
def heap_pop(hnode, hk1, hk2, pos, size):
    """Remove the smallest node; return ``(node, new size)``."""
    top = hnode[0]
    pos[top] = -1
    size -= 1
    if size > 0:
        hnode[0] = hnode[size]
        hk1[0] = hk1[size]
        hk2[0] = hk2[size]
        heap_sift_down(hnode, hk1, hk2, pos, ZERO, size)
    return top, size


@numba.njit(cache=True)
def heap_update(hnode, hk1, hk2, pos, size, node, k1, k2):
    """Give ``node`` (in the heap) the key ``(k1, k2)``."""
    i = pos[node]
    hk1[i] = k1
    hk2[i] = k2
    heap_sift_up(hnode, hk1, hk2, pos, i)
    heap_sift_down(hnode, hk1, hk2, pos, pos[node], size)


@numba.njit(cache=True)
def heap_decrease(hnode, hk1, hk2, pos, node, k1, k2):
    """Give ``node`` (in the heap) a key that is not larger than its old one."""
    i = pos[node]
    hk1[i] = k1
    hk2[i] = k2
    heap_sift_up(hnode, hk1, hk2, pos, i)


@numba.njit(cache=True)
def heap_remove(hnode, hk1, hk2, pos, size, node):
    """Remove ``node`` (in the heap); return the new size."""
    i = pos[node]
    pos[node] = -1
    size -= 1
    if i < size:
        hnode[i] = hnode[size]
        hk1[i] = hk1[size]
        hk2[i] = hk2[size]
        moved = hnode[i]
        pos[moved] = i
        heap_sift_up(hnode, hk1, hk2, pos, i)
        heap_sift_down(hnode, hk1, hk2, pos, pos[moved], size)
    return size


# ---------------------------------------------------------------------------
# finished paths
# ---------------------------------------------------------------------------


@numba.njit(cache=True)
def layer_path_cost(path, cost):
    """Cost of a path under a cost layer, in cell units, summed from the
    start: each step costs its length times ``1 + (cost[a] + cost[b]) / 2``."""
    total = 0.0
    for i in range(1, path.shape[0]):
        r0, c0 = path[i - 1, 0], path[i - 1, 1]
        r1, c1 = path[i, 0], path[i, 1]
        step = SQRT2 if (r0 != r1 and c0 != c1) else 1.0
        total += step * (1.0 + 0.5 * (cost[r0, c0] + cost[r1, c1]))
    return total
