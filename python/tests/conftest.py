"""Shared fixtures: the installed package (never the source tree's), the shared data, the CLI to compare with."""
import os
import pathlib
import subprocess

import pytest

import tessera

ROOT = pathlib.Path(__file__).resolve().parents[2]


def pytest_report_header():
    return f"tessera {tessera.__version__} from {tessera.__file__}"


@pytest.fixture(scope="session")
def shared_data():
    """The shared data folder (../shared/data or $TESSERA_SHARED_DATA); tests that need it skip without it."""
    path = pathlib.Path(os.environ.get("TESSERA_SHARED_DATA", ROOT.parent / "shared" / "data"))
    if not path.is_dir():
        pytest.skip(f"no shared data at {path}")
    return path


@pytest.fixture(scope="session")
def cli():
    """Runs the tessera command line (TESSERA_CLI, set by run.sh) and checks it succeeded."""
    exe = os.environ.get("TESSERA_CLI")
    if not exe:
        pytest.skip("TESSERA_CLI is not set (run through python/tests/run.sh)")

    def run(*args):
        return subprocess.run([exe, *map(str, args)], check=True, capture_output=True, text=True)

    return run
