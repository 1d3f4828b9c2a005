import numpy as np
import pytest
from encoding_cases import (
    assert_valid_simple,
    empty_ws,
    frame_paths,
    genome_matrix,
    same_paths,
    workspaces,
)
from hypothesis import given, settings
from hypothesis import strategies as st

from gapath import ConfigError
from gapath.encodings import BinaryEncoding, Frame
from gapath.problems import GridPathProblem

PATH_1 = "00011010110001000000001000001000011"
PATH_2 = "10111000010001100000001000001100111"


def bits(s):
    return np.array([[c == "1" for c in s]])


def reference_decode(enc, genome):
    """Straight transcription of the bit layout (frame rows), with a flag
    telling whether a move had to be clamped at the grid edge."""
    f = enc.frame
    h, nb, n_cols = f.height, enc.n_y_bits, f.n_cols
    g = [bool(b) for b in genome]
    clamped = False

    def y(o):
        return int("".join("1" if b else "0" for b in g[o : o + nb]), 2)

    def clamp(v):
        nonlocal clamped
        clamped |= not 0 <= v < h
        return min(max(v, 0), h - 1)

    sr, gr = f.start[0], f.goal[0]
    entries, exits = [sr], [clamp(sr - y(0) if g[-2] else sr + y(0))]
    for k in range(1, n_cols - 1):
        o = nb + (k - 1) * (2 + nb)
        s = -1 if g[o] else 1
        e = exits[-1] + s if g[o] == g[o + 1] else exits[-1]
        entries.append(clamp(e))
        exits.append(clamp(e + s * y(o + 2)))
    r = exits[-1]
    entries.append(r + int(np.sign(gr - r)))
    exits.append(gr)
    return entries, exits, clamped


@st.composite
def cases(draw):
    ws = draw(workspaces())
    enc = BinaryEncoding(Frame.of(ws))
    values = st.one_of(st.booleans(), st.integers(-2, 3))  # numbers: > 0.5 is a 1
    return ws, enc, genome_matrix(draw, enc.n_var, values)


@settings(max_examples=100, deadline=None)
@given(cases())
def test_any_genome_decodes_to_a_valid_path(case):
    ws, enc, X = case
    problem = GridPathProblem(ws, encoding="binary")
    for path in problem.decode(X):
        assert_valid_simple(ws, path)
    entries, exits = enc.decode(X)
    for i, genome in enumerate(X > 0.5):
        e, x, _ = reference_decode(enc, genome)
        assert entries[i].tolist() == e and exits[i].tolist() == x


@settings(max_examples=100, deadline=None)
@given(cases(), st.integers(0, 2**32 - 1))
def test_edge_fix_stays_in_bounds_and_removes_clamping(case, seed):
    ws, enc, X = case
    Xf = enc.edge_fix(X, np.random.default_rng(seed))
    assert Xf.dtype == bool and Xf.shape == X.shape
    for genome in Xf:
        assert not reference_decode(enc, genome)[2]
    # a genome that needs no fixing is left alone
    assert np.array_equal(enc.edge_fix(Xf, np.random.default_rng(seed + 1)), Xf)
    # redundant encoding: decode(encode(decode(X))) == decode(X)
    for G in (X, Xf):
        entries, exits = enc.decode(G)
        again = enc.decode(enc.encode_profiles(entries, exits))
        assert np.array_equal(again[0], entries) and np.array_equal(again[1], exits)


def test_paper_examples():
    # Ahmed & Deb Fig. 2 on 8x8, the strings of section 2.1 read left to right
    enc = BinaryEncoding(Frame.of(empty_ws(8, 8)))
    assert enc.n_var == len(PATH_1) == 35
    entries, exits = enc.decode(bits(PATH_1))
    assert exits[0].tolist() == [7, 4, 3, 3, 5, 6, 6, 0]  # integer (0, 3, 1, 0, -2, -1, 0)
    assert entries[0].tolist() == [7, 6, 3, 3, 4, 6, 6, 5]  # last column: diagonal up, then 5 up
    entries, exits = enc.decode(bits(PATH_2))
    assert exits[0].tolist() == [2, 1, 1, 0, 2, 3, 1, 0]  # integer (5, 1, 0, 1, -2, -1, 2)
    assert entries[0, -1] == 0  # the diagonal reaches the goal: no end-fixing run
    # encoding the paths gives the paper's strings back, except that the
    # horizontal step of Path 2 is written 10-000 rather than 01-000
    p = GridPathProblem(empty_ws(8, 8), encoding="binary")
    assert np.array_equal(p.encode(p.decode(bits(PATH_1))), bits(PATH_1))
    assert np.array_equal(p.encode(p.decode(bits(PATH_2))), bits(PATH_2[:8] + "10000" + PATH_2[13:]))


def test_horizontal_then_vertical_moves():
    # 10-y is C-Dy (up), 01-y C-Ey (down): the column is entered level
    enc = BinaryEncoding(Frame.of(empty_ws(8, 4, start=(4, 0), goal=(4, 3))))
    genome = "000100100101111"
    entries, exits = enc.decode(bits(genome))
    assert entries[0].tolist() == [4, 4, 2, 4] and exits[0].tolist() == [4, 2, 5, 4]
    # the start column moves down when the closing bits start with 0
    entries, exits = enc.decode(bits("011100001000000"))
    assert exits[0].tolist() == [7, 7, 7, 4]


def test_y_bits_follow_the_height():
    for h, nb in [(1, 1), (2, 1), (3, 2), (8, 3), (9, 4), (32, 5), (33, 6)]:
        assert BinaryEncoding(Frame.of(empty_ws(h, 5))).n_y_bits == nb


def test_encode_decode_round_trip_on_random_monotone_paths():
    ws = empty_ws(15, 20)
    p = GridPathProblem(ws, encoding="binary")
    paths = frame_paths(ws, np.random.default_rng(0), 50, max_step=4)
    X = p.encode(paths)
    assert X.dtype == bool
    assert same_paths(paths, p.decode(X))


@pytest.mark.parametrize(
    "start,goal", [((0, 7), (5, 0)), ((5, 3), (0, 3)), ((1, 2), (4, 2)), ((2, 0), (3, 7))]
)
def test_mirrored_and_transposed_frames(start, goal):
    ws = empty_ws(6, 8, start, goal)
    p = GridPathProblem(ws, encoding="binary")
    rng = np.random.default_rng(1)
    paths = frame_paths(ws, rng, 20)
    assert same_paths(paths, p.decode(p.encode(paths)))
    # binary-only paths (horizontal then vertical) round trip too
    X = p.encoding.edge_fix(rng.random((30, p.n_var)) < 0.5, rng)
    paths = p.decode(X)
    for path in paths:
        assert_valid_simple(ws, path)
    assert same_paths(paths, p.decode(p.encode(paths)))


def test_edge_fix_draws_rows_with_linear_probability():
    ws = empty_ws(6, 3)  # start row 5
    enc = BinaryEncoding(Frame.of(ws))
    assert enc.n_y_bits == 3
    # start: 2 up (row 3); gene 1: A-D7 from row 3, far beyond the top edge
    X = np.tile(bits("0101111111"), (60000, 1))
    Xf = enc.edge_fix(X, np.random.default_rng(5))
    rows = enc.decode(Xf)[1][:, 1]
    counts = np.bincount(rows, minlength=6)[:4]  # rows 0..3
    np.testing.assert_allclose(counts / counts.sum(), [3 / 6, 2 / 6, 1 / 6, 0], atol=0.01)
    assert (Xf[:, 3:5] == [True, True]).all()  # still a diagonal up


def test_edge_fix_turns_a_diagonal_at_the_edge_into_a_horizontal_step():
    enc = BinaryEncoding(Frame.of(empty_ws(4, 3)))  # 2 y bits, start row 3
    X = bits("11110111")  # start 3 up to row 0, then diagonal up: out of the grid
    Xf = enc.edge_fix(X, np.random.default_rng(0))
    assert Xf[0].tolist() == [c == "1" for c in "11100011"]
    X = bits("11000100")  # start 3 down from row 3: out; drawn back onto row 3
    assert enc.edge_fix(X, np.random.default_rng(0))[0].tolist() == [c == "1" for c in "00010000"]


def test_edge_fix_is_reproducible_for_a_seed():
    enc = BinaryEncoding(Frame.of(empty_ws(10, 10)))
    X = np.random.default_rng(0).random((40, enc.n_var)) < 0.5
    a = enc.edge_fix(X, np.random.default_rng(3))
    b = enc.edge_fix(X, np.random.default_rng(3))
    assert np.array_equal(a, b)
    assert not np.array_equal(a, X)  # random genomes do leave a 10-row grid


def test_unrepresentable_paths_are_rejected():
    enc = BinaryEncoding(Frame.of(empty_ws(5, 3)))
    # diagonal up then down (A-E1): dominated, not coded
    with pytest.raises(ConfigError, match="not representable in the binary encoding at column 1"):
        enc.encode([[(4, 0), (3, 1), (4, 1), (3, 2), (2, 2), (1, 2), (0, 2)]])
    # last transition not by the end-fixing rule (horizontal, then up)
    with pytest.raises(ConfigError, match="at column 2"):
        enc.encode([[(4, 0), (4, 1), (4, 2), (3, 2), (2, 2), (1, 2), (0, 2)]])
    with pytest.raises(ConfigError, match="needs|need"):
        enc.decode(np.zeros((1, 3), bool))
