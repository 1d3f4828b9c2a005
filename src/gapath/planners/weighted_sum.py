"""Single-objective optima over column-monotone paths, by dynamic programming.

:func:`weighted_sum_path` minimises ``w_length * length + w_vulnerability *
vulnerability`` over the feasible column-monotone paths (the path set of the
integer encoding, SPEC), column by column: the state is the exit row of the
current column, the transition from exit row ``p`` to exit row ``e`` of the
next column is one horizontal or diagonal step towards ``e`` and then
vertical steps to ``e``. Costs of vertical runs come from per-column prefix
sums, so a plan costs O(columns x rows^2).

:func:`weighted_sum_paths` gives the shortest path, the safest path and the
optima of evenly spread weights on the normalised objectives: the
"single-objective optimal paths" that seed a GA population
(:class:`gapath.operators.PlannerSampling`).
"""

from __future__ import annotations

import numba
import numpy as np

from gapath.errors import ConfigError, NoPathError
from gapath.grid import SQRT2, cuts_corner
from gapath.monotone import Frame, expand_profiles, split_paths
from gapath.objectives import LENGTH, VULNERABILITY, evaluate_paths, pad_paths


@numba.njit(cache=True)
def _weighted_dp(occ, pot, start_row, goal_row, col0, n_cols, w_len, w_vul, cell_size, corner_cutting):
    h = occ.shape[0]
    inf = np.inf
    # prefix sums down each used column: potential and obstacle count
    cum_pot = np.zeros((n_cols, h + 1))
    cum_occ = np.zeros((n_cols, h + 1), np.int64)
    for k in range(n_cols):
        for r in range(h):
            cum_pot[k, r + 1] = cum_pot[k, r] + pot[r, col0 + k]
            cum_occ[k, r + 1] = cum_occ[k, r] + (1 if occ[r, col0 + k] else 0)
    cost = np.full((n_cols, h), inf)
    back = np.full((n_cols, h), -1, np.int64)
    # start column: a vertical run from the start row to any free exit row
    for e in range(h):
        lo, hi = min(start_row, e), max(start_row, e)
        if cum_occ[0, hi + 1] - cum_occ[0, lo] == 0:
            cost[0, e] = w_len * abs(e - start_row) * cell_size + w_vul * (
                cum_pot[0, hi + 1] - cum_pot[0, lo]
            )
    for k in range(1, n_cols):
        c = col0 + k
        last = k == n_cols - 1
        for p in range(h):
            if cost[k - 1, p] == inf:
                continue
            for e in range(h):
                if last and e != goal_row:
                    continue
                s = 1 if e > p else (-1 if e < p else 0)
                entry = p + s
                lo, hi = min(entry, e), max(entry, e)
                if cum_occ[k, hi + 1] - cum_occ[k, lo] != 0:
                    continue
                if not corner_cutting and cuts_corner(occ, p, c - 1, entry, c):
                    continue
                step = SQRT2 if s != 0 else 1.0
                val = (
                    cost[k - 1, p]
                    + w_len * (step + (hi - lo)) * cell_size
                    + w_vul * (cum_pot[k, hi + 1] - cum_pot[k, lo])
                )
                if val < cost[k, e]:
                    cost[k, e] = val
                    back[k, e] = p
    exits = np.full(n_cols, -1, np.int64)
    if cost[n_cols - 1, goal_row] == inf:
        return exits
    exits[n_cols - 1] = goal_row
    for k in range(n_cols - 1, 0, -1):
        exits[k - 1] = back[k, exits[k]]
    return exits


def weighted_sum_path(workspace, w_length: float = 1.0, w_vulnerability: float = 0.0) -> np.ndarray:
    """The feasible column-monotone path minimising a weighted sum.

    Parameters
    ----------
    workspace : :class:`gapath.Workspace`.
    w_length, w_vulnerability : non-negative weights, not both zero.

    Returns
    -------
    (m, 2) int array of workspace cells, start to goal.

    Raises
    ------
    ConfigError
        On negative, non-finite or all-zero weights.
    NoPathError
        When no feasible column-monotone path exists.

    Examples
    --------
    >>> import numpy as np
    >>> from gapath import Workspace
    >>> weighted_sum_path(Workspace(np.zeros((3, 3), bool))).tolist()
    [[2, 0], [1, 1], [0, 2]]
    """
    w = np.array([w_length, w_vulnerability], dtype=float)
    if not np.isfinite(w).all() or (w < 0).any() or not w.any():
        raise ConfigError(f"weights must be finite, >= 0 and not all zero, got {tuple(w)}")
    frame = Frame.of(workspace)
    exits = _weighted_dp(
        frame.occ,
        frame.potential,
        frame.start[0],
        frame.goal[0],
        frame.col0,
        frame.n_cols,
        w[0],
        w[1],
        workspace.cell_size,
        workspace.corner_cutting,
    )
    if exits[0] < 0:
        raise NoPathError(
            f"no feasible column-monotone path from {workspace.start} to "
            f"{workspace.goal} in {workspace.name!r}"
        )
    prev = np.concatenate([[frame.start[0]], exits[:-1]])
    entries = prev + np.sign(exits - prev)
    entries[0] = frame.start[0]
    return split_paths(*expand_profiles(frame, entries[None], exits[None]))[0]


def weighted_sum_paths(workspace, n_weights: int = 9) -> list[np.ndarray]:
    """The shortest, the safest and ``n_weights`` weighted-sum optimal
    column-monotone paths, without repeats.

    The extremes are found with a tiny weight on the other objective (so
    they are non-dominated); the other weights are spread evenly over
    ``(0, 1)`` on objectives normalised by the extremes' range.

    Raises
    ------
    NoPathError
        When no feasible column-monotone path exists.
    """
    shortest = weighted_sum_path(workspace, 1.0, 1e-7)
    safest = weighted_sum_path(workspace, 1e-7, 1.0)
    P, L = pad_paths([shortest, safest])
    m = evaluate_paths(
        P, L, workspace.occ, workspace.potential, workspace.cell_size, workspace.corner_cutting
    )
    span_len = max(m[1, LENGTH] - m[0, LENGTH], 1e-12)
    span_vul = max(m[0, VULNERABILITY] - m[1, VULNERABILITY], 1e-12)
    paths = [shortest, safest]
    for w in np.linspace(0.0, 1.0, n_weights + 2)[1:-1]:
        paths.append(weighted_sum_path(workspace, w / span_len, (1.0 - w) / span_vul))
    unique, seen = [], set()
    for p in paths:
        key = p.tobytes()
        if key not in seen:
            seen.add(key)
            unique.append(p)
    return unique
