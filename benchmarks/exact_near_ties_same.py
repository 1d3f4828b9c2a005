"""Two-objective free fronts on random grids built for exact and near ties,
dumped for a comparison between two sources (the eighteenth session's check
in docs/results/exact_speed.md: does the order in which the search breaks
exact ties of its open list's keys change ``F`` or smoothness?).

Three designs of small grids (``--design``), each with the potential
replaced by one with many exact zeros and values a fraction of SPEC's
tolerance (1e-9, relative) apart, so that tolerance-equal but not equal
vulnerabilities are common:

1. 4x4 to 15x15, 0-25 % obstacles; potential 0, 1 or 2 plus 0, 0.6, 1.1,
   1.6 or -0.7 tolerances (times 1, 3 or 0.5 by case);
2. the same up to 29x29, perturbations of 0.4 to 1.9 tolerances either way;
3. 5x5 to 21x21, 0-20 % obstacles, 30-80 % zeros, the others 1 or 2 plus
   -1 to 1.5 times 0.5e-9 scaled by 1, 2, 4 or 8;
4. 4x4 to 11x11, 0-20 % obstacles, potential 0 but for 1-4 cells of 1e-5
   to 4e-5 and the goal's 1e12: every vulnerability-to-go is about 1e12,
   so g2 values 1e-5 apart (far beyond the tolerance) give the same
   f_vulnerability;
5. 10x10 to 39x39, 1-8 % obstacles, SPEC's own potential (exact zeros
   away from obstacles, terms down to exp(-50) near them).

For each case: :func:`free_front` on (length, vulnerability) with the
smoothest tie-break; ``F`` and smoothness as bytes, the expansions and tie
edges. ``compare`` prints how many cases differ in each.

Usage::

    PYTHONPATH=A/src python benchmarks/exact_near_ties_same.py dump a.pkl --design 2 --cases 0:6000
    PYTHONPATH=B/src python benchmarks/exact_near_ties_same.py dump b.pkl --design 2 --cases 0:6000
    python benchmarks/exact_near_ties_same.py compare a.pkl b.pkl
"""

from __future__ import annotations

import argparse

import numpy as np
from _fixtures import load_pair, random_query, save_dump

TOL = 1e-9
LV = ("length", "vulnerability")


def case(design: int, i: int):
    if design == 5:
        rng = np.random.default_rng(110000 + i)
        h, w = int(rng.integers(10, 40)), int(rng.integers(10, 40))
        occ = rng.random((h, w)) < rng.uniform(0.01, 0.08)
    elif design == 4:
        rng = np.random.default_rng(90000 + i)
        h, w = int(rng.integers(4, 12)), int(rng.integers(4, 12))
        occ = rng.random((h, w)) < rng.uniform(0, 0.2)
    elif design == 3:
        rng = np.random.default_rng(70000 + i)
        h, w = int(rng.integers(5, 22)), int(rng.integers(5, 22))
        occ = rng.random((h, w)) < rng.uniform(0, 0.2)
    else:
        rng = np.random.default_rng((9000 if design == 1 else 20000) + i)
        hi = 16 if design == 1 else 30
        lo = 4 if design == 1 else 6
        h, w = int(rng.integers(lo, hi)), int(rng.integers(lo, hi))
        occ = rng.random((h, w)) < rng.uniform(0, 0.25)
    ws = random_query(occ, rng)
    if design == 5:
        return ws
    if design == 4:
        pot = np.zeros((h, w))
        cells = np.argwhere(~occ)
        for r, c in cells[rng.choice(len(cells), min(len(cells), int(rng.integers(1, 5))), replace=False)]:
            pot[r, c] = 1e-5 * int(rng.integers(1, 5))
        pot[ws.goal] = 1e12
    elif design == 3:
        pz = rng.uniform(0.3, 0.8)
        base = np.where(rng.random((h, w)) < pz, 0.0, rng.choice([1.0, 1.0, 2.0], size=(h, w)))
        scale = rng.choice([1.0, 2.0, 4.0, 8.0])
        k = rng.choice([0, 0, 1, 2, 3, -1, -2], size=(h, w))
        pot = np.where(base > 0, base + k * 0.5e-9 * scale, 0.0)
    else:
        kind = i % 3
        base = rng.choice([0.0, 0.0, 1.0, 1.0, 2.0], size=(h, w))
        steps = [0.0, 0.0, 0.6, 1.1, 1.6, -0.7] if design == 1 else [0.0, 0.0, 0.4, 0.9, 1.3, 1.9, -0.8, -1.4]
        eps = rng.choice(steps, size=(h, w)) * TOL * (1 if kind == 0 else 3 if kind == 1 else 0.5)
        pot = np.maximum(base + eps * np.maximum(base, 1), 0.0)
    pot.setflags(write=False)
    ws.__dict__["potential"] = pot  # the cached property, replaced
    return ws


def dump(out: str, design: int, lo: int, hi: int) -> None:
    from gapath.errors import NoPathError
    from gapath.planners.exact import free_front

    runs = {}
    for i in range(lo, hi):
        ws = case(design, i)
        try:
            f = free_front(ws, LV)
        except NoPathError:
            continue
        runs[(design, i)] = (
            f.F.tobytes(),
            np.asarray(f.smoothness).tobytes(),
            f.stats["expansions"],
            f.stats["tie_edges"],
        )
    save_dump(runs, out, "cases")


def compare(fa: str, fb: str) -> int:
    a, b = load_pair(fa, fb)
    if a.keys() != b.keys():
        print("different cases")
        return 1
    names = ("F", "smoothness", "expansions", "tie_edges")
    count = dict.fromkeys(names, 0)
    for k in a:
        for n, x, y in zip(names, a[k], b[k]):
            if x != y:
                count[n] += 1
                if n in ("F", "smoothness"):
                    print(k, n, "differs")
    print(f"{len(a)} cases; differ: " + ", ".join(f"{n} {c}" for n, c in count.items()))
    return 1 if count["F"] or count["smoothness"] else 0


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("dump")
    d.add_argument("out")
    d.add_argument("--design", type=int, choices=(1, 2, 3, 4, 5), default=2)
    d.add_argument("--cases", default="0:1000", help="first:last (exclusive)")
    c = sub.add_parser("compare")
    c.add_argument("a")
    c.add_argument("b")
    args = ap.parse_args()
    if args.cmd == "dump":
        lo, hi = (int(x) for x in args.cases.split(":"))
        dump(args.out, args.design, lo, hi)
    else:
        raise SystemExit(compare(args.a, args.b))
