"""Numba helpers shared by the grid searches (:mod:`.astar`, :mod:`.dstar_lite`,
:mod:`.hybrid_astar`, the free encodings' decoders).

The move rules themselves (moves, corner rule, octile distance, cell checks)
are :mod:`gapath.grid`'s; here are

* the heuristics of the searches (:data:`HEURISTICS`, :func:`heuristic`),
* an *indexed* binary min-heap kept in preallocated arrays (cells and their
  two keys in heap order, and ``pos[cell]``, the cell's slot), ordered by
  ``(key1, key2, cell index)`` lexicographically, so ties are broken
  deterministically,
* the open list of one-shot searches (A*): a compact indexed heap in the same
  order that holds back an entry smaller than the whole heap instead of
  pushing it,
* the cost of a finished path under a cost layer.

Everything here works in cell units; callers scale by ``cell_size``.
"""

from __future__ import annotations

import math

import numba

from gapath.grid import SQRT2, octile

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
        heap_sift_down(hnode, hk1, hk2, pos, 0, size)
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
# open list of a one-shot search: flat indexed heap plus a held-back minimum
# ---------------------------------------------------------------------------
# For A*-like searches that only push, decrease and pop (no removal, no key
# increase). Entry ``i`` of the heap is ``heap[3 * i : 3 * i + 3] = (key1,
# key2, node)`` (node indices are exact in a float64), so moving an entry moves
# one short contiguous run; entries ``0 .. size - 1`` form a binary min-heap in
# the same order as above: lexicographic on the keys, then the smaller node.
#
# ``held`` is one more entry ``(key1, key2, node)`` kept outside the heap
# (``node == -1``: none). A pushed entry that sorts before the whole heap --
# typically the best successor of the cell just expanded -- is held instead of
# being sifted up and popped straight back down (one comparison instead of two
# traversals). The held entry always sorts before every heap entry, so pops
# come out exactly as from a plain heap.
#
# ``where[node]`` is ``heap index + 1`` while the node is in the heap and
# ``HELD`` while it is held; callers keep their own codes (<= 0, other than
# ``HELD``) there for nodes that are not open.

#: ``where[node]`` of the held node.
HELD = -2
#: ``held`` when no entry is held.
NOT_HELD = (0.0, 0.0, -1)


@numba.njit(cache=True, inline="always")
def _precedes(a1, a2, an, b1, b2, bn):
    """``(a1, a2, an) < (b1, b2, bn)`` lexicographically, without branches."""
    return (a1 < b1) | ((a1 == b1) & ((a2 < b2) | ((a2 == b2) & (an < bn))))


@numba.njit(cache=True, inline="always")
def _open_sift_up(heap, where, i, k1, k2, node):
    """Place the entry ``(k1, k2, node)`` at heap index ``i`` or above."""
    fnode = float(node)
    while i > 0:
        p = (i - 1) >> 1
        if not _precedes(k1, k2, fnode, heap[3 * p], heap[3 * p + 1], heap[3 * p + 2]):
            break
        heap[3 * i] = heap[3 * p]
        heap[3 * i + 1] = heap[3 * p + 1]
        heap[3 * i + 2] = heap[3 * p + 2]
        where[int(heap[3 * i + 2])] = i + 1
        i = p
    heap[3 * i] = k1
    heap[3 * i + 1] = k2
    heap[3 * i + 2] = fnode
    where[node] = i + 1


@numba.njit(cache=True, inline="always")
def open_push(heap, where, size, held, k1, k2, node):
    """Add ``node`` (not open) with key ``(k1, k2)``; return ``(size, held)``.

    ``heap`` needs room for ``3 * n`` values for nodes ``0 .. n - 1``.
    """
    if held[2] >= 0:
        if not _precedes(k1, k2, node, held[0], held[1], held[2]):
            _open_sift_up(heap, where, size, k1, k2, node)
            return size + 1, held
        _open_sift_up(heap, where, size, held[0], held[1], held[2])  # hold the new one
        where[node] = HELD
        return size + 1, (k1, k2, node)
    if size == 0 or _precedes(k1, k2, node, heap[0], heap[1], heap[2]):
        where[node] = HELD  # before the whole heap
        return size, (k1, k2, node)
    _open_sift_up(heap, where, size, k1, k2, node)
    return size + 1, held


@numba.njit(cache=True, inline="always")
def open_decrease(heap, where, held, k1, k2, node):
    """Give the open ``node`` a key not larger than its old one; return ``held``."""
    i = where[node]
    if i == HELD:  # smaller still: stays held
        return (k1, k2, node)
    _open_sift_up(heap, where, i - 1, k1, k2, node)
    if held[2] >= 0 and where[node] == 1 and _precedes(k1, k2, node, held[0], held[1], held[2]):
        heap[0] = held[0]  # now before the held entry: swap them
        heap[1] = held[1]
        heap[2] = float(held[2])
        where[held[2]] = 1
        where[node] = HELD
        return (k1, k2, node)
    return held


@numba.njit(cache=True, inline="always")
def open_pop(heap, where, size, held):
    """Remove the smallest entry; return ``(node, size, held)``, node -1 when
    the open list is empty. ``where[node]`` is left to the caller."""
    if held[2] >= 0:
        return held[2], size, NOT_HELD
    if size == 0:
        return -1, size, held
    node = int(heap[2])
    size -= 1
    k1 = heap[3 * size]  # the last entry sinks from the root
    k2 = heap[3 * size + 1]
    fnode = heap[3 * size + 2]
    i = 0
    while True:
        c = 2 * i + 1
        if c >= size:
            break
        if c + 1 < size:  # the smaller child, branch-free
            c += _precedes(
                heap[3 * c + 3],
                heap[3 * c + 4],
                heap[3 * c + 5],
                heap[3 * c],
                heap[3 * c + 1],
                heap[3 * c + 2],
            )
        if not _precedes(heap[3 * c], heap[3 * c + 1], heap[3 * c + 2], k1, k2, fnode):
            break
        heap[3 * i] = heap[3 * c]
        heap[3 * i + 1] = heap[3 * c + 1]
        heap[3 * i + 2] = heap[3 * c + 2]
        where[int(heap[3 * i + 2])] = i + 1
        i = c
    if size > 0:
        heap[3 * i] = k1
        heap[3 * i + 1] = k2
        heap[3 * i + 2] = fnode
        where[int(fnode)] = i + 1
    return node, size, held


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
