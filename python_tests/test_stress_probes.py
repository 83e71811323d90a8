"""Stress and probes (docs/theory.md §23) through fmpy: a probe at corner_1's point is corner_1 (value,
velocity, acceleration) and a probe on the clamped edge is the clamp, in every scheme, through
impacts; a probe outside the plate is refused naming the allowed range; root_stress_peak is the
running maximum of root_stress at every internal step, whether read or not, and survives FMU states;
the FMI 3.0 vertex_stress array agrees with the scalar stresses."""

import math

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave
from plate_fmu import PlateRun

from plateimpact import PlateImpactFMU
from plateimpact.driver import unzipped

EPS = np.finfo(float).eps
DT = 1e-5
# Close obstacles and a 2 mm base motion at 5 Hz: the corners hit within 60 ms.
# The recovery is on request (stress_outputs, probe_count): these tests ask for all of it.
CLOSE = {"obstacle_lower": -0.0021, "obstacle_upper": 0.0021, "stress_outputs": True, "probe_count": 4}
SCHEMES = {
    "newmark-argyris": {},
    "newmark-fvs": {"element": 2},
    "newmark-singular": {"mass": 2},
    "conserving": {"mass": 2, "time_scheme": 2},
    "flow": {"mass": 2, "time_scheme": 3},
}


def base(t, amplitude=0.002, f=5.0):
    w = 2 * math.pi * f
    return amplitude * math.sin(w * t), amplitude * w * math.cos(w * t), -amplitude * w * w * math.sin(w * t)


def record(run, steps, h=1e-3):
    """Communication steps of h from run.time with the base of base(); the outputs after each."""
    return [run.step(h, base=base(run.time)) for _ in range(steps)]


@pytest.mark.parametrize("scheme", SCHEMES)
def test_a_probe_at_a_corner_is_the_corner_and_one_on_the_clamp_is_the_clamp(fmu_path, scheme):
    points = {
        "probe_1_x": 1.2,
        "probe_1_y": 0.0,
        "probe_2_x": 1.2,
        "probe_2_y": 0.4,
        "probe_3_x": 0.0,
        "probe_3_y": 0.13,
    }
    with PlateRun(fmu_path, **CLOSE, **points, **SCHEMES[scheme]) as run:
        outs = record(run, 60)
    assert max(o["impacts_lower"] + o["impacts_upper"] for o in outs) > 0  # through impacts
    # The probe evaluates the same functional as the corner in another order of summation (a dense
    # row over up to n ≈ 800 coordinates): roundoff ≤ n·eps of the heights' scale. The velocity
    # divides 8 such errors by 2 dt, the acceleration 4 of them by dt².
    scale = max(abs(o[k]) for o in outs for k in ("corner_1", "corner_2", "clamp_displacement"))
    tol = 1e3 * EPS * scale
    for o in outs:
        for probe, corner in (("probe_1", "corner_1"), ("probe_2", "corner_2"), ("probe_3", "clamp")):
            ref = "clamp_displacement" if corner == "clamp" else corner
            assert abs(o[probe] - o[ref]) <= tol, (probe, o["time"], o[probe], o[ref])
            assert abs(o[f"{probe}_velocity"] - o[f"{corner}_velocity"]) <= 4 * tol / DT
            assert abs(o[f"{probe}_acceleration"] - o[f"{corner}_acceleration"]) <= 4 * tol / DT**2


@pytest.mark.parametrize(
    ("name", "value", "allowed"),
    [("probe_2_y", 0.5, "0 <= probe_2_y <= 0.4"), ("probe_4_x", 1.3, "0 <= probe_4_x <= 1.2")],
)
def test_a_probe_outside_the_plate_is_refused_with_the_allowed_range(fmu_path, name, value, allowed):
    messages = []
    with pytest.raises(FMICallException):
        PlateImpactFMU(fmu_path, logger=lambda s, c, m: messages.append(m), probe_count=4, **{name: value})
    text = " ".join(messages)
    assert f"invalid parameter {name} = {value}" in text and allowed in text, text


def test_the_root_peak_is_the_running_maximum_of_every_step_read_or_not(fmu_path):
    """Free vibration from a static pressure (no input moves: the same trajectory however it is
    read): read every internal step, the peak is the maximum of root_stress so far, t = 0 included;
    read every 10 ms, the peak is that same number, which no read value reaches."""
    scene = {"initial_load": -800.0, **CLOSE}
    with PlateRun(fmu_path, **scene) as fine:
        outs = [fine.outputs()] + [fine.step(DT) for _ in range(3000)]
    running = np.maximum.accumulate([o["root_stress"] for o in outs])
    assert [o["root_stress_peak"] for o in outs] == list(running)
    assert outs[0]["root_stress"] > 0  # the static shape is stressed at t = 0
    with PlateRun(fmu_path, **scene) as coarse:
        read = [coarse.step(1e-2) for _ in range(3)]
    assert read[-1]["root_stress_peak"] == running[-1]
    assert max(o["root_stress"] for o in read) < running[-1]


@pytest.mark.parametrize("h", [1e-3, 1.234e-3])  # on the grid, and between grid points (interpolated)
def test_the_stress_and_probes_continue_bit_identically_from_an_fmu_state(fmu_path, h):
    names = ("root_stress", "root_stress_peak", "max_stress", "max_stress_x", "probe_1", "probe_1_acceleration")
    with PlateRun(fmu_path, **CLOSE, probe_1_x=0.7, probe_1_y=0.1) as run:
        record(run, 10, h)
        state = run.fmu.getFMUstate()
        t = run.time
        first = record(run, 15, h)
        run.fmu.setFMUstate(state)
        run.time = t
        again = record(run, 15, h)
    for name in names:
        assert [o[name] for o in first] == [o[name] for o in again], name


def test_between_grid_points_a_probe_at_a_corner_is_still_the_corner(fmu_path):
    """Off the grid both are the same linear interpolation of their grid values (docs/theory.md §15)."""
    with PlateRun(fmu_path, **CLOSE, probe_1_x=1.2, probe_1_y=0.4) as run:
        outs = record(run, 40, 1.37e-3)
    scale = max(abs(o["corner_2"]) for o in outs)
    for o in outs:
        assert abs(o["probe_1"] - o["corner_2"]) <= 1e3 * EPS * scale
        assert o["max_stress"] >= o["root_stress"] and o["root_stress_peak"] >= o["root_stress"]


def test_fmi3_vertex_stress_agrees_with_the_scalar_stresses(fmu_path, tmp_path):
    fmu3 = fmu_path.parent / "fmi3" / "PlateImpact.fmu"
    unzipdir, md = unzipped(fmu3)  # extracted once per process, its library kept loaded
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s = FMU3Slave(
        guid=md.guid,
        unzipDirectory=unzipdir,
        modelIdentifier="PlateImpact",
        instanceName="t",
    )
    s.instantiate()
    s.enterInitializationMode(startTime=0.0)
    s.setFloat64([vr["initial_load"]], [-500.0])
    s.setBoolean([vr["stress_outputs"]], [True])
    s.exitInitializationMode()
    s.doStep(0.0, 2e-3)
    field = np.array(s.getFloat64([vr["vertex_stress"]], nValues=15 * 6)).reshape(15, 6)
    root, peak, largest = s.getFloat64([vr["root_stress"], vr["root_stress_peak"], vr["max_stress"]])
    x, y = s.getFloat64([vr["max_stress_x"], vr["max_stress_y"]])
    s.terminate()
    s.freeInstance()
    assert root <= peak and root <= largest
    assert field.max() <= largest * (1 + 1e-12)  # max_stress also sees the root's middles
    assert field[0].max() <= root * (1 + 1e-12)  # the clamped vertices are root samples
    if y in np.linspace(0.0, 0.4, 6) and x in np.linspace(0.0, 1.2, 15):  # the largest at a vertex
        assert field[round(x / 1.2 * 14), round(y / 0.4 * 5)] == pytest.approx(largest, rel=1e-12)


def test_what_is_not_asked_for_reads_zero_and_the_rest_is_unchanged(fmu_path):
    """Off by default (a master recording every output pays nothing): the stresses and the probes past
    probe_count read 0 (NaN is taken for a failed run by masters and checks), and asking for them
    changes no other output, bit for bit."""
    off_prefixes = ("root_stress", "max_stress", "probe_2", "probe_3", "probe_4")
    with PlateRun(fmu_path, **{**CLOSE, "stress_outputs": False, "probe_count": 1}, probe_1_x=0.9) as off:
        a = record(off, 30)
    with PlateRun(fmu_path, **CLOSE, probe_1_x=0.9) as on:
        b = record(on, 30)
    asked = [n for n in a[0] if n.startswith(off_prefixes)]
    assert len(asked) == 14  # root_stress(_peak), max_stress(_x, _y), probes 2-4 with their rates
    assert all(o[n] == 0.0 for o in a for n in asked)
    assert all(o[n] != 0.0 for o in b[1:] for n in asked if not n.endswith(("_x", "_y")))  # places may be 0
    shared = [n for n in a[0] if n not in asked]
    assert all(x[n] == y[n] for x, y in zip(a, b) for n in shared)


def test_a_probe_count_out_of_range_is_refused(fmu_path):
    messages = []
    with pytest.raises(FMICallException):
        PlateImpactFMU(fmu_path, logger=lambda s, c, m: messages.append(m), probe_count=5)
    assert "0 <= probe_count <= 4" in " ".join(messages), messages


def warnings_of(fmu_path, **parameters):
    """The warnings (status 1) an initialization with these parameters logs."""
    messages = []
    with PlateImpactFMU(fmu_path, logger=lambda s, c, m: messages.append((s, m)), **parameters):
        pass
    return [m for s, m in messages if s == 1]


def test_a_placed_probe_that_probe_count_leaves_off_is_warned_about(fmu_path):
    """Issue 46: a probe placed while probe_count leaves it off read 0 without a word."""
    said = warnings_of(fmu_path, probe_count=1, probe_1_x=0.6, probe_2_x=0.9, probe_2_y=0.2)
    assert len(said) == 1, said
    assert "probe_2 is placed at (0.9, 0.2) m but probe_count = 1 leaves it off" in said[0], said
    assert "probe_count >= 2" in said[0], said
    assert warnings_of(fmu_path, probe_count=2, probe_1_x=0.6, probe_2_x=0.9, probe_2_y=0.2) == []


def test_a_counted_probe_on_the_clamp_is_warned_about(fmu_path):
    """Issue 46: probe_count = 2 with probe 2 unplaced read the clamp's motion without a word."""
    said = warnings_of(fmu_path, probe_count=2, probe_1_x=0.6)
    assert len(said) == 1 and "probe_2 at (0, 0) m is counted (probe_count = 2)" in said[0], said
    assert "clamp's motion" in said[0] and "never set" in said[0], said


@pytest.mark.parametrize(
    "parameters, named",
    [
        ({"contact_substeps": 4}, "contact_substeps = 4"),
        ({"max_contact_substeps": 32}, "max_contact_substeps = 32"),
        ({"mass": 2, "time_scheme": 2, "contact_substeps": 4}, "contact_substeps = 4"),
    ],
)
def test_flow_settings_under_another_scheme_are_warned_about(fmu_path, parameters, named):
    """Issue 46: contact_substeps and max_contact_substeps under newmark (or conserving) were ignored
    without a word (a tolerance there was warned about already)."""
    said = warnings_of(fmu_path, **parameters)
    assert any(named in m and "time_scheme = flow" in m and "ignores it" in m for m in said), said
    flow = {k: v for k, v in parameters.items() if "substeps" in k}
    if "max_contact_substeps" in flow:  # the cap acts on a tolerance's sub-steps only (issue 56)
        flow["tolerance"] = 1e-5
    assert warnings_of(fmu_path, mass=2, time_scheme=3, **flow) == []
