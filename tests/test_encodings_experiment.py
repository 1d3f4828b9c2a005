import csv

from gapath.generators import random_workspace
from gapath.metrics import hv_ratio
from gapath.studies import encodings


def test_quick_encoding_comparison_writes_its_table(tmp_path):
    ws = random_workspace((12, 12), 25, seed=3)
    result = encodings.run(ws, runs=2, pop_size=30, n_gen=5)
    rows = result["rows"]
    assert [(r["protocol"], r["encoding"]) for r in rows] == [
        (p, e) for p in ("seeds", "seeded") for e in encodings.ENCODING_ORDER
    ]
    for r in rows:
        F = result["fronts"][(r["protocol"], r["encoding"])]
        assr = hv_ratio(F, result["exact"])
        assert abs(assr - r["merged_hv_ratio"]) < 1e-6
        assert r["run_hv_min"] <= r["run_hv_median"] <= r["run_hv_max"] <= r["merged_hv_ratio"] + 1e-9
    files = encodings.write_outputs(result, tmp_path)
    assert all(f.stat().st_size > 0 for f in files)
    table = list(csv.DictReader((tmp_path / "encodings.csv").open()))
    assert len(table) == 8
    assert "integer" in (tmp_path / "encodings.md").read_text()
