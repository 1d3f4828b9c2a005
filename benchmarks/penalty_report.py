"""``docs/results/penalty.md`` from the JSON lines of ``bench_penalty.py``.

The protocol section at the top of the existing file (everything before
``## Results``) is kept as written before the runs, and so is the
``## Findings`` section at its end (written after reading the results); the
results between them are regenerated.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

#: Ahmed & Deb, Table 1 success (%) for the rows swept.
PAPER_SUCCESS = {(32, 0.3): 97, (32, 0.6): 74, (32, 0.8): 52}
GOAL_HV = 0.9
BUNDLED = "default-32x32-173"


def _load(paths):
    rows = []
    for p in paths:
        for line in Path(p).read_text().splitlines():
            if line.strip():
                rows.append(json.loads(line))
    return rows


def _order(handlings):
    def key(h):
        return (1, h, 0.0) if h.startswith("adaptive") else (0, "", -float(h.split()[-1]))

    return sorted(set(handlings), key=key)


def _dist(values) -> str:
    v = np.asarray(values, float)
    return f"{np.median(v):.3f} [{v.min():.3f}, {v.max():.3f}]"


def fig3_summary(rows):
    """``{(handling, encoding): {map: [hv, ...]}}``."""
    out = {}
    for r in rows:
        out.setdefault((r["handling"], r["encoding"]), {}).setdefault(r["map"], []).append(r["hv_ratio"])
    return out


def table1_summary(rows):
    """``{(handling, grid, p0): {map_seed: [success, ...]}}``."""
    out = {}
    for r in rows:
        out.setdefault((r["handling"], r["grid"], r["p0"]), {}).setdefault(r["map_seed"], []).append(
            bool(r["success"])
        )
    return out


def _fig3_section(rows) -> list[str]:
    if not rows:
        return []
    maps = list(dict.fromkeys(r["map"] for r in rows))
    encs = list(dict.fromkeys(r["encoding"] for r in rows))
    handlings = _order(r["handling"] for r in rows)
    summ = fig3_summary(rows)
    n_seeds = sorted({len(v) for d in summ.values() for v in d.values()})
    head = "| handling | encoding | " + " | ".join(maps) + " | all maps |"
    lines = [
        "### Fig. 3 set-up: unseeded hypervolume ratio per run",
        "",
        f"Median [min, max] over GA seeds ({'/'.join(map(str, n_seeds))} runs per cell) of "
        "each run's HV ratio against its map's exact monotone front; `all maps`: over every run "
        "of the row.",
        "",
        head,
        "|---|---|" + "---|" * (len(maps) + 1),
    ]
    for h in handlings:
        for e in encs:
            d = summ.get((h, e), {})
            if not d:
                continue
            cells = [_dist(d[m]) if m in d else "-" for m in maps]
            allv = [x for m in maps for x in d.get(m, [])]
            lines.append(f"| {h} | {e} | " + " | ".join(cells) + f" | {_dist(allv)} |")
    lines.append("")
    # where the adaptive penalties settled
    for h in handlings:
        ad = [r for r in rows if r["handling"] == h and h.startswith("adaptive")]
        if not ad:
            continue
        lines += [
            f"Where `{h}` ended (last generation, median [min, max] over its runs on all maps): "
            + "; ".join(
                f"{e}: penalty {_dist([r['final_penalty'] for r in ad if r['encoding'] == e])}, "
                f"feasible share {_dist([r['feasible_share'] for r in ad if r['encoding'] == e])}"
                for e in encs
            )
            + ".",
            "",
        ]
    lines += [
        "(The lines of the fixed-penalty runs carry no usable feasible share: the benchmark "
        "read it from CV, which penalty mode leaves at 0; it now reads the interfering count.)",
        "",
    ]
    return lines


def _table1_section(rows) -> list[str]:
    if not rows:
        return []
    summ = table1_summary(rows)
    handlings = _order(r["handling"] for r in rows)
    grid_rows = sorted({(r["grid"], r["p0"]) for r in rows})
    map_seeds = sorted({r["map_seed"] for r in rows})
    obstacles = {}
    for r in rows:
        obstacles[(r["grid"], r["p0"], r["map_seed"])] = r["obstacles"]
    n_runs = sorted({len(v) for d in summ.values() for v in d.values()})
    lines = [
        "### Table 1 set-up: success per map",
        "",
        f"Success % of {'/'.join(map(str, n_runs))} GA runs per map (integer encoding, pop 200, "
        "at most 500 generations, stop at the first feasible path, unseeded) on dense maps "
        f"{', '.join(map(str, map_seeds))}; median [min, max] over the maps, and all runs pooled. "
        "Obstacles per map: "
        + "; ".join(
            f"{g}x{g} p0 {p:g}: " + ", ".join(str(obstacles.get((g, p, m), "-")) for m in map_seeds)
            for g, p in grid_rows
        )
        + ".",
        "",
        "| handling | row | paper % | per map | median [min, max] over maps | pooled % |",
        "|---|---|---|---|---|---|",
    ]
    for h in handlings:
        for g, p in grid_rows:
            d = summ.get((h, g, p))
            if not d:
                continue
            per_map = [100.0 * np.mean(d[m]) for m in map_seeds if m in d]
            pooled = 100.0 * np.mean([x for m in map_seeds for x in d.get(m, [])])
            lines.append(
                f"| {h} | {g}x{g} p0 {p:g} | {PAPER_SUCCESS.get((g, p), '-')} | "
                + " ".join(f"{v:.0f}" for v in per_map)
                + f" | {np.median(per_map):.0f} [{min(per_map):.0f}, {max(per_map):.0f}] | {pooled:.0f} |"
            )
    lines.append("")
    return lines


def _ranges(seeds) -> str:
    """``[6, 7, 8, 11, 12]`` -> ``"6-8, 11-12"``."""
    out, start = [], None
    for i, s in enumerate(seeds):
        if start is None:
            start = s
        if i + 1 == len(seeds) or seeds[i + 1] != s + 1:
            out.append(f"{start}-{s}" if s != start else str(s))
            start = None
    return ", ".join(out)


def _goal_section(fig3, table1, fresh=()) -> list[str]:
    if not fig3:
        return []
    summ = fig3_summary(fig3)
    encs = list(dict.fromkeys(r["encoding"] for r in fig3))
    adaptive = [h for h in _order(r["handling"] for r in fig3) if h.startswith("adaptive")]
    lines = ["### The goal", ""]
    for h in adaptive:
        meds = {e: float(np.median(summ[(h, e)][BUNDLED])) for e in encs if BUNDLED in summ.get((h, e), {})}
        met = [e for e, m in meds.items() if m >= GOAL_HV]
        verdict = (
            "**met for every encoding**"
            if len(met) == len(meds)
            else (f"**met for {', '.join(met)}; " if met else "**")
            + f"not met for {', '.join(e for e in meds if e not in met)}**"
        )
        seeds = sorted({r["seed"] for r in fig3 if r["handling"] == h and r["map"] == BUNDLED})
        lines.append(
            f"- `{h}`, Fig. 3 set-up (bundled map, GA seeds {seeds[0]}-{seeds[-1]}): unseeded median HV ratio "
            + ", ".join(f"{e} {m:.3f}" for e, m in meds.items())
            + f" against the goal {GOAL_HV}: {verdict}."
        )
    if fresh:
        fs = fig3_summary(fresh)
        for h in _order(r["handling"] for r in fresh):
            seeds = sorted({r["seed"] for r in fresh if r["handling"] == h})
            meds = {e: _dist(fs[(h, e)][BUNDLED]) for e in encs if BUNDLED in fs.get((h, e), {})}
            lines.append(
                f"- `{h}` on fresh GA seeds {_ranges(seeds)} (bundled map): median [min, max] "
                + ", ".join(f"{e} {d}" for e, d in meds.items())
                + "."
            )
    if table1:
        runs = {(r["handling"], r["grid"], r["p0"], r["map_seed"], r["seed"]): r for r in table1}
        for h in adaptive:
            pairs = [
                (a, runs[("penalty 1000", *k[1:])])
                for k, a in runs.items()
                if k[0] == h and ("penalty 1000", *k[1:]) in runs
            ]
            if not pairs:
                continue
            same = [
                a["success"] == b["success"] and a["first_feasible_gen"] == b["first_feasible_gen"]
                for a, b in pairs
            ]
            by_row = {}
            for a, b in pairs:
                by_row.setdefault((a["grid"], a["p0"]), [0, 0, 0])
                by_row[(a["grid"], a["p0"])][0] += a["success"]
                by_row[(a["grid"], a["p0"])][1] += b["success"]
                by_row[(a["grid"], a["p0"])][2] += 1
            rows_text = "; ".join(
                f"{g}x{g} p0 {p:g}: {s_a} vs {s_b} of {n}" for (g, p), (s_a, s_b, n) in sorted(by_row.items())
            )
            lost = [k for k, (s_a, s_b, _) in by_row.items() if s_a < s_b]
            lines.append(
                f"- `{h}`, Table 1 set-up: successful runs against penalty 1000 ({rows_text}); "
                f"{sum(same)} of {len(pairs)} runs found their first feasible path in the same "
                "generation as with penalty 1000, or failed as it did"
                + (
                    " (the same runs: the penalty stays at 1000 while no path is feasible, and "
                    "the run stops at the first feasible path)"
                    if all(same)
                    else ""
                )
                + (
                    ". Success not lost in any row."
                    if not lost
                    else ". Success lost in " + ", ".join(f"{g}x{g} p0 {p:g}" for g, p in sorted(lost)) + "."
                )
            )
    lines.append("")
    return lines


def write_report(jsonl: str, out: str, fresh: str | None = None) -> None:
    rows = _load(jsonl.split(","))
    fresh_rows = [r for r in _load(fresh.split(",")) if r.get("part") == "fig3"] if fresh else []
    fig3 = [r for r in rows if r.get("part") == "fig3"]
    table1 = [r for r in rows if r.get("part") == "table1"]
    out = Path(out)
    old = out.read_text() if out.exists() else "# Penalty sweep\n"
    head = old.split("\n## Results")[0].rstrip("\n")
    tail = ("\n## Findings" + old.split("\n## Findings", 1)[1]).rstrip("\n") if "\n## Findings" in old else ""
    body = (
        ["## Results", ""]
        + _fig3_section(fig3)
        + _table1_section(table1)
        + _goal_section(fig3, table1, fresh_rows)
    )
    out.write_text(head + "\n\n" + "\n".join(body).rstrip("\n") + "\n" + tail + "\n")
