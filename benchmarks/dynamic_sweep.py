"""A difficulty sweep of the dynamic study (issue 17 §4): which planner still
reaches the goal with more and faster obstacles and a shorter, narrower
sensor.

Usage::

    nice -n 10 python benchmarks/dynamic_sweep.py             # the committed protocol
    python benchmarks/dynamic_sweep.py --quick                 # 3 seeds, maze, no docs
    python benchmarks/dynamic_sweep.py --seeds 10 --docs /tmp/out

Runs :func:`gapath.dynamic.sweep.sweep`: NO-MOPP-style hybrid A* with
replanning, RRT*, grid A* and D* Lite, one factor at a time (moving
obstacles, their speed relative to the robot, sensor range, field of view)
around a hard base, over scenario seeds 0..N-1 (a new map, new obstacles
and planner seed per seed) on the maze and the warehouse. Prints one JSON
line per scenario, setting and planner (``dynamic_sweep``) and one verdict
line per scenario and setting (``dynamic_sweep_verdict``) to stdout, and
unless ``--quick`` writes ``dynamic_sweep.jsonl`` and ``dynamic_sweep.png``
into ``--docs`` (default ``docs/results``) and the sweep's section into
``dynamic.md`` there (between its markers; the rest of the file is left
alone). Wall-clock time on a possibly shared machine is printed to stderr.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from gapath.dynamic.sweep import (
    SCENARIOS,
    SEEDS,
    one_at_a_time,
    section,
    splice_block,
    sweep,
    sweep_png,
    verdicts,
)
from gapath.studies.dynamic import LABELS


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=None, help=f"scenario seeds 0..N-1 (default {len(SEEDS)})")
    ap.add_argument("--scenarios", default=",".join(SCENARIOS))
    ap.add_argument("--quick", action="store_true", help="3 seeds on the maze, nothing written")
    ap.add_argument(
        "--factors",
        default=None,
        help="only these settings (comma-separated: base, moving, speed, sensor, fov); nothing written",
    )
    ap.add_argument("--docs", default=str(Path(__file__).resolve().parents[1] / "docs" / "results"))
    args = ap.parse_args(argv)
    n = args.seeds if args.seeds is not None else (3 if args.quick else len(SEEDS))
    scenarios = ("maze",) if args.quick else tuple(s for s in args.scenarios.split(",") if s)
    t0 = time.perf_counter()

    def progress(done, total, row):
        if done % 50 == 0 or done == total:
            print(f"{done}/{total} runs, {time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)

    settings = one_at_a_time()
    if args.factors:
        keep = {f.strip() for f in args.factors.split(",")}
        settings = [(label, d) for label, d in settings if label in keep]
    res = sweep(settings, scenarios=scenarios, seeds=range(n), progress=progress)
    lines = [json.dumps({"benchmark": "dynamic_sweep", **r}) for r in res.table]
    lines += [json.dumps({"benchmark": "dynamic_sweep_verdict", **v}) for v in verdicts(res.rows)]
    print("\n".join(lines))
    if not (args.quick or args.factors):
        out = Path(args.docs)
        out.mkdir(parents=True, exist_ok=True)
        (out / "dynamic_sweep.jsonl").write_text("\n".join(lines) + "\n")
        sweep_png(res, out / "dynamic_sweep.png", LABELS)
        command = "nice -n 10 python benchmarks/dynamic_sweep.py"
        if args.seeds is not None or args.scenarios != ",".join(SCENARIOS):
            command += f" --seeds {n} --scenarios {','.join(scenarios)}"
        md = out / "dynamic.md"
        text = md.read_text() if md.exists() else "# Dynamic environments\n"
        md.write_text(splice_block(text, "dynamic-sweep", section(res, command, LABELS, "dynamic_sweep.png")))
        print(f"wrote {out}/dynamic_sweep.jsonl, dynamic_sweep.png, dynamic.md", file=sys.stderr)
    print(f"{len(res.rows)} runs in {time.perf_counter() - t0:.0f} s wall", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
