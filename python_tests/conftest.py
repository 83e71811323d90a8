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
