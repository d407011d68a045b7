"""The type stubs (tessera/_tessera.pyi) cover the extension module exactly: every public name, every parameter of
every signature pybind11 reports; and mypy accepts a script using the package through them."""
import ast
import pathlib
import re
import subprocess
import sys

import pytest

import tessera
import tessera.sketch
from tessera import _tessera

STUB = pathlib.Path(tessera.__file__).with_name("_tessera.pyi")


def stub_signatures():
    """{name: [parameter names of each def]} for the stub's functions and 'Class.method's."""
    tree = ast.parse(STUB.read_text())
    found = {}

    def add(name, fn):
        args = fn.args
        names = [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs if a.arg != "self"]
        found.setdefault(name, []).append(names)

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            add(node.name, node)
        elif isinstance(node, ast.ClassDef):
            found.setdefault(node.name, [])
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    add(f"{node.name}.{item.name}", item)
    return found


def top_level_split(text):
    """Splits a parameter list at the commas outside brackets (defaults like (800, 600) keep theirs)."""
    parts, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        depth += ch in "([{" and 1 or ch in ")]}" and -1 or 0
        if ch == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    return parts + [text[start:]]


def module_signatures():
    """The same from pybind11's docstrings ('name(a: int, b: float = 1.0) -> None', one line per overload)."""
    found = {}

    def add(name, obj):
        for line in (obj.__doc__ or "").splitlines():
            m = re.match(rf"^(?:\d+\. )?{re.escape(name.split('.')[-1])}\((.*)\) -> ", line.strip())
            if m:
                params = [p.split(":")[0].strip() for p in top_level_split(m.group(1)) if p.strip()]
                found.setdefault(name, []).append([p for p in params if p not in ("self", "*")])

    for name in dir(_tessera):
        obj = getattr(_tessera, name)
        if name.startswith("__") or isinstance(obj, (str, list, type(_tessera))):
            continue
        if isinstance(obj, type):
            found.setdefault(name, [])
            if hasattr(obj, "__members__"):
                continue  # an enum: the stub's _Enum has pybind11's methods, the class its members
            for attr, member in vars(obj).items():
                if not attr.startswith("__") or attr == "__init__":
                    if callable(member) or isinstance(member, staticmethod):
                        add(f"{name}.{attr}", getattr(obj, attr))
        elif callable(obj):
            add(name, obj)
    return found


def test_every_name_and_parameter_has_its_stub():
    stub, module = stub_signatures(), module_signatures()
    exceptions = {"Error", "InvalidInput", "IoError", "TopologyError", "MemoryBudgetError"}
    missing = sorted(n for n in module if n not in stub and n.split(".")[0] not in exceptions)
    assert not missing, f"not in {STUB.name}: {missing}"
    for name, overloads in module.items():
        if name in stub and overloads:
            assert sorted(map(tuple, stub[name])) == sorted(map(tuple, overloads)), name
    stale = sorted(n for n in stub if n not in module and "." not in n and n != "_Enum")  # _Enum: the stub's own
    assert not stale, f"in {STUB.name} but not in the module: {stale}"


def test_mypy_accepts_typed_use(tmp_path):
    pytest.importorskip("mypy")
    script = tmp_path / "use.py"
    script.write_text(
        "import numpy as np\nimport tessera\n"
        "mesh: tessera.Mesh = tessera.subdivide(tessera.cube(), 'catmull-clark', 2, limit=True)\n"
        "image: tessera.Image = tessera.render_mesh(mesh, size=(64, 48))\n"
        "hsv: np.ndarray = tessera.convert_colors(np.zeros((4, 3)), 'rgb', 'hsv', hue='degrees')\n"
        "t, ids, uv = tessera.RayCaster(mesh).cast(np.zeros((1, 3)), np.ones((1, 3)))\n")
    result = subprocess.run([sys.executable, "-m", "mypy", "--ignore-missing-imports", "--no-incremental",
                             "--cache-dir", str(tmp_path / "cache"), str(script)], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


def test_every_public_function_has_help():
    """help() says what each call does: a docstring beyond pybind11's signature lines."""
    def text(obj):
        lines = [line.strip() for line in (obj.__doc__ or "").splitlines()]
        return [line for line in lines if line and line != "Overloaded function."
                and not re.match(r"^(\d+\. )?\w+\(.*\) -> ", line)]

    undocumented = []
    for name in dir(_tessera):
        obj = getattr(_tessera, name)
        if name.startswith("_") or isinstance(obj, (str, list)):
            continue
        if isinstance(obj, type) and hasattr(obj, "__members__"):
            continue  # the enums: their members are the documentation
        if not text(obj):
            undocumented.append(name)
        if isinstance(obj, type) and not issubclass(obj, BaseException):
            for attr, member in vars(obj).items():
                if (attr == "__init__" or not attr.startswith("_")) and (callable(member) or isinstance(member, property)):
                    if not text(getattr(obj, attr)):
                        undocumented.append(f"{name}.{attr}")
    for name in dir(tessera) + [f"sketch.{n}" for n in dir(tessera.sketch)]:
        obj = getattr(tessera.sketch, name[7:]) if name.startswith("sketch.") else getattr(tessera, name)
        if not name.split(".")[-1].startswith("_") and callable(obj) and not isinstance(obj, type) and not text(obj):
            undocumented.append(name)
    assert not undocumented, undocumented
