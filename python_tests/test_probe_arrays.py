"""Issue 53: the FMI 3.0 FMU's probes as arrays the user sizes (docs/fmi3.md). probe_count is a
UInt64 structural parameter set in Configuration Mode (refused elsewhere, naming where), probe_x
and probe_y Float64 parameter arrays and probe, probe_velocity, probe_acceleration output arrays
of probe_count values. A probe at a corner's point reads the corner to roundoff, through impacts;
FMU states carry the count. Through fmpy's FMU3Slave with the Configuration Mode calls, and the
path a user of fmpy.simulate_fmu takes (one probe, placed by start values)."""

import sys

import fmpy
import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave

from plateimpact.driver import unzipped

EPS = sys.float_info.epsilon
DT = 1e-5  # the default internal step
H = 1e-3  # communication step
# Close obstacles and a 2 mm base motion at 5 Hz (as test_stress_probes.py): the corners hit
# within 60 ms, so the probes are compared through impacts.
CLOSE = {"obstacle_lower": -0.0021, "obstacle_upper": 0.0021}
# Three probes: corner_1's point, one inside, corner_2's point.
PLACES_X, PLACES_Y = [1.2, 0.6, 1.2], [0.0, 0.2, 0.4]


def slave(fmu3, tmp_path):
    """An instance of the FMU extracted once per process, its library kept loaded
    (plateimpact.driver.unzipped): the instances of one plate share its discretization."""
    unzipdir, md = unzipped(fmu3)
    s = FMU3Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier="PlateImpact", instanceName="probes")
    messages = []
    s.instantiate(logMessage=lambda env, status, category, message: messages.append(message.decode()))
    return {v.name: v.valueReference for v in md.modelVariables}, s, messages


def configured(fmu3, tmp_path, count, places=(PLACES_X, PLACES_Y)):
    """An instance with `count` probes (Configuration Mode) at `places`, initialized on CLOSE."""
    vr, s, messages = slave(fmu3, tmp_path)
    s.enterConfigurationMode()
    s.setUInt64([vr["probe_count"]], [count])
    s.exitConfigurationMode()
    s.setFloat64([vr["probe_x"], vr["probe_y"]], list(places[0]) + list(places[1]))
    s.setFloat64([vr[k] for k in CLOSE], list(CLOSE.values()))
    s.enterInitializationMode(startTime=0.0)
    s.exitInitializationMode()
    return vr, s, messages


def step(s, vr, t):
    """One communication step from t with the base 0.002 sin(2 pi 5 t) m set at t."""
    s.setFloat64([vr["base_displacement"]], [0.002 * np.sin(2 * np.pi * 5.0 * t)])
    s.doStep(t, H)


def test_probe_count_sizes_the_arrays_and_a_probe_at_a_corner_reads_the_corner(fmu3, tmp_path):
    vr, s, messages = configured(fmu3, tmp_path, 3)
    assert s.getUInt64([vr["probe_count"]]) == [3]
    assert s.getFloat64([vr["probe_x"], vr["probe_y"]], nValues=6) == PLACES_X + PLACES_Y
    rows, impacts = [], 0
    for k in range(60):
        step(s, vr, k * H)
        w = s.getFloat64([vr["probe"]], nValues=3)
        v = s.getFloat64([vr["probe_velocity"]], nValues=3)
        a = s.getFloat64([vr["probe_acceleration"]], nValues=3)
        c = s.getFloat64([vr[n] for n in ("corner_1", "corner_2", "corner_1_velocity", "corner_2_velocity")])
        ca = s.getFloat64([vr["corner_1_acceleration"], vr["corner_2_acceleration"]])
        impacts = max(impacts, sum(s.getInt32([vr["impacts_lower"], vr["impacts_upper"]])))
        rows.append((w, v, a, c, ca))
    assert impacts > 0  # through impacts
    # The probe evaluates the same functional as the corner in another order of summation:
    # roundoff of n eps of the heights' scale (test_stress_probes.py); the velocity divides 8 such
    # errors by 2 dt, the acceleration 4 by dt^2.
    scale = max(abs(x) for _, _, _, c, _ in rows for x in c[:2])
    tol = 1e3 * EPS * scale
    for w, v, a, c, ca in rows:
        for probe, corner in ((0, 0), (2, 1)):
            assert abs(w[probe] - c[corner]) <= tol
            assert abs(v[probe] - c[2 + corner]) <= 4 * tol / DT
            assert abs(a[probe] - ca[corner]) <= 4 * tol / DT**2
    # the probe inside moves, between the clamp and the corners
    assert 0 < max(abs(w[1]) for w, *_ in rows) < max(abs(x) for _, _, _, c, _ in rows for x in c[:2])
    with pytest.raises(FMICallException):
        s.getFloat64([vr["probe"]], nValues=1)  # three values now, not the start's one
    assert any("probe" in m and "needs 3 values" in m for m in messages), messages
    s.freeInstance()


@pytest.mark.parametrize("where", ["instantiated", "initialization mode", "step mode"])
def test_probe_count_outside_configuration_mode_is_refused_naming_it(fmu3, tmp_path, where):
    vr, s, messages = slave(fmu3, tmp_path)
    if where != "instantiated":
        s.enterInitializationMode(startTime=0.0)
    if where == "step mode":
        s.exitInitializationMode()
    with pytest.raises(FMICallException):
        s.setUInt64([vr["probe_count"]], [3])
    assert any("probe_count is a structural parameter: set it in Configuration Mode" in m for m in messages), messages
    s.freeInstance()


def test_probe_count_out_of_range_and_a_probe_outside_the_plate_are_refused(fmu3, tmp_path):
    vr, s, messages = slave(fmu3, tmp_path)
    s.enterConfigurationMode()
    with pytest.raises(FMICallException):
        s.setUInt64([vr["probe_count"]], [1025])
    assert any("probe_count = 1025 rejected: allowed 0 to 1024" in m for m in messages), messages
    s.freeInstance()
    vr, s, messages = slave(fmu3, tmp_path / "size")
    s.enterConfigurationMode()
    s.setUInt64([vr["probe_count"]], [2])
    s.exitConfigurationMode()
    with pytest.raises(FMICallException):
        s.setFloat64([vr["probe_x"]], [0.5])  # two values now
    assert any("nValues = 1 is too small" in m and "probe_x" in m and "takes 2 values" in m for m in messages)
    s.freeInstance()
    vr, s, messages = slave(fmu3, tmp_path / "outside")
    s.enterConfigurationMode()
    s.setUInt64([vr["probe_count"]], [2])
    s.exitConfigurationMode()
    s.setFloat64([vr["probe_x"], vr["probe_y"]], [0.5, 1.3, 0.1, 0.1])
    s.enterInitializationMode(startTime=0.0)
    with pytest.raises(FMICallException):
        s.exitInitializationMode()
    assert any("probe_2_x = 1.3" in m and "0 <= probe_2_x <= 1.2" in m and "probe_x[1]" in m for m in messages), (
        messages
    )
    s.freeInstance()


def test_zero_probes_leave_the_arrays_empty(fmu3, tmp_path):
    vr, s, _ = configured(fmu3, tmp_path, 0, ([], []))
    for k in range(5):
        step(s, vr, k * H)
    values = s.getFloat64([vr["corner_1"], vr["probe"], vr["probe_velocity"], vr["energy"]], nValues=2)
    assert values == s.getFloat64([vr["corner_1"], vr["energy"]]) and values[0] != 0.0
    s.freeInstance()


def test_fmu_states_carry_the_probe_count(fmu3, tmp_path):
    """A state of a three-probe run, serialized and set in a new instance (one probe by default),
    brings the count and the places with it; both continue the same bits."""
    vr, a, _ = configured(fmu3, tmp_path / "a", 3)
    for k in range(55):
        step(a, vr, k * H)
    state = a.serializeFMUState(a.getFMUState())
    _, b, _ = slave(fmu3, tmp_path / "b")
    assert b.getUInt64([vr["probe_count"]]) == [1]
    b.setFMUState(b.deserializeFMUState(state))
    assert b.getUInt64([vr["probe_count"]]) == [3]
    assert b.getFloat64([vr["probe_x"], vr["probe_y"]], nValues=6) == PLACES_X + PLACES_Y
    for s in (a, b):
        step(s, vr, 55 * H)
    names = ("probe", "probe_velocity", "probe_acceleration")
    assert [a.getFloat64([vr[n]], nValues=3) for n in names] == [b.getFloat64([vr[n]], nValues=3) for n in names]
    a.freeInstance()
    b.freeInstance()


def test_simulate_fmu_places_the_one_default_probe(fmu3):
    """fmpy.simulate_fmu sets structural parameters outside Configuration Mode (refused, with the
    reason) and sizes the arrays by their start values: its user places the one probe the FMU
    starts with (docs/fmi3.md)."""
    t = np.arange(601) * 1e-4
    base = np.array(
        list(zip(t, 0.002 * np.sin(2 * np.pi * 5 * t))), dtype=[("time", float), ("base_displacement", float)]
    )
    kwargs = dict(stop_time=0.06, output_interval=1e-4, input=base, output=["corner_1", "probe"])
    unzipdir, md = unzipped(fmu3)  # extracted once per process, its library kept loaded
    kwargs["model_description"] = md
    r = fmpy.simulate_fmu(unzipdir, start_values={**CLOSE, "probe_x": [1.2], "probe_y": [0.0]}, **kwargs)
    assert r["probe"].shape == (601, 1)
    tol = 1e3 * EPS * np.abs(r["corner_1"]).max()
    assert np.abs(r["probe"][:, 0] - r["corner_1"]).max() <= tol
    with pytest.raises(Exception):
        fmpy.simulate_fmu(unzipdir, start_values={"probe_count": 3}, **kwargs)
