import numpy as np
import pytest

from gapath import ConfigError, MapError, Workspace, default_workspace, dense_workspace, random_workspace


@pytest.mark.parametrize("value", ["no", "False", 0, 1, None, 0.0])
def test_corner_cutting_must_be_a_bool(value):
    with pytest.raises(ConfigError, match=f"corner_cutting must be True or False, got {value!r}"):
        Workspace(np.zeros((3, 3), bool), corner_cutting=value)
    with pytest.raises(ConfigError, match="corner_cutting must be True or False"):
        default_workspace().replace(corner_cutting=value)
    assert Workspace(np.zeros((3, 3), bool), corner_cutting=np.False_).corner_cutting is False


def test_problem_of_an_array_names_workspace_and_from_array():
    from gapath.problems import GridPathProblem

    with pytest.raises(
        ConfigError,
        match=r"expects a gapath\.Workspace, got ndarray; .*"
        r"gapath\.loaders\.from_array",
    ):
        GridPathProblem(np.zeros((4, 4), bool))


@pytest.mark.parametrize(
    "make", [lambda **kw: dense_workspace(8, 0.3, 1, **kw), lambda **kw: random_workspace((8, 8), 5, 1, **kw)]
)
def test_generators_check_start_and_goal(make):
    with pytest.raises(ConfigError, match=r"start \(9, 0\) is outside the 8x8 grid"):
        make(start=(9, 0))
    with pytest.raises(ConfigError, match=r"goal \(0, -1\) is outside the 8x8 grid"):
        make(goal=(0, -1))


def test_defaults_and_repr():
    ws = Workspace(np.zeros((4, 6), bool))
    assert ws.start == (3, 0) and ws.goal == (0, 5)
    assert "4x6" in repr(ws)
    assert not ws.occ.flags.writeable


@pytest.mark.parametrize(
    "occ,match",
    [
        (np.zeros((0, 3), bool), "non-empty 2-D"),
        (np.zeros(5, bool), "non-empty 2-D"),
        (np.array([[0, 2], [0, 0]]), "got 2 at \\(row 0, col 1\\)"),
        (np.array([["a", "b"]]), "must be boolean"),
    ],
)
def test_bad_occupancy(occ, match):
    with pytest.raises(MapError, match=match):
        Workspace(occ)


@pytest.mark.parametrize(
    "kw,match",
    [
        (dict(start=(5, 0)), r"start \(5, 0\) is outside the 4x4 grid"),
        (dict(goal=(0, -1)), r"goal \(0, -1\) is outside"),
        (dict(start=(1, 1)), r"start \(1, 1\) is on an obstacle"),
        (dict(start=(0, 3)), "start and goal are the same cell"),
        (dict(cell_size=0), "cell_size must be a positive number"),
        (dict(cell_size=-2.0), "cell_size must be a positive number"),
        (dict(cell_size=7e-10), r"cell_size must be at least 1e-06, got 7e-10"),
        (dict(start="a"), "start must be a \\(row, col\\) pair"),
    ],
)
def test_bad_workspace_settings(kw, match):
    occ = np.zeros((4, 4), bool)
    occ[1, 1] = True
    with pytest.raises(ConfigError, match=match):
        Workspace(occ, **kw)


def test_the_least_cell_size_keeps_the_smoothest_tie_break_acyclic():
    """At MIN_CELL_SIZE an open grid (zero potential everywhere, so every
    path ties in vulnerability) gives its one-point front with a path of the
    least step count: lengths two steps apart do not tie. (At 7e-10 the same
    search crashed the process: the tie edges formed cycles.)"""
    from gapath.planners.exact import free_front
    from gapath.workspace import MIN_CELL_SIZE

    ws = Workspace(np.zeros((8, 9), bool), cell_size=MIN_CELL_SIZE)
    front = free_front(ws, ("length", "vulnerability"))
    assert len(front) == 1
    assert len(front.paths[0]) == 9  # 8 diagonal-first steps from (7, 0) to (0, 8)
    assert front.F[0, 0] == pytest.approx((1 + 7 * np.sqrt(2)) * MIN_CELL_SIZE, rel=1e-12)


def test_errors_are_value_errors():
    assert issubclass(MapError, ValueError) and issubclass(ConfigError, ValueError)


def test_default_scenario():
    ws = default_workspace()
    assert ws.shape == (32, 32) and ws.n_obstacles == 173
    assert ws.start == (31, 0) and ws.goal == (0, 31)
    # it still equals what its recorded recipe generates
    assert np.array_equal(random_workspace((32, 32), 173, seed=2013).occ, ws.occ)


@pytest.mark.parametrize(
    "make",
    [
        lambda seed: dense_workspace(16, 1.0, seed=seed),
        lambda seed: dense_workspace(24, 0.7, seed=seed),
        lambda seed: random_workspace((20, 20), 300, seed=seed),
    ],
)
def test_generators_keep_a_feasible_monotone_path(make):
    from gapath.planners.exact import monotone_front

    for seed in range(4):
        ws = make(seed)
        front = monotone_front(ws)  # raises NoPathError when there is none
        assert len(front.F) >= 1
        assert make(seed) == ws  # seeded


def test_dense_generator_at_full_density_leaves_only_the_path():
    ws = dense_workspace(16, 1.0, seed=3)
    free = np.argwhere(~ws.occ)
    # one column-monotone path: every column has one contiguous run of free cells
    for c in range(16):
        rows = np.sort(free[free[:, 1] == c, 0])
        assert len(rows) >= 1 and (np.diff(rows) == 1).all()
    assert dense_workspace(16, 1.0, seed=4) != ws


def test_generator_errors():
    with pytest.raises(ConfigError, match="grid size must be positive"):
        dense_workspace(0, 0.5)
    with pytest.raises(ConfigError, match="p0 must be in"):
        dense_workspace(8, 1.5)
    with pytest.raises(ConfigError, match="exceeds"):
        random_workspace((4, 4), 100)
    with pytest.raises(ConfigError, match="n_obstacles must be >= 0"):
        random_workspace((4, 4), -1)


def test_replace():
    ws = default_workspace()
    ws2 = ws.replace(start=(30, 0))
    assert ws2.start == (30, 0) and ws2.goal == ws.goal
    with pytest.raises(ConfigError, match="unknown workspace field"):
        ws.replace(colour="red")


def test_copies_and_unpickled_workspaces_stay_read_only():
    """Kernels get the same (read-only) arrays from a copy, so numba does not
    compile a second specialization for a Dask worker's workspace."""
    import copy
    import pickle

    from gapath.workspace import read_only

    occ = np.zeros((6, 7), bool)
    occ[2, 1:5] = True
    ws = Workspace(occ)
    assert occ.flags.writeable  # the caller's array is not frozen
    for twin in (copy.deepcopy(ws), pickle.loads(pickle.dumps(ws)), ws.replace(name="b")):
        assert not twin.occ.flags.writeable and not twin.potential.flags.writeable
        np.testing.assert_array_equal(twin.occ, ws.occ)
        np.testing.assert_array_equal(twin.potential, ws.potential)
    frozen = read_only(occ[:, ::-1], np.float64)
    assert frozen.dtype == np.float64 and frozen.flags.c_contiguous and not frozen.flags.writeable
    assert read_only(ws.occ) is ws.occ  # already read-only: no copy
