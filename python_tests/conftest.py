"""Shared pytest fixtures of the PlateImpact Python tests."""

import os
import zipfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="session")
def fmu_path() -> Path:
    """The FMU under test: $PLATEIMPACT_FMU, else <repo>/build/PlateImpact.fmu."""
    return Path(os.environ.get("PLATEIMPACT_FMU", REPO / "build" / "PlateImpact.fmu"))


@pytest.fixture(scope="session")
def extracted_fmu(fmu_path, tmp_path_factory) -> Path:
    """The FMU unzipped once per session (tests that load the binary themselves)."""
    assert fmu_path.is_file(), f"FMU not built: {fmu_path} (build it or set PLATEIMPACT_FMU)"
    target = tmp_path_factory.mktemp("fmu")
    with zipfile.ZipFile(fmu_path) as archive:
        archive.extractall(target)
    assert (target / "binaries" / "linux64" / "PlateImpact.so").is_file()
    return target


# Tests that share a resource outside their tmp_path run in one pytest-xdist worker (test.sh runs
# `pytest -n auto --dist loadgroup`): the Wine prefix build-win64/wineprefix (made on first use).
SERIAL = {"test_win64.py": "wine"}

# `slow`: left out of the developer loop (`bash test.sh --quick`, `pytest -m "not slow"`); test.sh
# runs them all. A file name (every test in it) or a test's name without its parameters. Chosen
# by `pytest --durations=40`: each costs more than about 5 s of one core.
SLOW = {
    # files: builds, emulators, valgrind, subprocess catalogues
}


def pytest_collection_modifyitems(config, items):
    for item in items:
        file = item.path.name
        if file in SERIAL:
            item.add_marker(pytest.mark.xdist_group(SERIAL[file]))
        if file in SLOW or f"{file}::{item.originalname}" in SLOW:
            item.add_marker(pytest.mark.slow)
