import numpy as np
import pytest
from data_files import TESTS_DATA

from gapath import Workspace


@pytest.fixture
def data_dir():
    """``tests/data`` (the small real maps, scenario files and the Mars DTM
    committed with the tests). For the large optional files use
    :func:`data_files.data_path`, which also looks in ../shared/data."""
    return TESTS_DATA


def random_grid(rng, h, w, density=0.2, start=None, goal=None, **kw):
    occ = rng.random((h, w)) < density
    start = (h - 1, 0) if start is None else start
    goal = (0, w - 1) if goal is None else goal
    occ[start] = occ[goal] = False
    return Workspace(occ, start, goal, **kw)


@pytest.fixture
def small_ws():
    return random_grid(np.random.default_rng(7), 10, 12, 0.15)
