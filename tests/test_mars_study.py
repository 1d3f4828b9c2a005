"""A quick run of Lavin's Mars study (gapath.studies.mars,
benchmarks/mars_study.py)."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from gapath.studies import mars


def test_workspace_generator():
    ws = mars.mars_workspace(4, size=40)
    assert ws.shape == (40, 40) and ws.start == (39, 0) and ws.goal == (0, 39)
    assert 0.23 <= ws.n_obstacles / ws.occ.size < 0.23 + 14 * 14 / 1600
    assert not ws.occ[37:, :3].any() and not ws.occ[:3, 37:].any()
    again = mars.mars_workspace(4, size=40)
    np.testing.assert_array_equal(ws.occ, again.occ)


def test_costmap_from_the_dtm(data_dir):
    ws = mars.mars_workspace(1, size=30)
    dem = np.load(data_dir / "dem" / "mars_dtm.npy")
    cm = mars.mars_costmap(ws, 1, dem=dem)
    assert cm.terrain.startswith("mars_dtm reflect")
    e = cm.layer("elevation")
    assert e.min() == 0.0 and e.max() == 1.0
    r = cm.risk_cells[0]
    assert not ws.occ[r] and cm.layer("risk")[r] == 1.0
    assert cm.solar_rate == 1.0


def test_quick_study(tmp_path, capsys):
    root = Path(__file__).resolve().parents[1]
    sys.path.insert(0, str(root / "benchmarks"))
    try:
        import mars_study
    finally:
        sys.path.pop(0)
    jsonl = tmp_path / "mars.jsonl"
    assert mars_study.main(["--quick", "--size", "40", "--out", str(tmp_path), "--jsonl", str(jsonl)]) == 0
    lines = [json.loads(x) for x in capsys.readouterr().out.splitlines() if x.startswith("{")]
    assert [x["kind"] for x in lines].count("mars_workspace") == mars.QUICK["n_workspaces"]
    assert len(jsonl.read_text().splitlines()) == len(lines)
    rows = [x for x in lines if x["kind"] == "mars_table"]
    assert [r["algorithm"] for r in rows][:5] == ["A* renorm.", "D* renorm.", "A*", "D*", "D*-PO"]
    md = (tmp_path / "mars.md").read_text()
    assert "| D*-PO |" in md and "154.75" in md  # beside the paper's Table I
    # both comparisons, the second solar rate, the terrain on every table
    for title in (
        "## Table A: the paper's baselines",
        "## Table B: exact weighted-sum",
        "## Table C: solar 0.01",
    ):
        line = next(x for x in md.splitlines() if x.startswith(title))
        assert "terrain: HiRISE Mars DTM" in line or "terrain: **seeded fractal" in line
    assert md.count("benchmarks/mars_study.py --n 5 --size 40") >= 4  # the command at the top and per table
    csv = (tmp_path / "mars.csv").read_text().splitlines()
    assert csv[0].startswith("solar_rate,algorithm,n,F1_length")
    assert sum(x.startswith("0.01,") for x in csv) == 5
    compare = [x for x in lines if x["kind"] == "mars_table_solar_compare"]
    assert [r["algorithm"] for r in compare] == ["A* renorm.", "D* renorm.", "A*", "D*", "D*-PO"]
    for rec in (x for x in lines if x["kind"] == "mars_workspace"):
        for label in ("A*", "D*", "D*-PO", "A* renorm.", "D* renorm."):
            assert len(rec[label]["F"]) == 4 and rec[label]["seconds"] > 0
            assert rec["solar_compare"]["rate"] == 0.01 and len(rec["solar_compare"][label]["F"]) == 4
        assert isinstance(rec["dstar_po_dominated_by_ga"], bool)
        # A* and D* minimise the same weighted sum: equally good paths
        np.testing.assert_allclose(rec["A*"]["F"][0], rec["D*"]["F"][0], rtol=0.2)
    stats = next(x for x in lines if x["kind"] == "mars_stats")
    assert stats["n"] == mars.QUICK["n_workspaces"]
    # the GA is seeded from planners (as gapath solve): a front on every workspace,
    # so its row is in the table even with the quick budget
    assert "GA" in [r["algorithm"] for r in rows]
    assert all(x["GA"]["front_size"] > 0 for x in lines if x["kind"] == "mars_workspace")
    assert "seeded from planners" in md


def test_unseeded_ga_is_the_all_random_protocol():
    seeded = mars.run_workspace(0, size=24, ga_pop=12, ga_gen=3)
    unseeded = mars.run_workspace(0, size=24, ga_pop=12, ga_gen=3, ga_seed_from="none")
    # same workspace and planners, only the GA's first population differs
    assert seeded["A*"]["F"] == unseeded["A*"]["F"] and seeded["D*-PO"]["F"] == unseeded["D*-PO"]["F"]
    assert seeded["GA"]["front_size"] > 0
    if unseeded["GA"]["front_size"]:
        assert seeded["GA"]["front"] != unseeded["GA"]["front"]


def test_study_rejects_bad_settings():
    from gapath import ConfigError

    with pytest.raises(ConfigError):
        mars.mars_study(0)
    with pytest.raises(ConfigError, match="ga_seed_from"):
        mars.mars_study(1, ga_seed_from="dijkstra")
    with pytest.raises(ConfigError):
        mars.mars_workspace(1, size=2)


def test_window_overlap_on_a_tiny_dem():
    # a 2 x 3 DEM, windows of 2 x 4 (columns mirror beyond the third)
    ov = mars.window_overlap((2, 3), (2, 4), [(0, 0), (0, 3), (0, 1)])
    # window (0, 0): columns 0 1 2 2; (0, 3): 2 1 0 0; (0, 1): 1 2 2 1
    assert ov["dem_pixels"] == 6 and ov["window_cells"] == 8 and ov["windows"] == 3
    assert ov["distinct_per_window"] == {"median": 6.0, "min": 4, "max": 6}
    assert ov["distinct_all"] == 6
    # pixel sets: A = B = all 6, C = columns 1, 2 (4 pixels): Jaccard 1, 4/6, 4/6
    assert ov["pairwise_jaccard"]["max"] == 1.0
    assert ov["pairwise_jaccard"]["mean"] == pytest.approx((1 + 4 / 6 + 4 / 6) / 3)
    # shared: A in B 1, A in C 4/6, B in A 1, B in C 4/6, C in A 1, C in B 1
    assert ov["pairwise_shared"] == pytest.approx((1 + 4 / 6 + 1 + 4 / 6 + 1 + 1) / 6)
    # same pixel at the same position: A-B columns 1 only (1/4), A-C col 2 (1/4), B-C none... col 1: 1 vs 2, no
    assert ov["pairwise_same_cell"] == pytest.approx((1 / 4 + 1 / 4 + 0) / 3)
    with pytest.raises(Exception, match="two windows"):
        mars.window_overlap((2, 3), (2, 4), [(0, 0)])


def test_window_offsets_are_those_of_the_costmaps(data_dir):
    dem = np.load(data_dir / "dem" / "mars_dtm.npy")
    offsets = mars.window_offsets(3, dem.shape, seed=5)
    for i, off in enumerate(offsets):
        _, cm = mars.study_workspace(i, seed=5, size=20, dem=dem)
        assert cm.terrain == f"mars_dtm reflect offset={tuple(int(v) for v in off)}"


def test_paper_solar_scale():
    # gapath's step cost is (1 + r.s) / 2: all steps along the sun -> mean r.s = 1
    assert mars.paper_solar(10.0, 10) == 1.0 and mars.paper_solar(0.0, 4) == -1.0
    assert mars.paper_solar(3.0, 0) == 0.0
