"""Reference fronts and the quality of a front against one (SPEC).

A reference is the exact monotone front (``"monotone"``), the exact front
of all 8-connected paths (``"free"``), or a ``front.csv`` written by
``gapath exact`` / ``gapath solve``.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from gapath.errors import ConfigError, MapError
from gapath.metrics import coverage, hv_ratio, igd_plus


def read_front_csv(path, objectives=None) -> np.ndarray:
    """Objective matrix of a ``front.csv``; with ``objectives`` given, its
    columns must be exactly those names (in any order; returned in that
    order).

    Raises
    ------
    MapError
        If the file is missing, binary or malformed (names the file and line).
    ConfigError
        If its columns are not the requested objectives.
    """
    path = Path(path)
    try:
        rows = list(csv.reader(path.read_text().splitlines()))
    except OSError as exc:
        raise MapError(f"{path}: cannot read reference front ({exc.strerror})") from None
    except UnicodeDecodeError as exc:
        raise MapError(
            f"{path}: not a text front.csv (undecodable byte at offset {exc.start}); "
            f"expected a CSV file as written by 'gapath exact' or 'gapath solve'"
        ) from None
    if not rows:
        raise MapError(f"{path}: empty reference front (expected a header of objective names)")
    header = [h.strip() for h in rows[0]]
    values = []
    for i, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise MapError(f"{path}, line {i}: {len(row)} values, expected {len(header)}")
        try:
            values.append([float(v) for v in row])
        except ValueError:
            raise MapError(f"{path}, line {i}: non-numeric value in {row!r}") from None
    F = np.array(values, dtype=float).reshape(-1, len(header))
    if objectives is None:
        return F
    objectives = list(objectives)
    if sorted(header) != sorted(objectives):
        raise ConfigError(f"{path}: reference front has objectives {header}, the run has {objectives}")
    return F[:, [header.index(o) for o in objectives]]


def reference_front(workspace, objectives, reference) -> np.ndarray:
    """The reference objective matrix for ``reference`` in ``"monotone"``,
    ``"free"`` or a path to a ``front.csv``."""
    from gapath.planners import exact

    objectives = tuple(objectives)
    if reference == "monotone":
        return exact.monotone_front(workspace, objectives).F
    if reference == "free":
        return exact.free_front(workspace, objectives).F
    return read_front_csv(reference, objectives)


def front_quality(F, reference) -> dict:
    """Hypervolume ratio, IGD+, share of reference points found and sizes."""
    F = np.asarray(F, dtype=float)
    return {
        "hv_ratio": float(hv_ratio(F, reference)),
        "igd_plus": float(igd_plus(F, reference)),
        "reference_points_found": float(coverage(F, reference)),
        "front_size": int(len(F)),
        "reference_size": int(len(reference)),
    }
