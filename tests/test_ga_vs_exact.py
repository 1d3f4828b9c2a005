"""GA fronts never beat the exact fronts (SPEC: reference fronts)."""

import numpy as np
import pytest

from gapath.generators import random_workspace
from gapath.metrics import hv_ratio
from gapath.planners.exact import free_front, monotone_front
from gapath.solver import solve


def _dominates(a, b, tol=1e-9):
    scale = tol * np.maximum(1.0, np.maximum(np.abs(a), np.abs(b)))
    return bool((a <= b + scale).all() and (a < b - scale).any())


@pytest.mark.parametrize(
    "seed,objectives,encoding",
    [
        (1, ("length", "vulnerability"), "integer"),
        (2, ("length", "vulnerability"), "binary"),
        (3, ("length", "vulnerability", "smoothness"), "mixed"),
        (4, ("length", "smoothness"), "absolute"),
    ],
)
def test_no_ga_point_dominates_an_exact_point(seed, objectives, encoding):
    ws = random_workspace((14, 14), 35, seed=seed)
    r = solve(
        ws,
        objectives=objectives,
        encoding=encoding,
        pop_size=40,
        n_gen=15,
        seed=seed,
        tiebreak=None if len(objectives) == 3 else "smoothness",
    )
    # an empty GA front would pass every check below: it must hold feasible paths
    assert len(r.front.F) > 0, f"the GA found no feasible path on map seed {seed}"
    assert np.isfinite(r.front.F).all() and r.front.F.shape[1] == len(objectives)
    mono = monotone_front(ws, objectives).F
    free = free_front(ws, objectives).F
    for f in r.front.F:
        for e in np.vstack([mono, free]):
            assert not _dominates(f, e)
    # the monotone front bounds the GA (same path set) and the free front bounds both
    assert hv_ratio(r.front.F, mono) <= 1.0 + 1e-9
    assert hv_ratio(mono, free) <= 1.0 + 1e-9
