"""Where the archive's second approximate search fires (issue 14).

For each instance, the free-path archive's generation-1 searches as a run
makes them (``FreePathArchive.add_faces`` with the defaults: the exact
faces, the approximate three-objective search at e = 0.1 and, when the
exact (length, vulnerability) face cut to its ``eps_cover`` at 0.1 keeps
less than ``approx_retry`` of its HV, the same search at
``APPROX_RETRY_EPSILON``): one JSON line with ``approx_shortfall`` (that
share; None where the face did not finish or the rule is off) and
``retry`` (the finer front's size and whether it finished, or None).
No timing. Instances: the anytime names of ``bench_free_anytime.py`` and
``three`` for the instances of ``bench_free_paths.py --set three``.

Usage::

    python benchmarks/check_approx_retry.py --instances gen256-s1,...,berlin,three
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_free_anytime as anytime  # noqa: E402
import bench_free_paths as quality  # noqa: E402

from gapath.operators.archive import FreePathArchive  # noqa: E402
from gapath.problems import FreePathProblem  # noqa: E402

OBJECTIVES = ("length", "vulnerability", "smoothness")


def workspaces(names):
    """``(label, workspace)`` for each name (``three``: the quality set)."""
    for name in names:
        if name != "three":
            yield name, anytime.workspace(name, anytime.data_dir())
            continue
        folder = quality.data_dir()
        for m, n in quality.SETS["three"][2]:
            for q, (_, ws) in enumerate(quality.instances(folder, m, n)):
                yield f"three:{m}:{q}", ws


def check(ws) -> dict:
    archive = FreePathArchive(FreePathProblem(ws, OBJECTIVES))
    archive.add_faces()
    return dict(
        approx_shortfall=archive.approx_shortfall,
        retry=archive.retry_size,
        searches=[(list(objs), kept, done) for objs, kept, done in archive.face_sizes],
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--instances", required=True)
    ap.add_argument("--out", default=None, help="also append the JSON lines to this file")
    a = ap.parse_args(argv)
    out = open(a.out, "a") if a.out else None
    for label, ws in workspaces(a.instances.split(",")):
        line = json.dumps(dict(instance=label, **check(ws)))
        print(line, flush=True)
        if out:
            out.write(line + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
