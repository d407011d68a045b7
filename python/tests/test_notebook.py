"""The tour notebook (examples/python/tour.ipynb) runs from top to bottom in a Jupyter kernel on this interpreter, so
the kernel imports the installed package under test, and shows its pictures."""
import os
import pathlib
import sys

import pytest

import tessera

ROOT = pathlib.Path(__file__).resolve().parents[2]
NOTEBOOK = ROOT / "examples" / "python" / "tour.ipynb"


def pictures(notebook):
    """The outputs that show a picture: a PNG (Image, Canvas, ...) or HTML with an <img (a sketch's Animation)."""
    found = []
    for cell in notebook.cells:
        for output in cell.get("outputs", []):
            data = output.get("data", {})
            if "image/png" in data or "<img" in data.get("text/html", ""):
                found.append(output)
    return found


def test_tour_notebook_runs_and_shows_pictures(tmp_path, monkeypatch):
    nbclient = pytest.importorskip("nbclient")
    nbformat = pytest.importorskip("nbformat")
    pytest.importorskip("ipykernel")
    from jupyter_client.manager import KernelManager

    # The notebook finds the shared data through $TESSERA_SHARED_DATA (it runs in tmp_path, away from the
    # repository); without the data its cells that need it print a note and skip.
    data = pathlib.Path(os.environ.get("TESSERA_SHARED_DATA", ROOT.parent / "shared" / "data"))
    if data.is_dir():
        monkeypatch.setenv("TESSERA_SHARED_DATA", str(data.resolve()))
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel's debugger warning about frozen modules

    notebook = nbformat.read(NOTEBOOK, as_version=4)
    # The "python3" kernel, started with this interpreter (the installed spec may name another Python, one without
    # this package or with an older build of it).
    manager = KernelManager(kernel_name="python3")
    manager.kernel_spec.argv = [sys.executable, *manager.kernel_spec.argv[1:]]
    client = nbclient.NotebookClient(notebook, km=manager, kernel_name="python3", timeout=120,
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()  # raises CellExecutionError, with the cell and its traceback, if a cell fails

    errors = [output for cell in notebook.cells for output in cell.get("outputs", [])
              if output.get("output_type") == "error"]
    assert not errors
    # Its first code cell prints where tessera came from: the package this test imported.
    first = next(cell for cell in notebook.cells if cell.cell_type == "code")
    printed = "".join(output.get("text", "") for output in first.outputs if output.get("output_type") == "stream")
    assert tessera.__file__ in printed, printed
    shown = pictures(notebook)
    assert len(shown) >= 8, f"{len(shown)} pictures"
