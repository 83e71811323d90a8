"""Shared pytest fixtures of the PlateImpact Python tests."""
import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="session")
def fmu_path() -> Path:
    """The FMU under test: $PLATEIMPACT_FMU, else <repo>/build/PlateImpact.fmu."""
    return Path(os.environ.get("PLATEIMPACT_FMU", REPO / "build" / "PlateImpact.fmu"))
