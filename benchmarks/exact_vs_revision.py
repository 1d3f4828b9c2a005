"""The free front on (length, vulnerability) against the same function at
another git revision, on random small grids built to have many ties.

Extracts ``src/`` of ``--rev`` (default: the commit before the smoothest
tie-break was moved after the search) with ``git archive``, runs
:func:`gapath.planners.exact.free_front` on the same ``--cases`` workspaces
with both sources (one subprocess each) and prints one JSON line: cases, how
many differ in ``F`` (bit for bit), in ``smoothness``, in the paths (paths
may differ where several have exactly the same objectives), and the total
expansions of each. The cases: 4x4 to 24x24 grids, 0-30 % obstacles, either
corner rule, random start and goal; one in three gets a potential of a few
dyadic values, half of them 0 (exact ties everywhere), one in three is a
sparse 14x14 to 29x29 map with its true potential (exact zeros, near-ties).

Usage::

    python benchmarks/exact_vs_revision.py [--rev 82b556b] [--cases 600] [--tie-break smoothest|none]
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

import numpy as np
from _fixtures import random_query

ROOT = Path(__file__).resolve().parents[1]


def make(i: int):
    rng = np.random.default_rng(1000 + i)
    kind = i % 3
    h, w = int(rng.integers(4, 25)), int(rng.integers(4, 25))
    if kind == 2:
        h, w = int(rng.integers(14, 30)), int(rng.integers(14, 30))
        p = rng.uniform(0.0, 0.04)
    else:
        p = rng.uniform(0.0, 0.3)
    ws = random_query(rng.random((h, w)) < p, rng)
    if kind == 1:
        pot = rng.choice([0.0, 0.0, 0.0, 0.25, 0.5, 1.0], size=(h, w))
        pot.setflags(write=False)
        ws.__dict__["potential"] = pot  # the cached property, replaced
    return ws


def worker(n: int, out: str, tie_break: str) -> None:
    from gapath.errors import NoPathError
    from gapath.planners.exact import free_front

    res = {}
    for i in range(n):
        try:
            f = free_front(make(i), ("length", "vulnerability"), tie_break=tie_break)
            res[i] = (f.F, f.smoothness, [p.tolist() for p in f.paths], f.stats["expansions"])
        except NoPathError:
            res[i] = None
    with open(out, "wb") as fh:
        pickle.dump(res, fh)


def run(src: Path, n: int, out: Path, tie_break: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(src))
    code = (
        f"import sys; sys.path.insert(0, {str(Path(__file__).parent)!r}); import exact_vs_revision as m; "
        f"m.worker({n}, {str(out)!r}, {tie_break!r})"
    )
    subprocess.run([sys.executable, "-c", code], env=env, check=True)
    with open(out, "rb") as fh:
        return pickle.load(fh)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rev", default="82b556b")
    ap.add_argument("--cases", type=int, default=600)
    ap.add_argument("--tie-break", default="smoothest", choices=("smoothest", "none"))
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="gapath-rev-") as tmpname:
        tmp = Path(tmpname)
        archive = subprocess.run(
            ["git", "-C", str(ROOT), "archive", args.rev, "src"], capture_output=True, check=True
        ).stdout
        (tmp / "src.tar").write_bytes(archive)
        with tarfile.open(tmp / "src.tar") as tar:
            tar.extractall(tmp / "old", filter="data")
        old = run(tmp / "old" / "src", args.cases, tmp / "old.pkl", args.tie_break)
        new = run(ROOT / "src", args.cases, tmp / "new.pkl", args.tie_break)
    counts = {"cases": 0, "F_differ": 0, "smoothness_differ": 0, "paths_differ": 0}
    exp_old = exp_new = 0
    for i, a in old.items():
        b = new[i]
        if a is None or b is None:
            assert a is None and b is None, f"case {i}: a path in one revision only"
            continue
        counts["cases"] += 1
        counts["F_differ"] += not np.array_equal(a[0], b[0])
        counts["smoothness_differ"] += not np.array_equal(a[1], b[1])
        counts["paths_differ"] += a[2] != b[2]
        exp_old += a[3]
        exp_new += b[3]
    print(
        json.dumps(
            {
                "rev": args.rev,
                "tie_break": args.tie_break,
                **counts,
                "expansions_rev": exp_old,
                "expansions_now": exp_new,
            }
        ),
        flush=True,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
