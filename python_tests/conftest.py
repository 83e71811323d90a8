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
    # one qemu-aarch64 process for the C master and the QEMU_SUITE experiments (aarch64_chain: 49 s)
    "test_aarch64.py": "aarch64",
    "test_experiments_platforms.py::test_every_experiment_within_tolerance": "aarch64",
    "test_tolerance.py": "tolerance",  # the reference at dt = 1.25e-6 s, 64 sub-steps
    "test_speed_report.py": "speed-report",  # tools/speed_vs_error.py --quick (summary: 10 s)
    "test_elements_agree.py": "elements",  # the Argyris run both tests compare with
    "test_intermediate_inputs.py": "intermediate-inputs",  # three 0.2 s runs with a callback per step
    "test_impact_episodes.py": "impact-episodes",  # the default scene's 0.6 s (9 s)
    # the validator's run of every experiment, read by both (test_references.py's validator_run)
    "test_references.py::test_validator_passes_every_experiment": "references-validator",
    "test_references.py::test_serialized_state_restored_in_a_new_process_continues_bit_for_bit_here": (
        "references-validator"
    ),
}

# `slow`: left out of the developer loop (`bash test.sh --quick`, `pytest -m "not slow"`); test.sh
# runs them all. A file name (every test in it) or a test's name without its parameters. Chosen
# by `pytest --durations=60` (times of one core, no workers).
SLOW = {
    # compiles the whole solver from the source FMU (~50 s of CPU) where no aarch64 build of it is at hand
    "test_source_fmu.py",
    "test_aarch64.py",  # the C master under qemu-aarch64 (28 s)
    "test_win64.py",  # Wine (25 s)
    "test_valgrind.py",  # memcheck (6 s)
    "test_primary_copy.py::test_copies_loaded_and_unloaded_by_a_c_master_are_clean_under_memcheck",  # (5 s)
    "test_primary_copy.py::test_copies_of_the_win64_dll_share_the_first_ones_plate_under_wine",  # Wine
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
    "test_golden_emulated.py",  # the C golden driver under qemu-x86_64 (the CPU class the host is not: 43 s)
    "test_experiments_platforms.py",  # the experiments under Wine and qemu-aarch64 (53 s)
    "test_master_cofmupy.py",  # CoFmuPy's own interpreter, where it is installed (11 s)
}


# The sanitizer stage (scripts/sanitizer-stage.sh) runs the tests marked `sanitizer` but not
# `repeats_paths`. A test of a `sanitizer` file left out of it is marked
# `repeats_paths(<covering>...)`: each argument names what runs its code paths under ASan + UBSan
# instead: a test of the stage (its node id, as `pytest --collect-only -q` prints it from
# python_tests/), or a libFuzzer harness (fuzz/<harness>.cpp, the fuzz stage, the same build).
# test_sanitizer_selection.py checks that every name is one. Where a test's parameters differ in
# this, the decorator cannot say it: the node ids here, each with what covers it.
LEFT_OUT_OF_THE_SANITIZER_STAGE = {
    "test_physics.py::test_static_beam_limit_is_exact[argyris]": (
        "test_physics.py::test_static_beam_limit_is_exact[fvs]",  # the static solve, the other element
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[argyris]",
    ),
    # No obstacles on the paper's mesh: the same engine and free flight as FVS's (its plate has no
    # contact rows either), the Argyris element's stepping in the state test (issue 54: its plate,
    # built for it alone, was 15 s of the stage's CPU under ASan)
    "test_physics.py::test_energy_is_conserved_without_contact_and_input[argyris-0.5]": (
        "test_physics.py::test_energy_is_conserved_without_contact_and_input[fvs-0.5]",
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[argyris]",
    ),
    "test_physics.py::test_energy_is_conserved_without_contact_and_input[argyris-0.25]": (
        "test_physics.py::test_energy_is_conserved_without_contact_and_input[fvs-0.5]",  # β changes numbers only
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[argyris]",
    ),
    "test_physics.py::test_energy_is_conserved_without_contact_and_input[fvs-0.25]": (
        "test_physics.py::test_energy_is_conserved_without_contact_and_input[fvs-0.5]",
    ),
    "test_physics.py::test_free_vibration_dissipates_at_impacts_and_respects_the_obstacle[argyris]": (
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[argyris]",  # impacts
        "test_conserving.py::test_no_reported_displacement_passes_an_obstacle[scene1]",  # the released shape
    ),
    "test_physics.py::test_free_vibration_dissipates_at_impacts_and_respects_the_obstacle[fvs]": (
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[fvs]",
    ),
    # base motion, load and both obstacles: the scene of test_fmi_conformance.py's CONFIGS
    "test_physics.py::test_energy_ledger_with_base_load_and_both_obstacles[argyris]": (
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[argyris]",
    ),
    "test_physics.py::test_energy_ledger_with_base_load_and_both_obstacles[fvs]": (
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[fvs]",
    ),
    "test_physics.py::test_energy_ledger_of_the_reduced_model[argyris-6]": (
        "test_physics.py::test_energy_ledger_of_the_reduced_model[fvs-6]",
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[reduced_modal]",
    ),
    "test_physics.py::test_energy_ledger_of_the_reduced_model[argyris-20]": (
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[reduced_modal]",
    ),
    "test_physics.py::test_energy_ledger_of_the_reduced_model[fvs-20]": (
        "test_physics.py::test_energy_ledger_of_the_reduced_model[fvs-6]",
    ),
    "test_conserving.py::test_the_paper_scheme_lets_free_edge_mid_pass_the_obstacle": (
        "test_conserving.py::test_no_reported_displacement_passes_an_obstacle[scene0]",  # the same scene, conserving
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[argyris]",  # the paper's
    ),
    "test_conserving.py::test_momentum_balance_of_the_port": (
        "test_conserving.py::test_work_of_the_clamp_force_is_the_energy_input_through_impacts[0]",  # the port sums
        "test_port.py::test_velocity_and_acceleration_drives_give_the_displacement_drive[velocity]",
    ),
    "test_conserving.py::test_flow_scheme_closes_the_ledger_through_impacts[1e-05]": (
        "test_conserving.py::test_flow_scheme_closes_the_ledger_through_impacts[4e-05]",  # dt changes numbers only
    ),
    "test_conserving.py::test_flow_scheme_closes_the_ledger_through_impacts[2e-05]": (
        "test_conserving.py::test_flow_scheme_closes_the_ledger_through_impacts[4e-05]",
    ),
    "test_port.py::test_2048_hz_signal_through_simulate_fmu": (
        "test_fmi_conformance.py::test_simulate_fmu_runs",  # fmpy's simulate_fmu
        "test_port.py::test_a_step_of_half_dt_interpolates_the_grid",  # steps off the grid
        "test_input_reconstruction.py::test_reconstruction_with_varying_steps_and_a_master_time_with_roundoff",
    ),
    "test_port.py::test_probe_velocity_and_acceleration_are_the_differences_of_the_displacements": (
        "test_port.py::test_velocity_and_acceleration_drives_give_the_displacement_drive[velocity]",
        "test_port.py::test_port_outputs_at_t0_describe_the_initial_state[scene0-law0]",
    ),
    "test_input_reconstruction.py::test_fmpy_simulate_with_an_input_file_meets_the_goal": (
        "test_input_reconstruction.py::test_reconstruction_is_exact_for_the_polynomials_it_represents[ramp-linear]",
        "test_fmi_conformance.py::test_simulate_fmu_runs",
    ),
    # libcosim's run: values only at every step, steps an importer rounds, its order of calls
    "test_libcosimpy.py::test_libcosimpy_and_fmpy_give_the_same_outputs": (
        "test_input_reconstruction.py::test_held_load_step_is_applied_as_a_step_under_the_default_mode",
        "test_fmi_conformance.py::test_status_functions_and_tolerant_step_sizes",
        "fuzz/call_sequence.cpp",  # call orders, legal and not
    ),
    "test_libcosimpy.py::test_libcosimpy_sets_the_integer_switches_on_the_unmodified_fmu": (
        "test_input_reconstruction.py::test_unknown_mode_is_rejected[base_input_mode-4]",  # an Integer switch set
        "fuzz/parameters.cpp",  # every Integer parameter, its edges and past them
    ),
    # A plate with the upper obstacle off, then the default plate: both instances' setup and the
    # cache's lookups run in the stage wherever one obstacle is off (scene1: released onto the
    # lower one) and wherever a second instance shares a plate (the threads); which parameters
    # make a key is the C++ unit test DiscretizationCache.EveryKeyParameterChangesTheResult's (issue 54:
    # 35 s of the stage's CPU, its two default-mesh plates built for it alone under ASan)
    "test_discretization_cache.py::test_a_plate_built_with_one_obstacle_is_not_shared_with_one_that_has_both": (
        "test_conserving.py::test_no_reported_displacement_passes_an_obstacle[scene1]",
        "test_fmi_conformance.py::test_two_threads_match_sequential_runs[flow]",
    ),
    # the cache's sharing runs in every test here that makes a second instance of a plate
    "test_discretization_cache.py::test_a_shared_plate_gives_the_golden_output_bit_for_bit": (
        "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[argyris]",
        "test_fmi_conformance.py::test_two_threads_match_sequential_runs[flow]",
    ),
}


def xdist_group_of(nodeid):
    """The group of SERIAL or SHARED_FIXTURE a node id belongs to, or None."""
    path, _, rest = nodeid.partition("::")
    file = path.rsplit("/", 1)[-1]
    name = rest.split("::")[-1].split("[")[0]
    for key in (f"{file}::{name}", file):
        if key in SHARED_FIXTURE:
            return SHARED_FIXTURE[key]
    return SERIAL.get(file)


def pytest_xdist_make_scheduler(config, log):
    """`--dist loadgroup` with the groups above read from the node ids by the controller.

    pytest-xdist 3.8's loadgroup finds a test's group in a suffix its workers append to the node id
    (`item._nodeid`), which pytest 9 no longer reads (the node id lives in `item._id`): the
    `xdist_group` markers below had no effect, so each worker made a SHARED_FIXTURE again (the
    catalogue's 69 child processes ran twice, test_intermediate_inputs.py's three runs twice, ...)
    and SERIAL's tests ran in both workers (issue 54, found by `--durations`). The scheduler here
    takes the group from the tables, whatever the versions."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadGroupScheduling

    class TableGroupScheduling(LoadGroupScheduling):
        def _split_scope(self, nodeid):
            return xdist_group_of(nodeid) or super()._split_scope(nodeid)

    return TableGroupScheduling(config, log)


# tryfirst: before pytest's own -m deselection, so that the markers it selects by are there and
# PLATEIMPACT_LIST_REPEATS_PATHS lists every test left out (test_sanitizer_selection.py)
@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    list_repeats_paths = os.environ.get("PLATEIMPACT_LIST_REPEATS_PATHS") == "1"
    for item in items:
        file = item.path.name
        covering = LEFT_OUT_OF_THE_SANITIZER_STAGE.get(f"{file}::{item.name}")
        if covering:
            item.add_marker(pytest.mark.repeats_paths(*covering))
        if list_repeats_paths and item.get_closest_marker("sanitizer"):
            left_out = item.get_closest_marker("repeats_paths")
            if left_out:  # for test_sanitizer_selection.py
                print(f"repeats_paths {item.nodeid} -> {' '.join(left_out.args)}")
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


# After every test fmpy's native logger proxy points at a logger this module keeps alive (why:
# fmpy_callbacks.py; seen in test_fmi3 after test_silent_answers).
_KEPT_LOGGER: list = []


@pytest.fixture(autouse=True)
def _fmpy_logger_proxy_kept_alive():
    yield
    from ctypes import byref

    from fmpy.fmi2 import printLogMessage
    from fmpy.logging import addLoggerProxy
    from fmpy_callbacks import callbacks

    if not _KEPT_LOGGER:
        _KEPT_LOGGER.append(callbacks(printLogMessage).logger)
    fresh = callbacks(printLogMessage)  # the proxy replaces the struct's logger: a fresh struct each time
    fresh.logger = _KEPT_LOGGER[0]
    addLoggerProxy(byref(fresh))
    _KEPT_LOGGER.append(fresh)
    del _KEPT_LOGGER[1:-1]
