"""The feasibility-preserving repair's results in ``docs/results/penalty.md``.

Reads the JSON lines of ``bench_penalty.py --repair ...`` (and the
penalty-1000 Table 1 runs of ``penalty_table1.jsonl`` to pair with) and
rewrites the part of ``penalty.md`` between ``<!-- repair-results -->`` and
``<!-- /repair-results -->``; everything else in the file is kept.

Usage: python benchmarks/repair_report.py [--dir docs/results]
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
from scipy.stats import mannwhitneyu

FIG3 = (
    "repair_fig3_bundled.jsonl",
    "repair_fig3_bundled_baseline.jsonl",
    "repair_fig3_bundled_reach.jsonl",
    "repair_fig3_bundled_baseline_mixed.jsonl",
    "repair_fig3_bundled_baseline_binary.jsonl",
    "repair_fig3_bundled_half.jsonl",
    "repair_fig3_nocorridor.jsonl",
)
TABLE1 = ("repair_table1.jsonl", "repair_table1_half.jsonl")
TABLE1_BASE = "penalty_table1.jsonl"
PAPER_SUCCESS = {(32, 0.3): 97, (32, 0.6): 74, (32, 0.8): 52}
GOAL = 0.9
BUNDLED = "default-32x32-173"
START, END = "<!-- repair-results -->", "<!-- /repair-results -->"


def _load(path: Path):
    if not path.exists():
        return []
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def _label(r) -> str:
    return r["handling"] + (f" + {r['repair']}" if r.get("repair") else " (edge-fixing only)")


def _dist(v) -> str:
    v = np.asarray(v, float)
    return f"{np.median(v):.3f} [{v.min():.3f}, {v.max():.3f}] {int((v >= GOAL).sum())}/{len(v)}"


def _seed_text(seeds) -> str:
    s = sorted(set(seeds))
    return f"{s[0]}-{s[-1]}" if s == list(range(s[0], s[-1] + 1)) else ", ".join(map(str, s))


def fig3_lines(rows) -> list[str]:
    maps = list(dict.fromkeys(r["map"] for r in rows))
    cells = {}
    for r in rows:
        cells.setdefault((_label(r), r["encoding"]), {}).setdefault(r["map"], []).append(r)
    lines = [
        "### Fig. 3 set-up with the repair: unseeded hypervolume ratio per run",
        "",
        "Per cell: median [min, max] of the runs' HV ratio against the map's exact monotone front, "
        "then the count of runs >= 0.9 and the GA seeds.",
        "",
        "| handling | encoding | " + " | ".join(maps) + " |",
        "|---|---|" + "---|" * len(maps),
    ]
    for (label, enc), d in cells.items():
        out = []
        for m in maps:
            rs = d.get(m)
            out.append(
                "-"
                if not rs
                else f"{_dist([r['hv_ratio'] for r in rs])} (seeds {_seed_text(r['seed'] for r in rs)})"
            )
        lines.append(f"| {label} | {enc} | " + " | ".join(out) + " |")
    lines.append("")
    # tests that can fail: the repair vs each other handling, per encoding, bundled map, same seeds
    key = ("penalty 1000 + feasible-local", "integer")
    for (ref, enc_a), d_a in cells.items():
        if ref != key[0] or BUNDLED not in d_a:
            continue
        a = [r["hv_ratio"] for r in d_a[BUNDLED]]
        for (label, enc), d in cells.items():
            if enc != enc_a or label == ref or BUNDLED not in d:
                continue
            b = [r["hv_ratio"] for r in d[BUNDLED]]
            p = mannwhitneyu(a, b, alternative="two-sided").pvalue
            lines.append(
                f"- Bundled map, {enc}, `{ref}` against `{label}` (same GA seeds): two-sided "
                f"Mann-Whitney U p = {p:.2g} ({len(a)} and {len(b)} runs)."
            )
    lines.append("")
    # the encodings under the repair (bundled map): pairwise, Holm-adjusted
    by_enc = {
        e: [r["hv_ratio"] for r in d[BUNDLED]]
        for (label, e), d in cells.items()
        if label == key[0] and BUNDLED in d
    }
    pairs = [(a, b) for i, a in enumerate(by_enc) for b in list(by_enc)[i + 1 :]]
    if pairs:
        ps = [mannwhitneyu(by_enc[a], by_enc[b], alternative="two-sided").pvalue for a, b in pairs]
        order = np.argsort(ps)
        holm, running = [0.0] * len(ps), 0.0
        for rank, j in enumerate(order):
            running = max(running, min(1.0, (len(ps) - rank) * ps[j]))
            holm[j] = running
        lines.append(
            f"- Encodings under `{key[0]}` on the bundled map, two-sided Mann-Whitney U (p unadjusted / Holm): "
            + "; ".join(f"{a} vs {b} {p:.2g} / {h:.2g}" for (a, b), p, h in zip(pairs, ps, holm))
            + "."
        )
        lines.append("")
    secs = {}
    for r in rows:
        if r["map"] == BUNDLED:
            secs.setdefault((_label(r), r["encoding"]), []).append(r["seconds"])
    lines.append(
        "Wall seconds per run on the bundled map (median; shared 2-core machine at a load of 4-9, "
        "not a timing): "
        + "; ".join(f"{label}, {enc}: {np.median(v):.1f}" for (label, enc), v in secs.items())
        + "."
    )
    lines.append("")
    return lines


def table1_lines(rows, base) -> list[str]:
    base = {
        (r["grid"], r["p0"], r["map_seed"], r["seed"]): r for r in base if r["handling"] == "penalty 1000"
    }
    maps = sorted({r["map_seed"] for r in rows})
    lines = [
        "### Table 1 set-up with the repair: success per map",
        "",
        f"Success % of the 10 GA runs per dense map {', '.join(map(str, maps))} "
        "(integer, pop 200, at most 500 generations, stop at the first feasible path, unseeded); "
        "penalty 1000 without repair: the same runs in `penalty_table1.jsonl`. First feasible "
        "generation: median [min, max] over the successful runs.",
        "",
        "| handling | row | paper % | per map | median [min, max] over maps | pooled % | penalty 1000 "
        "pooled % | both / repair only / penalty only / neither | first feasible gen (repair) | "
        "(penalty 1000) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for label, g, p in dict.fromkeys((_label(r), r["grid"], r["p0"]) for r in rows):
        rs = [r for r in rows if (_label(r), r["grid"], r["p0"]) == (label, g, p)]
        per_map = [100 * np.mean([r["success"] for r in rs if r["map_seed"] == m]) for m in maps]
        pairs = [(r, base.get((g, p, r["map_seed"], r["seed"]))) for r in rs]
        pairs = [(a, b) for a, b in pairs if b is not None]
        both = sum(a["success"] and b["success"] for a, b in pairs)
        only_a = sum(a["success"] and not b["success"] for a, b in pairs)
        only_b = sum(b["success"] and not a["success"] for a, b in pairs)
        neither = len(pairs) - both - only_a - only_b
        ga = [a["first_feasible_gen"] for a in rs if a["success"]]
        gb = [b["first_feasible_gen"] for _, b in pairs if b["success"]]

        def gens(v):
            return f"{np.median(v):.0f} [{min(v)}, {max(v)}]" if v else "-"

        lines.append(
            f"| {label} | {g}x{g} p0 {p:g} | {PAPER_SUCCESS.get((g, p), '-')} | "
            + " ".join(f"{v:.0f}" for v in per_map)
            + f" | {np.median(per_map):.0f} [{min(per_map):.0f}, {max(per_map):.0f}] | "
            f"{100 * np.mean([r['success'] for r in rs]):.0f} | "
            f"{100 * np.mean([b['success'] for _, b in pairs]):.0f} | "
            f"{both} / {only_a} / {only_b} / {neither} | {gens(ga)} | {gens(gb)} |"
        )
    lines.append("")
    return lines


def goal_lines(fig3, table1, base) -> list[str]:
    lines = ["### The goal with the repair", ""]
    for label in dict.fromkeys(_label(r) for r in fig3 if r.get("repair")):
        meds = {}
        for r in fig3:
            if _label(r) == label and r["map"] == BUNDLED:
                meds.setdefault(r["encoding"], []).append(r["hv_ratio"])
        if not meds:
            continue
        text = ", ".join(f"{e} {np.median(v):.3f}" for e, v in meds.items())
        met = [e for e, v in meds.items() if np.median(v) >= GOAL]
        lines.append(
            f"- `{label}`, Fig. 3 set-up (bundled map, fresh GA seeds "
            f"{_seed_text(r['seed'] for r in fig3 if _label(r) == label and r['map'] == BUNDLED)}): "
            f"median HV ratio {text}: **goal met for {', '.join(met) if met else 'no encoding'}**"
            + (f", not for {', '.join(e for e in meds if e not in met)}" if len(met) < len(meds) else "")
            + "."
        )
    if table1:
        b = {
            (r["grid"], r["p0"], r["map_seed"], r["seed"]): r["success"]
            for r in base
            if r["handling"] == "penalty 1000"
        }
        lost = []
        for label, g, p in dict.fromkeys((_label(r), r["grid"], r["p0"]) for r in table1):
            rs = [r for r in table1 if (_label(r), r["grid"], r["p0"]) == (label, g, p)]
            n_a = sum(r["success"] for r in rs)
            n_b = sum(b.get((g, p, r["map_seed"], r["seed"]), False) for r in rs)
            if n_a < n_b:
                lost.append(f"{g}x{g} p0 {p:g} ({label})")
            lines.append(
                f"- `{_label(rs[0])}`, Table 1 32x32 p0 {p:g}: {n_a} of {len(rs)} runs against {n_b} at penalty 1000."
            )
        lines.append(
            "- Table 1 success: "
            + ("**not lost in any row**." if not lost else f"**lost in {', '.join(lost)}**.")
        )
    lines.append("")
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dir", default="docs/results")
    args = ap.parse_args(argv)
    d = Path(args.dir)
    fig3 = [r for f in FIG3 for r in _load(d / f) if r.get("part") == "fig3"]
    table1 = [r for f in TABLE1 for r in _load(d / f) if r.get("part") == "table1"]
    base = [r for r in _load(d / TABLE1_BASE) if r.get("part") == "table1"]
    body = []
    if fig3:
        body += fig3_lines(fig3)
    if table1:
        body += table1_lines(table1, base)
    body += goal_lines(fig3, table1, base)
    md = d / "penalty.md"
    text = md.read_text()
    head, rest = text.split(START, 1)
    tail = rest.split(END, 1)[1]
    md.write_text(head + START + "\n\n" + "\n".join(body).rstrip("\n") + "\n\n" + END + tail)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
