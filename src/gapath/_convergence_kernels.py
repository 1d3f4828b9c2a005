"""numba kernel of :mod:`gapath.convergence`: dominance up to a tolerance,
computed exactly as :func:`gapath.metrics.nondominated` computes it."""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["dominated_by"]


@numba.njit(cache=True, inline="always")
def _close(a, b, tol):
    # gapath.metrics.close: |a - b| <= tol * max(1, |a|, |b|), same operations
    return abs(a - b) <= tol * max(1.0, max(abs(a), abs(b)))


@numba.njit(cache=True)
def dominated_by(B, A, tol):
    """For each row of ``B`` (n, m): whether a row of ``A`` (k, m) dominates
    it up to ``tol``: every ``a_i`` is smaller than or close to ``b_i`` and
    some ``a_i`` is smaller and not close (finite values)."""
    n, m = B.shape
    out = np.zeros(n, np.bool_)
    for r in range(n):
        for q in range(A.shape[0]):
            not_worse = True
            better = False
            for i in range(m):
                a, b = A[q, i], B[r, i]
                eq = _close(a, b, tol)
                if not (a <= b or eq):
                    not_worse = False
                    break
                if a < b and not eq:
                    better = True
            if not_worse and better:
                out[r] = True
                break
    return out
