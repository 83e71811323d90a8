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


@pytest.fixture(scope="session")
def fmu3(fmu_path) -> Path:
    """The FMI 3.0 FMU under test: $PLATEIMPACT_FMU3, else fmi3/PlateImpact.fmu beside fmu_path."""
    path = Path(os.environ.get("PLATEIMPACT_FMU3", Path(fmu_path).parent / "fmi3" / "PlateImpact.fmu"))
    assert path.is_file(), f"FMI 3.0 FMU not built: {path}"
    return path


@pytest.fixture(scope="session")
def unzipped3(fmu3, tmp_path_factory):
    """(unzip directory, model description) of the FMI 3.0 FMU, extracted once per session."""
    from fmpy import extract, read_model_description

    return extract(str(fmu3), str(tmp_path_factory.mktemp("fmu3"))), read_model_description(str(fmu3))


# Tests that share a resource outside their tmp_path run in one pytest-xdist worker (test.sh runs
# `pytest -n auto --dist loadgroup`): the Wine prefix build-win64/wineprefix (made on first use).
SERIAL = {"test_win64.py": "wine"}
# Tests that share a module fixture that is expensive to make, in one worker so that it is made
# once (spread over the workers, each worker made it again: issue 46 found the work twice). A file
# name (every test in it) or a file's test without its parameters; each its own group, so that the
# groups still spread over the workers.
SHARED_FIXTURE = {
    "test_fmi_conformance.py::test_catalogue": "fmi-catalogue",  # 69 child processes (catalogue_outcomes)
    "test_aarch64.py": "aarch64",  # the C master under qemu-aarch64 (runs: 28 s)
    "test_tolerance.py": "tolerance",  # the reference at dt = 1.25e-6 s, 64 sub-steps
    "test_speed_report.py": "speed-report",  # tools/speed_vs_error.py --quick (summary: 10 s)
    "test_elements_agree.py": "elements",  # the Argyris run both tests compare with
    "test_intermediate_inputs.py": "intermediate-inputs",  # three 0.2 s runs with a callback per step
    "test_impact_episodes.py": "impact-episodes",  # the default scene's 0.6 s (9 s)
}

# `slow`: left out of the developer loop (`bash test.sh --quick`, `pytest -m "not slow"`); test.sh
# runs them all. A file name (every test in it) or a test's name without its parameters. Chosen
# by `pytest --durations=60` (times of one core, no workers).
SLOW = {
    "test_source_fmu.py",  # compiles the whole solver from the source FMU (145 s)
    "test_golden.py::test_golden_bit_for_bit_on_other_cpus",  # Python under qemu-x86_64 (40 s each)
    "test_aarch64.py",  # the C master under qemu-aarch64 (28 s)
    "test_win64.py",  # Wine (25 s)
    "test_valgrind.py",  # memcheck (6 s)
    "test_speed_report.py",  # tools/speed_vs_error.py --quick (10 s)
    "test_examples.py",  # the examples as users run them (17 s)
    "test_fmi_conformance.py::test_catalogue",  # one child process per case (31 s)
    "test_fmi_conformance.py::test_two_threads_match_sequential_runs",
    "test_impact_laws.py::test_singular_mass_energy_through_impacts_converges_in_dt",
    "test_references.py::test_validator_passes_every_experiment",
    "test_system_model.py::test_coupled_system_reaches_the_held_input_accuracy",
    "test_stability.py::test_stability_case",  # the stress matrix, short horizons (25 s)
    "test_conserving.py::test_conserving_and_singular_p0_tend_to_the_same_impact_times",
    "test_fmi3.py::test_animate_example_quick",
    "test_golden_emulated.py",  # the C golden driver under qemu-x86_64 (Nehalem, Haswell: 79 s)
    "test_experiments_platforms.py",  # the experiments under Wine and qemu-aarch64 (53 s)
    "test_master_cofmupy.py",  # CoFmuPy's own interpreter, where it is installed (11 s)
}


def pytest_collection_modifyitems(config, items):
    for item in items:
        file = item.path.name
        if file in SERIAL:
            item.add_marker(pytest.mark.xdist_group(SERIAL[file]))
        for key in (file, f"{file}::{item.originalname}"):
            if key in SHARED_FIXTURE:
                item.add_marker(pytest.mark.xdist_group(SHARED_FIXTURE[key]))
        if file in SLOW or f"{file}::{item.originalname}" in SLOW:
            item.add_marker(pytest.mark.slow)
    # The slow ones first (a stable sort): pytest-xdist hands tests out in this order, so the long
    # ones start while the short ones fill the other worker, instead of running alone at the end.
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)


# fmpy formats FMI 2.0 log messages in a native proxy that keeps one global pointer to the last Python
# logger registered (fmpy.logging.addLoggerProxy). A simulate_fmu(..., logger=f) registers f's ctypes
# callback and drops it when it returns, so the next FMU that logs through fmpy's default callbacks in
# the same process calls freed memory (a segfault of an xdist worker, seen in test_fmi3 after
# test_silent_answers). After every test the global points at one logger this module keeps alive.
_KEPT_LOGGER: list = []


@pytest.fixture(autouse=True)
def _fmpy_logger_proxy_kept_alive():
    yield
    from ctypes import byref

    from fmpy.fmi2 import (
        calloc,
        fmi2CallbackAllocateMemoryTYPE,
        fmi2CallbackFreeMemoryTYPE,
        fmi2CallbackFunctions,
        fmi2CallbackLoggerTYPE,
        free,
        printLogMessage,
    )
    from fmpy.logging import addLoggerProxy

    if not _KEPT_LOGGER:
        callbacks = fmi2CallbackFunctions()
        callbacks.logger = fmi2CallbackLoggerTYPE(printLogMessage)
        callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        _KEPT_LOGGER.append((callbacks, callbacks.logger))
    python_logger = _KEPT_LOGGER[0][1]
    fresh = fmi2CallbackFunctions()  # the proxy replaces the struct's logger: register a fresh one
    fresh.logger = python_logger
    addLoggerProxy(byref(fresh))
    _KEPT_LOGGER.append(fresh)
    del _KEPT_LOGGER[1:-1]
