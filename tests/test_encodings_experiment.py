import csv

import numpy as np

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


def test_pairwise_tests_separate_different_samples_and_not_equal_ones():
    rng = np.random.default_rng(5)
    low, high = rng.uniform(0.5, 0.6, 10), rng.uniform(0.8, 0.9, 10)
    per_run = {
        ("seeds", 0.3, "integer", None): high.tolist(),
        ("seeds", 0.3, "mixed", None): low.tolist(),
        ("seeds", 0.3, "binary", "bits"): (low + 0.001).tolist(),
        ("seeds", 1000.0, "integer", None): [0.5149] * 10,
        ("seeds", 1000.0, "mixed", None): [0.5149] * 10,
    }
    tests = {(t["penalty"], t["a"], t["b"]): t for t in encodings.pairwise_tests(per_run)}
    assert len(tests) == 4  # pairs only within one protocol and penalty
    assert tests[(0.3, "integer", "mixed")]["p"] < 0.001
    assert tests[(0.3, "integer", "mixed")]["U"] == 100
    assert tests[(0.3, "mixed", "binary (1/bits)")]["p"] > 0.05
    assert tests[(1000.0, "integer", "mixed")]["p"] == 1.0


def test_penalties_and_binary_rates_are_rows_of_their_own():
    ws = random_workspace((10, 10), 15, seed=2)
    seen = []
    result = encodings.run(
        ws,
        runs=2,
        pop_size=20,
        n_gen=4,
        encodings=("integer", "binary"),
        protocols=("seeds",),
        penalties=(1000.0, "adaptive"),
        binary_rates=("bits", "grid"),
        on_run=lambda key, r: seen.append((key, r.settings)),
    )
    keys = [(r["penalty"], r["encoding"], r["binary_rate"]) for r in result["rows"]]
    assert keys == [
        (p, e, b)
        for p in (1000.0, "adaptive")
        for e, b in (("integer", None), ("binary", "bits"), ("binary", "grid"))
    ]
    assert len(seen) == 12 and set(result["per_run"]) == {k for k, _ in seen}
    for (_protocol, pen, _enc, rate), settings in seen:
        assert settings["constraints"] == ("adaptive" if pen == "adaptive" else "penalty")
        assert settings.get("pm_prob_var") == ("grid" if rate == "grid" else None)
