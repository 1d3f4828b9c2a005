"""The notebooks run top to bottom in their quick mode (GAPATH_QUICK=1)."""

from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"


@pytest.mark.parametrize(
    "name",
    [
        "01_quickstart.ipynb",
        "02_encodings.ipynb",
        "03_dense.ipynb",
        "04_exact_vs_ga.ipynb",
        "05_mars.ipynb",
        "06_dynamic.ipynb",
        "07_free_paths.ipynb",
    ],
)
def test_notebook_runs_in_quick_mode(name, monkeypatch):
    path = NOTEBOOKS / name
    nb = nbformat.read(path, as_version=4)
    assert all(not c.get("outputs") for c in nb.cells if c.cell_type == "code"), (
        f"{name}: commit notebooks without outputs"
    )
    monkeypatch.setenv("GAPATH_QUICK", "1")
    client = nbclient.NotebookClient(
        nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(NOTEBOOKS)}}
    )
    client.execute()  # raises CellExecutionError with the cell and traceback on failure
    errors = [o for c in nb.cells for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors
    # the notebooks plot: at least one image was produced
    images = [o for c in nb.cells for o in c.get("outputs", []) if "image/png" in o.get("data", {})]
    assert images, f"{name}: no plot"
