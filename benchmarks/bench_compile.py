"""Numba compile time of the test suite from a cold cache.

Runs ``pytest`` (the suite's default selection, or the arguments given after
``--``) in a subprocess with an empty ``NUMBA_CACHE_DIR`` and the plugin
``_numba_compile_log.py``, then prints JSON lines: one ``suite`` line (wall
seconds, pytest's exit code, compilations, compile seconds, and how many
compilations and seconds went to *extra* specializations: every signature of
a kernel but its most expensive one, typically compiled because an argument
came writable instead of read-only, or as a literal instead of an
``int64``), then one line per
kernel compiled more than once, most expensive first. Wall time: the suite
runs on one process, so the figure moves with the machine's other load.

Usage::

    python benchmarks/bench_compile.py [--top 15] [--src SRC] [-- PYTEST_ARGS...]

``--src`` points at another checkout's ``src`` (to measure a previous
revision with the same plugin).
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--top", type=int, default=15, help="kernels compiled more than once to list")
    ap.add_argument("--src", type=Path, default=HERE.parent / "src", help="the gapath src to measure")
    ap.add_argument("pytest_args", nargs="*", help="pytest's arguments, after --")
    args = ap.parse_args(argv)
    src = args.src.resolve()
    root = src.parent
    with tempfile.TemporaryDirectory() as tmp:
        log = Path(tmp) / "compiles.jsonl"
        env = dict(os.environ)
        env.update(
            NUMBA_CACHE_DIR=str(Path(tmp) / "numba"),
            GAPATH_COMPILE_LOG=str(log),
            PYTHONPATH=os.pathsep.join([str(HERE), str(src)]),
        )
        cmd = [sys.executable, "-m", "pytest", "-q", "-p", "_numba_compile_log", "-p", "no:cacheprovider"]
        t0 = time.perf_counter()
        rc = subprocess.call(cmd + args.pytest_args, cwd=root, env=env, stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - t0
        recs = [json.loads(line) for line in log.read_text().splitlines()] if log.exists() else []
    by = collections.defaultdict(list)
    for r in recs:
        by[r["kernel"]].append(r)
    # numba's own (typed containers, ufunc loops) are not gapath's to fix
    multi = {k: v for k, v in by.items() if len(v) > 1 and not k.startswith("numba.")}
    extra_s = sum(sum(sorted((r["s"] for r in v), reverse=True)[1:]) for v in multi.values())
    print(
        json.dumps(
            {
                "what": "suite",
                "src": str(src),
                "pytest_rc": rc,
                "wall_s": round(wall, 1),
                "compilations": len(recs),
                "compile_s": round(sum(r["s"] for r in recs), 1),
                "kernels_compiled_twice_or_more": len(multi),
                "extra_specializations": sum(len(v) - 1 for v in multi.values()),
                "extra_specialization_s": round(extra_s, 1),
            }
        ),
        flush=True,
    )
    ranked = sorted(multi.items(), key=lambda kv: -sum(r["s"] for r in kv[1]))
    for name, rs in ranked[: args.top]:
        print(
            json.dumps(
                {
                    "what": "kernel",
                    "kernel": name,
                    "specializations": len(rs),
                    "s": round(sum(r["s"] for r in rs), 1),
                }
            )
        )
    return 0 if rc == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
