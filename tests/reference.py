"""Plain-Python reference implementations the numba kernels are tested against."""

import math

import numpy as np


def potential(occ, s2=0.5):
    """Sum over ALL obstacle cells (no window)."""
    h, w = occ.shape
    obs = np.argwhere(occ)
    pot = np.zeros((h, w))
    for r in range(h):
        for c in range(w):
            for orow, ocol in obs:
                pot[r, c] += math.exp(-((r - orow) ** 2 + (c - ocol) ** 2) / (2 * s2))
    return pot


def metrics(occ, path, cell_size=1.0, corner_cutting=True):
    pot = potential(occ)
    path = [tuple(int(v) for v in p) for p in path]
    length = sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(path, path[1:])) * cell_size
    vul = sum(pot[p] for p in path)
    smooth = 0.0
    for a, b, c in zip(path, path[1:], path[2:]):
        h1 = math.atan2(-(b[0] - a[0]), b[1] - a[1])
        h2 = math.atan2(-(c[0] - b[0]), c[1] - b[1])
        d = abs(h2 - h1) % (2 * math.pi)
        smooth += min(d, 2 * math.pi - d)
    interf = sum(bool(occ[p]) for p in path)
    if not corner_cutting:
        for a, b in zip(path, path[1:]):
            if a[0] != b[0] and a[1] != b[1] and (occ[a[0], b[1]] or occ[b[0], a[1]]):
                interf += 1
    return length, vul, smooth, interf
