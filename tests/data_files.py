"""Where the tests find real maps, scenario files and elevation rasters.

The small files live in the repository, in ``tests/data/`` (see its README:
sources, licences, SHA-256); a fresh clone runs every test that needs them.
The large ones (512x512 MovingAI maps, the Berlin street maps, the Willow
Garage ROS map, the Earth DEM) stay optional: they are looked up in
``$GAPATH_SHARED_DATA`` and then in ``../shared/data`` next to the clone, and
a test that needs one of them is skipped when it is in neither.

Every folder has the same layout (``movingai/mapf``, ``movingai/grid``,
``ros/<name>``, ``dem``), so a relative name such as
``"movingai/mapf/den312d.map"`` means the same file everywhere; a map and its
``.scen`` always come from the same folder.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

#: The data committed with the tests.
TESTS_DATA = Path(__file__).resolve().parent / "data"


def data_roots() -> list[Path]:
    """The data folders that exist, searched in this order: ``tests/data``,
    ``$GAPATH_SHARED_DATA``, ``../shared/data`` (beside the repository)."""
    candidates = [TESTS_DATA]
    if os.environ.get("GAPATH_SHARED_DATA"):
        candidates.append(Path(os.environ["GAPATH_SHARED_DATA"]))
    candidates.append(Path(__file__).resolve().parents[2] / "shared" / "data")
    roots = []
    for p in candidates:
        if p.is_dir() and p.resolve() not in [r.resolve() for r in roots]:
            roots.append(p)
    return roots


def find_data(name: str) -> Path | None:
    """The file ``name`` (relative, e.g. ``"movingai/grid/arena.map"``) from
    the first data folder that has it, or None."""
    for root in data_roots():
        if (root / name).is_file():
            return root / name
    return None


def data_path(name: str) -> Path:
    """:func:`find_data`, or skip the calling test when no folder has the file."""
    path = find_data(name)
    if path is None:
        pytest.skip(
            f"optional test data {name!r} not found (not in tests/data; "
            "looked in $GAPATH_SHARED_DATA and ../shared/data)"
        )
    return path


def glob_data(pattern: str) -> list[Path]:
    """Files matching ``pattern`` (relative glob) in any data folder, one per
    relative name (the first folder wins), sorted by relative name."""
    found: dict[str, Path] = {}
    for root in data_roots():
        for p in root.glob(pattern):
            found.setdefault(p.relative_to(root).as_posix(), p)
    return [found[k] for k in sorted(found)]
