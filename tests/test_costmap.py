"""Costmap layers (gapath.costmap): built-in layers, DEM resampling, fractal
terrain, risk, the dynamic solar cost, path objectives and bad input."""

import math

import numpy as np
import pytest

from gapath import ConfigError, Workspace
from gapath.costmap import (
    Costmap,
    elevation_from_dem,
    fractal_terrain,
    load_dem,
    risk_layer,
)


@pytest.fixture
def ws():
    occ = np.zeros((6, 7), bool)
    occ[2, 3] = True
    return Workspace(occ, cell_size=2.0)


def test_builtin_layers(ws):
    cm = Costmap(ws)
    assert cm.names == ("distance", "heuristic", "solar")
    assert cm.objective_names == ("length", "solar")
    dist = cm.layer("distance")
    assert dist[2, 3] == np.inf and dist[0, 0] == 1.0
    heur = cm.layer("heuristic")
    # octile distance to the goal (0, 6), times cell_size
    assert heur[0, 6] == 0.0
    assert heur[5, 0] == pytest.approx((6 - 5 + 5 * math.sqrt(2)) * 2.0)
    assert not heur.flags.writeable


def test_elevation_normalised_and_user_layers(ws):
    elev = np.arange(42.0).reshape(6, 7) * 3 + 100
    cm = Costmap(ws, elevation=elev, risk=(1, 1), layers={"slope": np.ones((6, 7))})
    assert cm.names == ("distance", "heuristic", "elevation", "solar", "risk", "slope")
    e = cm.layer("elevation")
    assert e.min() == 0.0 and e.max() == 1.0
    np.testing.assert_allclose(e, (elev - elev.min()) / (elev.max() - elev.min()))
    assert cm.objective_names == ("length", "elevation", "solar", "risk", "slope")


def test_dem_bilinear_and_reflect():
    dem = np.array([[0.0, 2.0], [4.0, 6.0]])
    # bilinear: pixel-centre alignment, corners clamp to the DEM corners
    out = elevation_from_dem(dem, (4, 4), normalise=False)
    assert out[0, 0] == 0.0 and out[3, 3] == 6.0
    assert out[0, 1] == pytest.approx(0.5)  # x = 0.25 between 0 and 2
    np.testing.assert_allclose(out, out[:, ::-1][:, ::-1])
    # reflect: one pixel per cell, mirrored copies (period 2n)
    row = np.arange(3.0)[None, :]
    r = elevation_from_dem(row, (1, 8), method="reflect", normalise=False)
    assert r.tolist() == [[0, 1, 2, 2, 1, 0, 0, 1]]
    r = elevation_from_dem(row, (1, 4), method="reflect", offset=(0, 4), normalise=False)
    assert r.tolist() == [[1, 0, 0, 1]]
    with pytest.raises(ConfigError, match="unknown DEM method"):
        elevation_from_dem(dem, (3, 3), method="cubic")


def test_mars_dtm_window(data_dir):
    dem = load_dem(data_dir / "dem" / "mars_dtm.npy")
    assert dem.shape == (120, 70)
    win = elevation_from_dem(dem, (100, 100), method="reflect", offset=(10, 50))
    assert win.shape == (100, 100) and win.min() == 0.0 and win.max() == 1.0
    # columns 20.. of the window mirror the DTM back from its last column
    raw = elevation_from_dem(dem, (100, 100), method="reflect", offset=(10, 50), normalise=False)
    np.testing.assert_array_equal(raw[:, 19], dem[10:110, 69])
    np.testing.assert_array_equal(raw[:, 20], dem[10:110, 69])
    np.testing.assert_array_equal(raw[:, 21], dem[10:110, 68])
    cm = Costmap(Workspace(np.zeros((30, 40), bool)))
    cm.set_elevation(data_dir / "dem" / "mars_dtm.npy")  # bilinear over the whole DTM
    assert cm.layer("elevation").shape == (30, 40)


def test_fractal_terrain_seeded():
    a = fractal_terrain((33, 20), seed=5)
    b = fractal_terrain((33, 20), seed=5)
    c = fractal_terrain((33, 20), seed=6)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)
    assert a.min() == 0.0 and a.max() == 1.0
    # smoother with a larger Hurst exponent: smaller mean neighbour difference
    rough = np.abs(np.diff(fractal_terrain((64, 64), 1, hurst=0.2), axis=1)).mean()
    smooth = np.abs(np.diff(fractal_terrain((64, 64), 1, hurst=1.0), axis=1)).mean()
    assert smooth < rough


def test_risk_layer_capped_inverse_square():
    r = risk_layer((5, 6), (2, 2))
    assert r[2, 2] == 1.0 and r[2, 3] == 1.0  # capped at d <= 1
    assert r[2, 4] == pytest.approx(1 / 4)
    assert r[0, 5] == pytest.approx(1 / (4 + 9))
    two = risk_layer((5, 6), [(2, 2), (0, 0)])
    assert two[2, 4] == pytest.approx(1 / 4 + 1 / 20)
    assert risk_layer((5, 6), (2, 2), cap=2.0)[2, 3] == 0.25


def test_solar_cost_rotates():
    cm = Costmap(Workspace(np.zeros((3, 3), bool)), solar_rate=math.pi / 2)
    # step 0: sun vector [1, 0] (east); moving east costs 1, moving west 0
    assert cm.solar_cost(0, 1, 0) == pytest.approx(1.0)
    assert cm.solar_cost(0, -1, 0) == pytest.approx(0.0)
    assert cm.solar_cost(-1, 0, 0) == pytest.approx(0.5)
    # step 1: the vector turned counter-clockwise to north (towards row 0)
    assert cm.solar_cost(-1, 0, 1) == pytest.approx(1.0)
    assert cm.solar_cost(-1, 1, 1) == pytest.approx(0.5 * (1 + math.sqrt(0.5)))
    table = cm.solar_table(3)
    assert table.shape == (3, 8)
    assert table[0, 0] == pytest.approx(1.0) and table[1, 2] == pytest.approx(1.0)
    assert ((table >= 0) & (table <= 1)).all()


def test_evaluate_path_paper_definitions(ws):
    elev = np.random.default_rng(0).random((6, 7))
    cm = Costmap(ws, elevation=elev, risk=(5, 6), solar_rate=0.25)
    path = [(5, 0), (4, 1), (4, 2), (3, 2)]
    v = cm.evaluate_path(path)
    assert v["length"] == pytest.approx((2 + math.sqrt(2)) * 2.0)
    e = cm.layer("elevation")
    assert v["elevation"] == pytest.approx(np.mean([e[c] for c in path]))
    r = cm.layer("risk")
    assert v["risk"] == pytest.approx(np.mean([r[c] for c in path]))
    steps = [(-1, 1), (0, 1), (-1, 0)]
    expect = sum(
        0.5 * (1 + (dc * math.cos(0.25 * k) - dr * math.sin(0.25 * k)) / math.hypot(dr, dc))
        for k, (dr, dc) in enumerate(steps)
    )
    assert v["solar"] == pytest.approx(expect)


def test_with_workspace_shares_layers(ws):
    cm = Costmap(ws, elevation=np.ones((6, 7)), risk=(0, 0))
    other = cm.with_workspace(ws.replace(goal=(0, 5)))
    assert other.workspace.goal == (0, 5) and cm.workspace.goal == (0, 6)
    assert other.layer("heuristic")[0, 5] == 0.0
    with pytest.raises(ConfigError, match="shape"):
        cm.with_workspace(Workspace(np.zeros((3, 3), bool)))


@pytest.mark.parametrize(
    "values, match",
    [
        (np.ones((6, 6)), r"layer 'slope' must have the grid's shape \(6, 7\), got shape \(6, 6\)"),
        (np.full((6, 7), np.nan), r"layer 'slope' holds NaN at \(row 0, col 0\)"),
        (
            np.where(np.eye(6, 7) > 0, -0.5, 1.0),
            r"layer 'slope' holds the negative value -0.5 at \(row 0, col 0\)",
        ),
        (np.full((6, 7), np.inf), r"layer 'slope' holds inf"),
        (np.zeros((6, 7), bool), r"layer 'slope' must be a numeric array"),
    ],
)
def test_bad_layers(ws, values, match):
    cm = Costmap(ws)
    with pytest.raises(ConfigError, match=match):
        cm.add_layer("slope", values)


def test_bad_names_and_settings(ws):
    cm = Costmap(ws)
    with pytest.raises(ConfigError, match="unknown layer 'foo'"):
        cm.layer("foo")
    with pytest.raises(ConfigError, match="'elevation' is not set"):
        cm.layer("elevation")
    with pytest.raises(ConfigError, match="dynamic"):
        cm.layer("solar")
    with pytest.raises(ConfigError, match="reserved"):
        cm.add_layer("heuristic", np.ones((6, 7)))
    with pytest.raises(ConfigError, match="unknown objective 'foo'"):
        cm.check_objectives(["length", "foo"])
    with pytest.raises(ConfigError, match="given twice"):
        cm.check_objectives("length,solar,length")
    with pytest.raises(ConfigError, match="not a path objective"):
        cm.check_objectives(["heuristic"])
    with pytest.raises(ConfigError, match="'risk' is not set"):
        cm.check_objectives(["risk"])
    with pytest.raises(ConfigError, match="elevation.*holds NaN"):
        Costmap(ws, elevation=np.full((6, 7), np.nan))
    with pytest.raises(ConfigError, match="outside"):
        Costmap(ws, risk=(9, 9))
    with pytest.raises(ConfigError, match="solar_rate"):
        Costmap(ws, solar_rate=float("nan"))
    with pytest.raises(ConfigError, match="cap"):
        risk_layer((3, 3), (1, 1), cap=0)
