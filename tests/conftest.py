import os
from pathlib import Path

import numpy as np
import pytest

from gapath import Workspace


def shared_data() -> Path | None:
    env = os.environ.get("GAPATH_SHARED_DATA")
    for p in ([Path(env)] if env else []) + [Path(__file__).resolve().parents[2] / "shared" / "data"]:
        if p.is_dir():
            return p
    return None


@pytest.fixture
def data_dir():
    d = shared_data()
    if d is None:
        pytest.skip("shared data folder not found")
    return d


def random_grid(rng, h, w, density=0.2, start=None, goal=None, **kw):
    occ = rng.random((h, w)) < density
    start = (h - 1, 0) if start is None else start
    goal = (0, w - 1) if goal is None else goal
    occ[start] = occ[goal] = False
    return Workspace(occ, start, goal, **kw)


@pytest.fixture
def small_ws():
    return random_grid(np.random.default_rng(7), 10, 12, 0.15)
