"""No silent wrong answer (issue 40, item 1): a result the FMU computes but that is likely not what
the user meant comes with one warning (status fmi2Warning, category logStatusWarning, logged even
with loggingOn = false, as errors are) naming the cause and the fix; a dt that resolves nothing
of the plate's motion is refused with the allowed range. A normal run logs no warning.

The yardstick is the first period of the clamped-free strip, T1 = 2π L² / (1.8751² √(D/ρh))
(the default plate: 0.164 s; its first mode 5.95 Hz, T1 = 0.168 s)."""

import math
import re

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
        # the refused value is named as the input driven, not as base_displacement (never set)
        assert ": the clamp's position (integrated from base_acceleration) = -0.1" in refusal, refusal
        assert ": base_displacement =" not in refusal and "<= base_displacement <=" not in refusal, refusal
    finally:
        plate.free()


def run_integrated_clamp(fmu_path, acceleration, steps, h=1e-3, **parameters):
    """base_drive = acceleration driven by `acceleration(t)` for `steps` steps of h: the warnings."""
    said = []
    plate = PlateImpactFMU(fmu_path, initialize=False, logger=lambda s, c, m: said.append((s, m)))
    try:
        plate.initialize({"base_drive": 3, **parameters})
        for k in range(steps):
            plate.set("base_acceleration", acceleration(k * h))
            plate.step(h)
    finally:
        plate.free()
    return [m for s, m in said if s == 1]


def test_a_clamp_drifting_from_its_acceleration_is_said_with_its_size_and_the_missing_start_velocity(fmu_path):
    """The README's 10 Hz, 0.09 m sine given as its acceleration with the obstacles off: the clamp starts at
    rest, so it drifts at the mean velocity -A w = -5.65 m/s (-1.13 m at 0.2 s), silently on ef797a9 (issue
    71). Said once, when the input has swung (its third sign change, t = 0.15 s): the drift, the time, the
    mean velocity against the velocity's swing 2 A w, and the start velocity it lacks (A w). The cosine's
    acceleration A w^2 cos(w t), whose velocity from rest A w sin(w t) has zero mean, stays silent."""
    A, w = 0.09, 2 * math.pi * 10.0
    said = run_integrated_clamp(
        fmu_path,
        lambda t: -A * w * w * math.sin(w * t),
        200,
        obstacle_lower_enabled=False,
        obstacle_upper_enabled=False,
    )
    drift = [m for m in said if "base_acceleration has moved the clamp by" in m]
    assert len(drift) == 1, said
    moved, t = re.search(r"moved the clamp by (\S+) m from its start by t = (\S+) s", drift[0]).groups()
    assert 0.15 <= float(t) <= 0.16, drift
    # from rest, z(t) = A sin(w t) - A w t: the clamp's position then (the integral of the input as the FMU
    # reconstructs it between the samples of h = 1e-3 s, w h = 0.063: within 1 %)
    assert float(moved) == pytest.approx(A * math.sin(w * float(t)) - A * w * float(t), rel=1e-2), drift
    mean, swing = re.search(r"mean velocity of (\S+) m/s, \S+ of the (\S+) m/s", drift[0]).groups()
    assert float(swing) == pytest.approx(2 * A * w, rel=1e-2), drift
    assert f"lacks a start velocity of about {-float(mean):.3g} m/s" in drift[0], drift
    assert -float(mean) == pytest.approx(A * w, rel=0.1), drift  # A w, up to the sin(w t)/t part at 1.5 periods
    assert "Drive base_velocity" in drift[0], drift
    quiet = run_integrated_clamp(fmu_path, lambda t: 0.04 * w * w * math.cos(w * t), 300)
    assert quiet == [], quiet


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


def refusal(fmu_path, base0=0.0, **parameters):
    """The log of an initialization (the clamp starting at base0) the FMU refuses (it must refuse it)."""
    messages = []
    plate = PlateImpactFMU(fmu_path, initialize=False, logger=lambda s, c, m: messages.append(m))
    try:
        with pytest.raises(Exception, match="fmi2ExitInitializationMode failed"):
            plate.initialize({**SMALL, **parameters}, base0=base0)
    finally:
        plate.free()
    return " ".join(messages)


def test_refusals_of_the_material_name_si_units_and_the_range(fmu_path):
    """A density or a modulus out of range is refused with its SI unit and the conversion a user in g/cm3
    or GPa needs beside the allowed range (issue 71: the refusal named neither unit)."""
    text = refusal(fmu_path, density=-7.85)
    assert "invalid parameter density = -7.85" in text and "0.01 <= density <= 1e+06 (kg/m^3" in text, text
    assert "SI units; steel is 7850 kg/m^3" in text, text
    text = refusal(fmu_path, youngs_modulus=0.0)
    assert "invalid parameter youngs_modulus = 0" in text and "1 <= youngs_modulus <= 1e+14" in text, text
    assert "(Pa: the FMU takes SI units; steel is 2.1e11 Pa" in text, text
    text = refusal(fmu_path, thickness=0.0)
    assert "(m: the FMU takes SI units" in text, text


def test_modes_beyond_the_model_are_said_to_run_the_full_model(fmu_path):
    """modes above the plate's free dofs (newmark) or its massive modes (a singular mass under conserving)
    kept every mode there is, the full model and its cost, without a word (issue 71): said once at
    initialization, with the dofs where the engine states them; the run is the full model's (the same bits
    as modes = 0). modes below stays silent."""
    corners = {}
    for modes in (0, 10_000):
        with PlateRun(fmu_path, **SMALL, initial_load=1000.0, modes=modes) as run:
            corners[modes] = [run.step(1e-3)["corner_1"] for _ in range(5)]
            said = [m for m in warnings(run) if "modes = " in m]
        if modes:
            assert len(said) == 1 and "more than the plate's" in said[0] and "free dofs" in said[0], warnings(run)
            dofs = int(said[0].split("more than the plate's ")[1].split(" ")[0])
            assert 0 < dofs < modes and "the full model of modes = 0" in said[0], said
        else:
            assert said == [], said
    assert corners[0] == corners[10_000]
    with PlateRun(fmu_path, **SMALL, modes=10) as run:
        assert warnings(run) == []
    with PlateRun(fmu_path, **SMALL, mass=2, time_scheme=2, modes=10_000) as run:
        said = [m for m in warnings(run) if "modes = 10000" in m]
        assert len(said) == 1 and "massive modes" in said[0], warnings(run)
    with PlateRun(fmu_path, **SMALL, mass=2, time_scheme=2, modes=4) as run:
        assert warnings(run) == []


def test_the_condensed_laws_refuse_restitution_and_beta_alike_naming_the_scheme(fmu_path):
    """Under time_scheme = conserving or flow, restitution was refused naming "conserving" (also under flow)
    while beta, which those laws have no use for, was ignored silently (issue 71): both are refused, naming
    the scheme set, the reason and how to go on."""
    for scheme, name in ((2, "conserving"), (3, "flow")):
        other = "flow" if name == "conserving" else "conserving"
        text = refusal(fmu_path, mass=2, time_scheme=scheme, restitution=0.5)
        assert "invalid parameter restitution = 0.5" in text and f"time_scheme = {name}" in text, text
        assert f"time_scheme = {other}" not in text and "time_scheme = newmark (1)" in text, text
        text = refusal(fmu_path, mass=2, time_scheme=scheme, beta=0.25)
        assert "invalid parameter beta = 0.25" in text and f"time_scheme = {name}" in text, text
        assert "midpoint rule" in text and "leave beta at 0.5" in text, text
    with PlateRun(fmu_path, **SMALL, mass=2, time_scheme=3, beta=0.5) as run:  # the default, said or not
        assert warnings(run) == []


def test_a_state_taken_with_other_parameters_is_said_to_replace_the_instances(fmu_path):
    """An FMU state carries its parameters: set into an instance built with others, it replaced them without
    a word (issue 71; the instance then ran on as the state's plate). Said, naming what changed and from what;
    a state of the same parameters, set back into its own instance, stays silent."""
    with PlateRun(fmu_path, **SMALL) as donor:
        donor.step(1e-3)
        blob = donor.fmu.serializeFMUstate(donor.fmu.getFMUstate())
        with PlateRun(fmu_path, **SMALL, initial_load=1000.0, poisson_ratio=0.25) as run:
            run.step(1e-3)
            own = run.fmu.getFMUstate()
            run.step(1e-3)
            run.fmu.setFMUstate(own)
            assert warnings(run) == []  # its own parameters: nothing to say
            run.fmu.setFMUstate(run.fmu.deSerializeFMUstate(blob))
            said = [m for m in warnings(run) if "FMU state" in m]
            assert len(said) == 1, warnings(run)
            assert "initial_load = 0 (was 1000)" in said[0] and "poisson_ratio = 0.3 (was 0.25)" in said[0], said
            assert "runs on with the state's parameters" in said[0], said
            assert run.fmu.getReal([run.vars["initial_load"].valueReference])[0] == 0.0  # the state's, as said


def test_a_plate_started_past_a_tip_stop_is_refused_naming_the_plate_not_the_clamp(fmu_path):
    """examples/stop_under_tip.py's stop (x >= 1 m at -0.05 m) with the clamp starting at -0.06 m: the flat
    plate starts under the stop, the clamp is not under it; the refusal blamed "the clamped edge" (issue 71).
    It names the plate under the stop; a whole-plate obstacle's refusal says its stop covers the clamp."""
    tip = dict(obstacle_lower=-0.05, obstacle_lower_x_min=1.0, obstacle_upper_enabled=False)
    text = refusal(fmu_path, base0=-0.06, **tip)
    assert "base_displacement = -0.06 starts the plate flat at that height, below obstacle_lower = -0.05" in text
    assert "does not reach the clamped edge: the plate there, not the clamp, is outside" in text, text
    text = refusal(fmu_path, base0=-0.06, obstacle_lower=-0.05)
    assert "below obstacle_lower = -0.05 (its stop covers the clamped edge)" in text, text


def test_the_correct_scenes_stay_silent(fmu_path):
    """No warning on a correct scene (issue 71's goal, with this pass's warnings: SI units, modes beyond the
    model, the integrated clamp's drift, a replaced state's parameters, the input's miss): every LS-REF
    experiment as its references run it (stimuli set at each communication point), each its first 0.05 s,
    and the README's accurate configuration of examples/error_against_the_plate.py. A state of its own
    parameters set back stays silent too."""
    from plateimpact import references

    scenes = [(e.name, e.parameters, e.stimuli, e.step) for e in references.EXPERIMENTS]
    accurate = {"nx": 28, "ny": 10, "modes": 40, "time_scheme": "flow", "mass": "singular_p0", "contact_substeps": 4}
    scenes.append(("error_against_the_plate accurate", accurate, scenes[0][2], 1e-3))
    for name, parameters, stimuli, h in scenes:
        said = []
        plate = PlateImpactFMU(fmu_path, initialize=False, logger=lambda s, c, m: said.append((s, m)))
        try:
            plate.initialize(dict(parameters))
            state = plate.fmu.getFMUstate()
            for k in range(round(0.05 / h)):
                for input_name, f in stimuli.items():
                    plate.set(input_name, float(f(np.array([k * h]))[0]))
                plate.step(h)
            plate.fmu.setFMUstate(state)
            plate.fmu.freeFMUstate(state)
        finally:
            plate.free()
        assert [m for s, m in said if s == 1] == [], name
