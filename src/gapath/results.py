"""Writing a run's outputs: front.csv, paths.json, summary.json and plots.

Every file is written to a temporary name and renamed into place, so an
interrupted write never leaves a truncated file behind.
"""

from __future__ import annotations

import csv
import io
import json
import os
import platform
import tempfile
from importlib import metadata
from pathlib import Path

from gapath import plotting


def versions() -> dict[str, str]:
    """Versions of Python and of the packages a result depends on."""
    out = {"python": platform.python_version()}
    for pkg in ("gapath", "pymoo", "numpy", "numba"):
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            out[pkg] = "unknown"
    return out


def atomic_write(path, data: str | bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file and a rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode() if isinstance(data, str) else data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def front_csv(front) -> str:
    """The front as CSV: one column per objective (SPEC names), one row per
    path; values printed with full precision."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(front.objectives)
    for row in front.F:
        w.writerow([repr(float(v)) for v in row])
    return buf.getvalue()


def write_front(out_dir, workspace, front, summary: dict, *, plots: bool = True) -> None:
    """Write ``front.csv``, ``paths.json``, ``summary.json`` (and, with
    ``plots``, ``front.png`` and ``paths.png``) into ``out_dir``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    atomic_write(out / "front.csv", front_csv(front))
    records = front.records()
    frame = getattr(workspace, "frame", None)
    if frame is not None:   # the path in the map's world frame too (ROS maps: metres)
        for rec in records:
            rec["world"] = frame.to_world(rec["path"]).round(6).tolist()
    atomic_write(out / "paths.json", json.dumps(records, indent=1) + "\n")
    if plots:
        for name, draw in (("front.png", lambda: plotting.plot_front(front, workspace=workspace)),
                           ("paths.png", lambda: plotting.plot_paths(workspace, front))):
            atomic_write(out / name, plotting.png_bytes(draw()))
    atomic_write(out / "summary.json", json.dumps(summary, indent=1, sort_keys=True) + "\n")


def run_summary(result) -> dict:
    """The ``summary.json`` content of a :class:`gapath.solver.SolveResult`."""
    marks = plotting.marked_paths(result.front)
    return {
        "settings": result.settings,
        "versions": versions(),
        "wall_time_s": round(result.seconds, 3),
        "evaluations": result.n_eval,
        "generations": result.n_gen,
        "interrupted": result.interrupted,
        "front_size": len(result.front),
        "marked": {k: {"index": i, **dict(zip(result.front.objectives, map(float, result.front.F[i])))}
                   for k, i in marks.items()},
    }


def write_result(result, out_dir, *, plots: bool = True, extra: dict | None = None) -> None:
    """All outputs of a :class:`gapath.solver.SolveResult`; ``extra`` entries
    are added to ``summary.json`` (e.g. ``quality`` against a reference)."""
    summary = run_summary(result)
    summary.update(extra or {})
    write_front(out_dir, result.workspace, result.front, summary, plots=plots)
