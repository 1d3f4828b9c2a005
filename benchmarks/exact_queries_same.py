"""The two-objective free fronts on the 45 MovingAI queries, dumped for a
comparison between two sources (the sixteenth and seventeenth sessions'
check of docs/results/exact_speed.md).

For each of the five maps of ``bench_exact_peers.py`` (room-32-32-4,
maze-32-32-2, random-64-64-10, den312d, Berlin_1_256) the 9 ``.scen`` lines
``linspace(0, n - 1, 9)``, both tie-breaks (90 runs): :func:`free_front` on
(length, vulnerability), and for each run ``F``, smoothness, every path (as
bytes) and the stats except the times. Run it once with each source on
``PYTHONPATH`` (``dump``), then compare the two files (``compare``): every
run whose ``F``, smoothness, paths or stats (expansions, generated labels,
label rows, solutions, tie edges; ``peak_bytes`` reported apart) differ is
printed, then the count.

Usage::

    PYTHONPATH=A/src python benchmarks/exact_queries_same.py dump a.pkl
    PYTHONPATH=B/src python benchmarks/exact_queries_same.py dump b.pkl
    python benchmarks/exact_queries_same.py compare a.pkl b.pkl
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _fixtures import load_pair, save_dump  # noqa: E402


def dump(out: str) -> None:
    from bench_exact_peers import MAPF, MAPS2, queries

    from gapath.loaders import load_movingai
    from gapath.planners.exact import free_front

    runs = {}
    for name in MAPS2:
        for qi, sc in queries(name, 9):
            ws = load_movingai(MAPF / f"{name}.map", sc.start, sc.goal, corner_cutting=False)
            for tb in ("smoothest", "none"):
                f = free_front(ws, ("length", "vulnerability"), tie_break=tb)
                stats = {k: v for k, v in f.stats.items() if "seconds" not in k}
                paths = [np.asarray(p).tobytes() for p in f.paths]
                runs[(name, qi, tb)] = (f.F.tobytes(), np.asarray(f.smoothness).tobytes(), paths, stats)
    save_dump(runs, out, "runs")


def compare(fa: str, fb: str) -> int:
    a, b = load_pair(fa, fb)
    if a.keys() != b.keys():
        print("different runs")
        return 1
    bad = peak = 0
    for k in a:
        x, y = a[k], b[k]
        diffs = [n for n, i in (("F", 0), ("smoothness", 1), ("paths", 2)) if x[i] != y[i]]
        sx, sy = dict(x[3]), dict(y[3])
        peak += sx.pop("peak_bytes", None) != sy.pop("peak_bytes", None)
        if sx != sy:
            diffs.append(
                str({s: (sx.get(s), sy.get(s)) for s in set(sx) | set(sy) if sx.get(s) != sy.get(s)})
            )
        if diffs:
            bad += 1
            print(k, diffs)
    print(f"{len(a)} runs, {bad} differ, peak_bytes differ in {peak}")
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "dump":
        dump(sys.argv[2])
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(sys.argv[2], sys.argv[3]))
    else:
        print(__doc__)
        sys.exit(2)
