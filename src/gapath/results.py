"""Writing a run's outputs: front.csv, paths.json, summary.json and plots.

Every file is written to a temporary name and renamed into place, so an
interrupted write never leaves a truncated file behind; the files get the
permissions the umask gives (``0644`` under the usual ``022``). JSON is
strict (:func:`dumps`): a value that is not finite (an empty front's IGD+)
is written as ``null``, never as ``Infinity`` or ``NaN``.
"""

from __future__ import annotations

import csv
import io
import json
import math
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


def json_safe(obj):
    """``obj`` with every value JSON can hold as such: floats that are not
    finite become ``None``, NumPy scalars and arrays Python numbers and
    lists, tuples lists (dict keys are left alone).

    Examples
    --------
    >>> import numpy as np
    >>> json_safe({"igd_plus": float("inf"), "F": np.array([1.5, np.nan]), "n": np.int64(3)})
    {'igd_plus': None, 'F': [1.5, None], 'n': 3}
    """
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, (str, int, bool)) or obj is None:
        return obj
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_safe(v) for v in obj]
    tolist = getattr(obj, "tolist", None)  # NumPy arrays and scalars
    if tolist is not None:
        return json_safe(tolist())
    return obj


def dumps(obj, **kwargs) -> str:
    """Strict JSON text of ``obj`` (:func:`json_safe`, then ``json.dumps``
    with ``allow_nan=False``); ``kwargs`` go to ``json.dumps``.

    Every JSON file gapath writes goes through this function.

    Examples
    --------
    >>> dumps({"hv_ratio": 0.0, "igd_plus": float("inf")}, sort_keys=True)
    '{"hv_ratio": 0.0, "igd_plus": null}'
    """
    return json.dumps(json_safe(obj), allow_nan=False, **kwargs)


def _umask() -> int:
    """The process's umask (read on every call: it may change)."""
    try:  # Linux: read it without changing it
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def check_output_dir(path, flag: str = "--out") -> Path:
    """Check that ``path`` can be used as an output directory, without
    creating anything: it is a writable directory, or it does not exist and
    its nearest existing parent is a writable directory.

    Raises
    ------
    ConfigError
        Naming ``flag`` and the path, when it is a file, below a file, or
        cannot be written.

    Examples
    --------
    >>> import tempfile
    >>> d = tempfile.mkdtemp()
    >>> check_output_dir(Path(d) / "new" / "run") == Path(d) / "new" / "run"
    True
    """
    from gapath.errors import ConfigError

    path = Path(path)
    probe = path
    while not probe.exists():
        if probe.is_symlink():
            raise ConfigError(f"{flag} {str(path)!r}: {str(probe)!r} is a broken symbolic link")
        if probe.parent == probe:
            break
        probe = probe.parent
    if not probe.is_dir():
        what = "is a file" if probe == path else f"is below {str(probe)!r}, a file"
        raise ConfigError(f"{flag} {str(path)!r} {what}; expected a directory")
    try:
        fd, tmp = tempfile.mkstemp(dir=probe, prefix=".gapath-write-test.")
    except OSError as exc:
        where = "" if probe == path else f" (its parent {str(probe)!r} is not writable)"
        raise ConfigError(f"{flag} {str(path)!r}: cannot write there{where}: {exc.strerror or exc}") from None
    os.close(fd)
    os.unlink(tmp)
    return path


def atomic_write(path, data: str | bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file and a rename; the
    file's permissions are ``0666`` less the umask, as ``open`` gives."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        if hasattr(os, "fchmod"):  # not on Windows (before 3.13)
            os.fchmod(fd, 0o666 & ~_umask())
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
    if frame is not None:  # the path in the map's world frame too (ROS maps: metres)
        for rec in records:
            rec["world"] = frame.to_world(rec["path"]).round(6).tolist()
    atomic_write(out / "paths.json", dumps(records, indent=1) + "\n")
    if plots:
        for name, draw in (
            ("front.png", lambda: plotting.plot_front(front, workspace=workspace)),
            ("paths.png", lambda: plotting.plot_paths(workspace, front)),
        ):
            atomic_write(out / name, plotting.png_bytes(draw()))
    atomic_write(out / "summary.json", dumps(summary, indent=1, sort_keys=True) + "\n")


def run_summary(result) -> dict:
    """The ``summary.json`` content of a :class:`gapath.solver.SolveResult`."""
    marks = result.front.marked()
    return {
        "settings": result.settings,
        "versions": versions(),
        "wall_time_s": round(result.seconds, 3),
        "evaluations": result.n_eval,
        "generations": result.n_gen,
        "interrupted": result.interrupted,
        "front_size": len(result.front),
        "marked": {
            k: {"index": i, **dict(zip(result.front.objectives, map(float, result.front.F[i])))}
            for k, i in marks.items()
        },
    }


def write_result(result, out_dir, *, plots: bool = True, extra: dict | None = None) -> None:
    """All outputs of a :class:`gapath.solver.SolveResult`; ``extra`` entries
    are added to ``summary.json`` (e.g. ``quality`` against a reference)."""
    summary = run_summary(result)
    summary.update(extra or {})
    write_front(out_dir, result.workspace, result.front, summary, plots=plots)
