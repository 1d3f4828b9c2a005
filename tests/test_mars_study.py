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
    assert [r["algorithm"] for r in rows][:3] == ["A*", "D*", "D*-PO"]
    md = (tmp_path / "mars.md").read_text()
    assert "| D*-PO |" in md and "154.75" in md  # beside the paper's Table I
    csv = (tmp_path / "mars.csv").read_text().splitlines()
    assert csv[0].startswith("algorithm,n,F1_length")
    for rec in (x for x in lines if x["kind"] == "mars_workspace"):
        for label in ("A*", "D*", "D*-PO"):
            assert len(rec[label]["F"]) == 4 and rec[label]["seconds"] > 0
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
