"""Accuracy on request (docs/theory.md §22): the flow law with a tolerance through fmpy, as users run
it. On §5.2's release (8600 Pa onto the lower obstacle, dt = 1e-5 s, h = 1e-4 s) corner_1 over
0.3 s stays inside the tolerance of a converged reference and error_estimate is within a factor 3
of the measured error; the parameters' ranges are refused with the allowed range; a tolerance a
scheme does not use, and a step the cap bounded, are warned of."""

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from plate_fmu import PlateRun

from plateimpact import PlateImpactFMU

H = 1e-4
RELEASE = dict(mass="singular_p0", time_scheme="flow", initial_load=8600.0, obstacle_upper_enabled=False)


def corner(fmu_path, stop=0.3, **parameters):
    with PlateImpactFMU(fmu_path, **RELEASE, **parameters) as plate:
        rows = [plate.step(H) for _ in range(round(stop / H))]
    return np.array([r["corner_1"] for r in rows]), rows[-1]


@pytest.fixture(scope="module")
def reference(fmu_path):
    """dt = 1.25e-6 s with 64 sub-steps per contact step: 2.1e-8 m from dt = 6.25e-7 s over these
    0.3 s (tools/tolerance_study.py), far below the tolerances checked."""
    return corner(fmu_path, dt=1.25e-6, contact_substeps=64)[0]


@pytest.mark.parametrize("tolerance", [1e-4, 1e-5])
def test_corner_within_the_tolerance_and_the_estimate_within_factor_3(fmu_path, reference, tolerance):
    c, last = corner(fmu_path, dt=1e-5, tolerance=tolerance)
    error = np.abs(c - reference).max()
    assert error <= tolerance
    assert error / 3 <= last["error_estimate"] <= 3 * error, (error, last["error_estimate"])
    assert last["capped_steps"] == 0
    # energy exact at every tolerance: the ledger E - E0 = input - damped closes (no damping here)
    assert last["energy_dissipated"] == 0.0


def test_tolerance_zero_is_the_fixed_count(fmu_path):
    """tolerance = 0 (the default) keeps contact_substeps, bit for bit, and estimates nothing."""
    a, last = corner(fmu_path, stop=0.1, dt=1e-5)
    b, _ = corner(fmu_path, stop=0.1, dt=1e-5, tolerance=0.0, contact_substeps=16)
    assert np.array_equal(a, b) and last["error_estimate"] == 0.0


@pytest.mark.parametrize(
    "name, value, allowed",
    [("tolerance", -1e-5, "0 <= tolerance <= 1"), ("max_contact_substeps", 100, "a power of two from 2 to 1024")],
)
def test_out_of_range_is_refused_with_the_allowed_range(fmu_path, name, value, allowed):
    messages = []
    with pytest.raises(FMICallException):
        PlateImpactFMU(fmu_path, logger=lambda s, c, m: messages.append(m), **{name: value})
    assert allowed in " ".join(messages), messages


def warnings(run):
    return [m for s, _, m in run.log if s == 1]


def test_a_tolerance_the_scheme_ignores_is_warned_of(fmu_path):
    with PlateRun(fmu_path, nx=4, ny=2, mass="singular_p0", time_scheme="conserving", tolerance=1e-5) as run:
        assert [m for m in warnings(run) if "used by time_scheme = flow only" in m], warnings(run)


def test_a_capped_step_is_counted_and_warned_of_once(fmu_path):
    """Two sub-steps at most against a tolerance they cannot meet: the cap bounds the work, the
    steps are counted, the estimate still grows and passes the tolerance; each is said once, the
    cap's warning naming the parameter to raise."""
    with PlateRun(fmu_path, nx=8, ny=3, **RELEASE, tolerance=1e-9, max_contact_substeps=2) as run:
        for _ in range(1000):  # the first impact near 0.07 s
            out = run.step(H)
        assert out["capped_steps"] > 0 and out["error_estimate"] > 1e-9
        for _ in range(1000):
            out = run.step(H)
        capped = [m for m in warnings(run) if "raise max_contact_substeps" in m]
        passed = [m for m in warnings(run) if "passed tolerance" in m]
        assert len(capped) == 1 and len(passed) == 1, warnings(run)
