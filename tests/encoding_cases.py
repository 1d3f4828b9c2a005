"""Shared cases for the encoding tests: workspaces with any start and goal,
random representable paths in any frame, path checks."""

import numpy as np
from hypothesis import strategies as st

from gapath import Workspace
from gapath.encodings import Frame
from gapath.generators import random_monotone_path


def empty_ws(h, w, start=None, goal=None):
    return Workspace(np.zeros((h, w), bool), start, goal)


@st.composite
def workspaces(draw, max_side=12):
    """A free grid (1..max_side a side, at least 2 cells) with start and goal
    anywhere: mirrored and transposed frames included."""
    h = draw(st.integers(1, max_side))
    w = draw(st.integers(2 if h == 1 else 1, max_side))
    cells = [(r, c) for r in range(h) for c in range(w)]
    start = draw(st.sampled_from(cells))
    goal = draw(st.sampled_from([x for x in cells if x != start]))
    return empty_ws(h, w, start, goal)


def genome_matrix(draw, n_var, values, max_rows=6):
    n = draw(st.integers(1, max_rows))
    return np.array(draw(st.lists(st.lists(values, min_size=n_var, max_size=n_var), min_size=n, max_size=n)))


def frame_paths(ws, rng, n, max_step=3):
    """``n`` random column-monotone paths of the integer encoding's kind
    (workspace cells), drawn in the canonical frame so that mirrored and
    transposed workspaces work too."""
    f = Frame.of(ws)
    return [
        f.to_workspace(random_monotone_path(f.occ.shape, f.start, f.goal, rng, max_step=max_step))
        for _ in range(n)
    ]


def assert_valid_simple(ws, path):
    assert ws.is_valid_path(path), path
    assert len({tuple(c) for c in path}) == len(path), path  # no repeated cell


def same_paths(a, b):
    return len(a) == len(b) and all(np.array_equal(x, y) for x, y in zip(a, b))
