"""The Python examples of README.md and docs/python.md, run as written (in order, one namespace per page) from a
folder laid out as the repository; a block that opens a window is left out (test_sketch_window.py covers windows)."""
import os
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def blocks(page):
    return re.findall(r"^```python\n(.*?)^```", (ROOT / page).read_text(), re.S | re.M)


@pytest.mark.parametrize("page", ["README.md", "docs/python.md"])
def test_examples_run(page, tmp_path, monkeypatch, shared_data):
    clone = tmp_path / "clone"
    clone.mkdir()
    for entry in ("examples", "scenes"):
        (clone / entry).symlink_to(ROOT / entry)
    (tmp_path / "shared").mkdir()
    (tmp_path / "shared" / "data").symlink_to(shared_data)  # ../shared/data, as beside a clone
    monkeypatch.chdir(clone)
    monkeypatch.setenv("TESSERA_SHARED_DATA", str(shared_data))
    namespace = {"__name__": "__docs__"}
    ran = 0
    for code in blocks(page):
        if "window=True" in code:
            continue
        exec(compile(code, f"{page} block {ran + 1}", "exec"), namespace)
        ran += 1
    assert ran >= (1 if page == "README.md" else 10)
