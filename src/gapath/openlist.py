"""The open list of one-shot grid searches, as numba kernels.

A compact indexed binary min-heap in one preallocated float array, ordered
by ``(key1, key2, node)`` lexicographically (ties broken deterministically),
that holds back an entry smaller than the whole heap instead of pushing it.
A* (:mod:`gapath.planners.astar`) and the free encodings' decoders
(:mod:`gapath.encodings.free`) search with it; it sits on the ground floor
so that both use it without one importing the other's private modules.
"""

from __future__ import annotations

import numba

__all__ = ["HELD", "NOT_HELD", "open_decrease", "open_pop", "open_push"]


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
