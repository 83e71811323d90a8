"""No silent wrong answer (issue 40, item 1): a result the FMU computes but that is likely not what
the user meant comes with one warning (status fmi2Warning, category logStatusWarning, logged even
with loggingOn = false, as errors are) naming the cause and the fix; a dt that resolves nothing
of the plate's motion is refused with the allowed range. A normal run logs no warning.

The yardstick is the first period of the clamped-free strip, T1 = 2π L² / (1.8751² √(D/ρh))
(the default plate: 0.164 s; its first mode 5.95 Hz, T1 = 0.168 s)."""

import math

import fmpy
import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from long_steps import _restore_fmpy_logger
from plate_fmu import PlateRun

from plateimpact import PlateImpactFMU

SMALL = dict(nx=4, ny=2)
E, NU, T, RHO, L = 2.1e11, 0.3, 0.01, 7770.0, 1.2
T1 = 2 * math.pi * L**2 / (1.8751**2 * math.sqrt(E * T**3 / (12 * (1 - NU**2)) / (RHO * T)))


def warnings(run):
    return [m for s, _, m in run.log if s == 1]


def test_a_normal_run_warns_of_nothing(fmu_path):
    with PlateRun(fmu_path, **SMALL, dt=1e-4) as run:
        for _ in range(20):
            run.step(1e-4, base=0.001)
        run.close()
        assert warnings(run) == []


def test_a_dt_that_resolves_nothing_is_refused(fmu_path):
    """dt = 1 s (inside dt's own range): a 1 s run returned all-zero outputs without a word."""
    messages = []
    with pytest.raises(FMICallException):
        PlateImpactFMU(fmu_path, logger=lambda s, c, m: messages.append(m), **SMALL, dt=1.0)
    text = " ".join(messages)
    assert "invalid parameter dt = 1" in text and "first period" in text, text
    bound = float(text.split("dt <= ")[1].split(" s")[0])
    assert bound == pytest.approx(T1 / 2, rel=1e-4)  # the allowed range is the stated one
    # just inside the bound: built (and warned of)
    with PlateRun(fmu_path, **SMALL, dt=0.99 * bound) as run:
        assert [m for m in warnings(run) if "first period" in m]


def test_a_coarse_dt_is_warned_of_once(fmu_path):
    dt = T1 / 10  # five times coarser than T1/20, allowed
    with PlateRun(fmu_path, **SMALL, dt=dt) as run:
        for _ in range(3):
            run.step(dt, base=0.0)
        run.close()
        coarse = [m for m in warnings(run) if "first period" in m]
        assert len(coarse) == 1 and "dt <= " in coarse[0], warnings(run)


def test_a_load_only_run_is_told_once_at_the_info_level(fmu_path):
    """Issue 53: a run that never sets the clamp's input (the paper's §5.2 release: a load only, or
    none) is a scene as likely meant as not: one message at the info level, no warning a user learns
    to ignore."""
    with PlateRun(fmu_path, logger=lambda *entry: None, **SMALL, dt=1e-4) as run:
        for _ in range(5):
            run.step(1e-4, base=None, load=100.0)
        run.close()
        assert warnings(run) == [], warnings(run)
        told = [m for _, category, m in run.log if category == "logInfo" and "never set" in m]
        assert len(told) == 1 and "base_displacement" in told[0] and "load-only" in told[0], run.log


def test_a_motion_input_of_another_drive_is_warned_of_at_the_end(fmu_path):
    """The warning stays where it catches a mistake: base_velocity set while base_drive =
    displacement reads base_displacement (never set), the clamp stands still."""
    with PlateRun(fmu_path, **SMALL, dt=1e-4) as run:
        for _ in range(5):
            run.set("base_velocity", 0.01)
            run.step(1e-4, base=None, load=100.0)
        assert warnings(run) == []  # nothing to say before the run ends
        run.close()
        never = [m for m in warnings(run) if "never set" in m]
        assert len(never) == 1 and never[0].startswith("fmi2Terminate: base_velocity was set"), warnings(run)
        assert "base_drive = displacement moves the clamp by base_displacement" in never[0], never


def test_outputs_interpolated_inside_one_grid_step_are_warned_of_once(fmu_path):
    dt = 1e-4
    with PlateRun(fmu_path, **SMALL, dt=dt) as run:
        for _ in range(6):
            run.step(0.3 * dt, base=0.0)
        inside = [m for m in warnings(run) if "interpolated" in m]
        assert len(inside) == 1 and "whole multiple of dt" in inside[0], warnings(run)


def test_an_experiment_tolerance_is_said_to_change_nothing_at_the_warning_level(fmu_path):
    """fmpy's relative_tolerance (FMI's experiment tolerance) does not reach the fixed-grid scheme: the
    results are the same bits, and the FMU says so as a Warning (an OK message fmpy hides), naming
    the parameters that do set the accuracy (issue 71)."""
    said = []

    def logger(component, instance, status, category, message):
        said.append((status, message.decode()))

    kwargs = dict(stop_time=0.01, output_interval=1e-3, output=["corner_1"])
    plain = fmpy.simulate_fmu(str(fmu_path), **kwargs)
    try:
        tight = fmpy.simulate_fmu(str(fmu_path), relative_tolerance=1e-9, logger=logger, **kwargs)
    finally:
        _restore_fmpy_logger()
    assert np.array_equal(plain["corner_1"], tight["corner_1"])
    warned = [m for s, m in said if s == 1 and "tolerance = 1e-09" in m]
    assert len(warned) == 1, said
    assert "the parameter dt" in warned[0] and "the parameter tolerance" in warned[0], warned


def test_a_costly_run_is_said_once_at_the_warning_level(fmu_path):
    """A run whose estimated cost passes a minute of CPU per simulated second says so once, as a
    Warning (fmpy hides OK and info-level lines), with what would make it cheaper (issue 70): the
    small plate's step over dt = 1e-9 s. The same plate at dt = 1e-4 (above) warns of nothing."""
    with PlateRun(fmu_path, **SMALL, dt=1e-9) as run:
        run.close()
        costly = [m for m in warnings(run) if "each simulated second will cost" in m]
        assert len(costly) == 1, warnings(run)
        assert "coarser mesh" in costly[0] and "obstacle_lower_x_min" in costly[0], costly


def test_a_call_after_a_refused_one_says_how_to_go_on(fmu_path):
    """After a refused call the instance is in the error state; every later call is refused too, and
    its message says what is still allowed: reset, set a saved state, or free (issue 71)."""
    plate = PlateImpactFMU(fmu_path, initialize=False, logger=lambda *entry: None)
    try:
        with pytest.raises(Exception):
            plate.initialize({"thickness": -1.0})
        with pytest.raises(Exception):
            plate.step(1e-3)
        last = plate.errors()[-1]
        assert "fmi2DoStep is not allowed in state error" in last, plate.errors()
        assert "fmi2Reset" in last and "fmi2SetFMUstate" in last and "fmi2FreeInstance" in last, last
    finally:
        plate.free()


def test_a_drifting_integrated_clamp_is_refused_naming_the_input_driven(fmu_path):
    """base_drive = acceleration with a sine's acceleration -A w^2 sin(w t): the clamp starts at rest, so
    its velocity is A w (cos(w t) - 1) and it drifts by -A w t (5.7 m/s for the README's 10 Hz, 0.09 m
    sine) into the lower obstacle at -0.1 m within 0.02 s. The refusal names base_displacement, which
    the user never set: it now says that it is the clamp integrated from base_acceleration and why it
    drifts (issue 71)."""
    w, h = 2 * math.pi * 10.0, 1e-3
    plate = PlateImpactFMU(fmu_path, initialize=False, logger=lambda *entry: None)
    try:
        plate.initialize({"base_drive": 3})
        with pytest.raises(Exception):
            for k in range(100):
                plate.set("base_acceleration", -0.09 * w * w * math.sin(w * k * h))
                plate.step(h)
        refusal = plate.errors()[-1]
        assert "puts the clamped edge past obstacle_lower" in refusal, plate.errors()
        assert "integrated from base_acceleration" in refusal and "A w (cos(w t) - 1)" in refusal, refusal
    finally:
        plate.free()


def test_a_geometry_in_millimetres_and_a_thick_plate_are_said_in_si_units(fmu_path):
    """length 1200, width 400, thickness 10 (millimetres) runs as a 1.2 km plate; thickness = 10 (mm) on a
    plate in metres is 25 times its smaller side, outside Kirchhoff's thin-plate range; a density in
    g/cm3 and a modulus in GPa are no material's. Each is said at initialization, naming SI units
    (issue 71); the default plate (thickness 0.025 of its width) says nothing."""
    cases = {
        "a plate over 100 m": dict(length=1200.0, width=400.0, thickness=10.0),
        "outside the thin-plate range": dict(thickness=10.0),
        "density = 7.77 kg/m3": dict(density=7.77),
        "youngs_modulus = 210 Pa": dict(youngs_modulus=210.0),
    }
    for said, parameters in cases.items():
        with PlateRun(fmu_path, **SMALL, **parameters) as run:
            hits = [m for m in warnings(run) if said in m]
            assert len(hits) == 1 and "SI units" in hits[0], (said, warnings(run))
    with PlateRun(fmu_path, **SMALL) as run:
        assert not [m for m in warnings(run) if "SI units" in m], warnings(run)
