"""The FMI 3.0 FMU (build/fmi3/PlateImpact.fmu) against the FMI 2.0 one (build/PlateImpact.fmu),
through fmpy: both model descriptions valid and declaring the same variables and defaults; the
same outputs bit for bit on the default scene without early return; with early return (and
event mode) the steps end exactly at the internal grid times at which a contact starts or
ends; the vertex displacements as an array sized by the structural parameters; bad calls
rejected with a logged fmi3Error."""

import os
import re
import zipfile
from pathlib import Path

import fmpy
import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

from plateimpact.driver import unzipped

DT = 1e-5  # the default internal step (fixedInternalStepSize)
# Free vibration between close obstacles: pressed onto the lower one at t = 0 (initial_load),
# released, it flies up to the upper one. No input moves, so the trajectory does not depend on
# where the communication points are: the contact events of any run are the same grid times.
FREE_FLIGHT = {"initial_load": -1500.0, "obstacle_lower": -0.01, "obstacle_upper": 0.01}
OUTPUTS = [
    "corner_1",
    "corner_2",
    "free_edge_mid",
    "energy",
    "energy_dissipated",
    "energy_input",
    "energy_damped",
    "contact_vertices",
    "qp_kkt_residual_max",
    "qp_iterations_total",
    "qp_iterations_max",
]


@pytest.fixture(scope="module")
def fmu2(fmu_path) -> Path:
    return Path(fmu_path)


@pytest.fixture(scope="module")
def fmu3(fmu_path) -> Path:
    """$PLATEIMPACT_FMU3, else fmi3/PlateImpact.fmu beside the FMI 2.0 FMU under test."""
    path = Path(os.environ.get("PLATEIMPACT_FMU3", Path(fmu_path).parent / "fmi3" / "PlateImpact.fmu"))
    assert path.is_file(), f"FMI 3.0 FMU not built: {path}"
    return path


def sine_input(stop, step):
    """The default scene's base 0.09 sin(2 pi 10 t) m as fmpy input samples."""
    t = np.arange(round(stop / step) + 1) * step
    signal = np.zeros(len(t), dtype=[("time", np.float64), ("base_displacement", np.float64)])
    signal["time"] = t
    signal["base_displacement"] = 0.09 * np.sin(2 * np.pi * 10.0 * t)
    return signal


def contact_changes(result):
    """Times at which contact_vertices goes from 0 to > 0 or back."""
    c = result["contact_vertices"] > 0
    return [float(result["time"][k]) for k in range(1, len(result)) if c[k] != c[k - 1]]


def on_grid(t):
    """t is exactly n * DT in double precision (the FMU's clock: step count times dt). The
    regular communication points are fmpy's (n + 1) * interval, which need not be."""
    return t == round(t / DT) * DT


def simulate(fmu, **kwargs):
    """fmpy.simulate_fmu on the FMU extracted once per process, its library kept loaded
    (plateimpact.driver.unzipped): the runs of one plate share its discretization, as a user's
    runs in one process do (the same bits: test_discretization_cache.py). On the .fmu file fmpy
    extracts and loads a fresh copy every call."""
    unzipdir, md = unzipped(fmu)
    return fmpy.simulate_fmu(unzipdir, model_description=md, **kwargs)


def test_both_fmus_validate(fmu2, fmu3):
    for path in (fmu2, fmu3, fmu2.parent / "SineSweep.fmu", fmu3.parent / "SineSweep.fmu"):
        assert validate_fmu(str(path)) == [], path


def test_fmi3_archive_layout(fmu3):
    names = set(zipfile.ZipFile(fmu3).namelist())
    assert "modelDescription.xml" in names
    assert "binaries/x86_64-linux/PlateImpact.so" in names
    assert not any(n.startswith("binaries/linux64") for n in names)


def test_same_variables_and_defaults(fmu2, fmu3):
    md2 = fmpy.read_model_description(str(fmu2))
    md3 = fmpy.read_model_description(str(fmu3))
    assert md3.fmiVersion == "3.0"
    assert md3.guid == md2.guid  # one source, one binding: the same GUID as instantiationToken
    types = {"Real": "Float64", "Integer": "Int32", "Boolean": "Boolean"}
    by_name3 = {v.name: v for v in md3.modelVariables}
    # FMI 2.0's scalar probes are FMI 3.0's arrays (issue 53): probe_count a structural parameter
    scalar_probes = {f"probe_{k}{s}" for k in range(1, 5) for s in ("_x", "_y", "", "_velocity", "_acceleration")}
    assert {v.name for v in md2.modelVariables} - set(by_name3) == scalar_probes
    for v2 in md2.modelVariables:
        if v2.name in scalar_probes | {"probe_count"}:
            continue
        v3 = by_name3[v2.name]
        assert (v3.valueReference, v3.causality, v3.type) == (v2.valueReference, v2.causality, types[v2.type])
        assert (v3.start, v3.unit, v3.declaredType is None) == (v2.start, v2.unit, v2.declaredType is None)
    extra = {v.name for v in md3.modelVariables} - {v.name for v in md2.modelVariables}
    assert extra == {"time", "vertex_output", "vertices_x", "vertices_y", "vertex_displacement", "vertex_stress"} | {
        "probe_x",
        "probe_y",
        "probe",
        "probe_velocity",
        "probe_acceleration",
    }
    assert (by_name3["probe_count"].causality, by_name3["probe_count"].type, by_name3["probe_count"].start) == (
        "structuralParameter",
        "UInt64",
        "1",
    )
    assert by_name3["probe"].shape == by_name3["probe_x"].shape == (1,)  # one probe to start with (size > 0)
    assert by_name3["time"].causality == "independent"
    assert (by_name3["vertices_x"].start, by_name3["vertices_y"].start) == ("15", "6")  # nx + 1, ny + 1
    assert by_name3["vertices_x"].causality == "structuralParameter"
    assert by_name3["vertex_displacement"].shape == (1, 15, 6)
    assert by_name3["vertex_stress"].shape == (1, 15, 6)
    assert (by_name3["vertex_output"].causality, by_name3["vertex_output"].start) == ("structuralParameter", "1")
    xml = zipfile.ZipFile(fmu3).read("modelDescription.xml").decode()
    assert re.search(r'name="vertex_output"[^>]* min="0" max="1"', xml)  # (fmpy reads no UInt64 range)
    cs = md3.coSimulation
    assert float(cs.fixedInternalStepSize) == DT == float(by_name3["dt"].start)
    assert cs.mightReturnEarlyFromDoStep and cs.hasEventMode and cs.canHandleVariableCommunicationStepSize
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate  # fmpy keeps the FMI 2.0 spelling
    assert md3.defaultExperiment.stopTime == md2.defaultExperiment.stopTime


def test_default_scene_bit_identical_to_fmi2(fmu2, fmu3):
    """0.1 s of the default scene (impacts from t = 0.05 s on), base values every 1e-4 s, no
    derivatives (FMI 3.0 has no input derivatives: both reconstruct the same way)."""
    names3 = {v.name for v in fmpy.read_model_description(str(fmu3)).modelVariables}
    outputs = [
        v.name
        for v in fmpy.read_model_description(str(fmu2)).modelVariables
        if v.causality == "output" and v.name in names3  # FMI 2.0's scalar probes are FMI 3.0's arrays
    ]
    kwargs = dict(stop_time=0.1, output_interval=1e-4, input=sine_input(0.1, 1e-4), output=outputs)
    r2 = simulate(fmu2, **kwargs)
    r3 = simulate(fmu3, **kwargs)
    assert len(r2) == len(r3) == 1001 and len(outputs) >= len(OUTPUTS)
    assert r3["contact_vertices"].max() > 0  # the scene has impacts
    assert np.array_equal(r2["time"], r3["time"])
    for name in outputs:  # every output of the FMI 2.0 FMU
        # bit for bit; the outputs not asked for (stress_outputs, probe_count) are NaN in both
        assert np.array_equal(r2[name], r3[name], equal_nan=True), name


def test_event_mode_without_early_return_steps_through(fmu3):
    kwargs = dict(stop_time=0.1, output_interval=1e-4, input=sine_input(0.1, 1e-4), output=OUTPUTS)
    plain = simulate(fmu3, **kwargs)
    events = simulate(fmu3, use_event_mode=True, **kwargs)
    for name in OUTPUTS:
        assert np.array_equal(plain[name], events[name]), name


def test_early_return_at_the_contact_events_on_the_internal_grid(fmu3):
    """The events of an early-return run at 1e-3 s are exactly those of a run that
    communicates at every internal step (the outputs there too)."""
    fine = simulate(fmu3, stop_time=0.2, output_interval=DT, start_values=FREE_FLIGHT, output=OUTPUTS)
    expected = contact_changes(fine)
    assert len(expected) >= 2  # the release from the lower obstacle, the hit on the upper one
    early = simulate(
        fmu3,
        stop_time=0.2,
        output_interval=1e-3,
        start_values=FREE_FLIGHT,
        output=OUTPUTS,
        early_return_allowed=True,
        use_event_mode=True,
    )
    # The same internal steps; an event at the last internal step of a communication step is
    # reported at fmpy's own regular time (75 * 1e-3, not 7500 * 1e-5: one ulp apart).
    assert [round(t / DT) for t in contact_changes(early)] == [round(t / DT) for t in expected]
    off_regular = [t for t in early["time"] if abs(t / 1e-3 - round(t / 1e-3)) > 1e-9]
    assert off_regular and set(off_regular) <= set(expected)  # every early return is an event
    assert all(on_grid(t) for t in off_regular)  # the FMU's clock: n dt exactly
    fine_at = {round(t / DT): k for k, t in enumerate(fine["time"])}
    for k, t in enumerate(early["time"]):
        for name in OUTPUTS:  # bit for bit at every point of the early-return run
            assert early[name][k] == fine[name][fine_at[round(t / DT)]], (t, name)


def test_default_scene_early_return_reports_the_impacts(fmu3):
    """The done-when of issue 22: results at the impact times of the default scene."""
    early = simulate(
        fmu3,
        stop_time=0.1,
        output_interval=1e-3,
        input=sine_input(0.1, 1e-3),
        output=["contact_vertices", "corner_1"],
        early_return_allowed=True,
    )
    impacts = contact_changes(early)
    assert impacts and 0.04 < impacts[0] < 0.1
    off_regular = [t for t in early["time"] if abs(t / 1e-3 - round(t / 1e-3)) > 1e-9]
    assert off_regular and set(off_regular) <= set(impacts)  # the steps ended at the impacts
    assert all(on_grid(t) for t in off_regular)


def slave(fmu3, **instantiate):
    """An instance of the FMU extracted once per process (its library kept loaded: simulate)."""
    unzipdir, md = unzipped(fmu3)
    s = FMU3Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier="PlateImpact", instanceName="t")
    messages = []
    s.instantiate(logMessage=lambda env, status, category, message: messages.append(message.decode()), **instantiate)
    return md, s, messages


def test_step_returns_early_with_event_mode(fmu3):
    md, s, messages = slave(fmu3, earlyReturnAllowed=True, eventModeUsed=True)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s.setFloat64([vr[k] for k in FREE_FLIGHT], list(FREE_FLIGHT.values()))
    s.enterInitializationMode(startTime=0.0)
    s.exitInitializationMode()
    s.updateDiscreteStates()
    s.enterStepMode()
    assert s.getInt32([vr["contact_vertices"]])[0] > 0  # pressed onto the lower obstacle
    event, terminate, early, t = s.doStep(0.0, 0.05)
    assert event and early and not terminate and 0 < t < 0.05 and on_grid(t)
    assert s.getInt32([vr["contact_vertices"]])[0] == 0  # released: the event is visible
    assert s.getFloat64([vr["time"]])[0] == t
    s.enterEventMode()
    assert s.updateDiscreteStates()[:2] == (False, False)  # nothing to iterate, no termination
    s.enterStepMode()
    event, _, early, t2 = s.doStep(t, 0.01)  # on from the event: the next one is the upper hit
    assert t < t2 <= t + 0.01 and on_grid(t2)
    s.terminate()
    with pytest.raises(FMICallException):
        s.doStep(t2, 0.01)  # terminated
    assert any("illegal call sequence" in m for m in messages)
    s.freeInstance()


def test_vertex_displacement_array(fmu3):
    md, s, messages = slave(fmu3)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s.setInt32([vr["nx"], vr["ny"]], [6, 2])
    assert s.getUInt64([vr["vertices_x"], vr["vertices_y"]]) == [7, 3]
    s.enterInitializationMode(startTime=0.0)
    s.exitInitializationMode()
    s.setFloat64([vr["base_displacement"]], [0.0])
    for k in range(20):
        s.doStep(k * 1e-3, 1e-3)
    w = np.array(s.getFloat64([vr["vertex_displacement"]], nValues=21)).reshape(1, 7, 3)[0]
    corners = s.getFloat64([vr["corner_1"], vr["corner_2"]])
    assert np.all(w[0] == 0.0)  # the clamped edge at x = 0, base at rest
    assert w[6, 0] == pytest.approx(corners[0], rel=1e-12, abs=1e-15)
    assert w[6, 2] == pytest.approx(corners[1], rel=1e-12, abs=1e-15)
    with pytest.raises(FMICallException):
        s.getFloat64([vr["vertex_displacement"]], nValues=90)  # the default mesh's size, not this one's
    # The message names the array and the number of values it needs.
    assert any("nValues = 90" in m and "vertex_displacement" in m and "needs 21 values" in m for m in messages), (
        messages
    )
    s.freeInstance()


def test_vertex_stress_read_while_off_is_said(fmu3):
    """Issue 56: vertex_stress reads 0 unless stress_outputs = true; the first read says so."""
    md, s, messages = slave(fmu3)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s.enterInitializationMode(startTime=0.0)
    s.exitInitializationMode()
    s.doStep(0.0, 1e-3)
    assert s.getFloat64([vr["vertex_stress"]], nValues=90) == [0.0] * 90
    s.getFloat64([vr["vertex_stress"]], nValues=90)
    said = [m for m in messages if "stress_outputs = false" in m]
    s.freeInstance()
    assert len(said) == 1 and "vertex_stress was read while stress_outputs = false" in said[0], messages


def test_vertex_output_switches_the_array_off(fmu3):
    """vertex_output = 0 (the array's first extent) empties vertex_displacement: it needs zero
    values and reads as none, beside the scalars; the run itself is the same bits as with the
    array on. Out of its range 0..1 it is refused with the range; after initialization (fixed)
    it cannot be set."""

    def run(switch):
        md, s, messages = slave(fmu3)
        vr = {v.name: v.valueReference for v in md.modelVariables}
        if switch is not None:
            s.setUInt64([vr["vertex_output"]], [switch])
        s.enterInitializationMode(startTime=0.0)
        s.exitInitializationMode()
        for k in range(30):
            s.setFloat64([vr["base_displacement"]], [0.09 * np.sin(2 * np.pi * 10 * k * 1e-3)])
            s.doStep(k * 1e-3, 1e-3)
        return md, s, vr, messages

    md, s, vr, _ = run(0)
    assert s.getUInt64([vr["vertex_output"], vr["vertices_x"]]) == [0, 15]  # the mesh is still there
    off = s.getFloat64([vr["corner_1"], vr["vertex_displacement"], vr["energy"]], nValues=2)
    assert len(off) == 2
    with pytest.raises(FMICallException):
        s.setUInt64([vr["vertex_output"]], [1])  # fixed: not after initialization
    s.freeInstance()
    md, s, vr, _ = run(None)
    on = s.getFloat64([vr["corner_1"], vr["vertex_displacement"], vr["energy"]], nValues=92)
    assert [on[0], on[-1]] == off and max(abs(x) for x in on[1:-1]) > 0.0
    s.freeInstance()
    md, s, messages = slave(fmu3)
    with pytest.raises(FMICallException):
        s.setUInt64([vr["vertex_output"]], [2])
    assert any("vertex_output = 2 rejected: allowed 0 to 1" in m for m in messages), messages
    s.freeInstance()


@pytest.mark.parametrize(
    "call, expected",
    [
        (lambda s, vr: s.getInt64([vr["element"]]), "is the Int32 variable element"),
        (lambda s, vr: s.setUInt64([vr["vertices_x"]], [2**40]), "out of the Int32 range"),
        (lambda s, vr: s.setFloat64([vr["time"]], [1.0]), "cannot be set"),
        (lambda s, vr: s.getFloat32([vr["length"]]), "no Float32 variables"),
        (lambda s, vr: s.enterEventMode(), "illegal call sequence"),
    ],
)
def test_bad_calls_are_logged_errors(fmu3, call, expected):
    md, s, messages = slave(fmu3)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    if "element" in expected:
        s.enterInitializationMode(startTime=0.0)
    with pytest.raises(FMICallException):
        call(s, vr)
    assert any(expected in m for m in messages), messages
    s.freeInstance()


def test_sinesweep_fmi3_matches_fmi2(fmu2):
    sweep2, sweep3 = fmu2.parent / "SineSweep.fmu", fmu2.parent / "fmi3" / "SineSweep.fmu"
    r2 = fmpy.simulate_fmu(str(sweep2), stop_time=0.05, output_interval=1e-4)
    r3 = fmpy.simulate_fmu(str(sweep3), stop_time=0.05, output_interval=1e-4)
    for name in ("base_displacement", "frequency"):
        assert np.array_equal(r2[name], r3[name])
    assert np.array_equal(r2["time"], r3["time"]) and np.ptp(r3["base_displacement"]) > 0


def test_animate_example_quick(fmu3, tmp_path):
    """examples/animate.py: a GIF and a still at the first contact onset (an early return)."""
    import runpy
    import sys
    from unittest import mock

    argv = ["animate.py", "--fmu", str(fmu3), "--out", str(tmp_path)]
    argv += ["--start", "0.045", "--stop", "0.06", "--interval", "5e-3"]
    script = Path(__file__).resolve().parent.parent / "examples" / "animate.py"
    with mock.patch.object(sys, "argv", argv):
        runpy.run_path(str(script), run_name="__main__")
    from PIL import Image

    gif = Image.open(tmp_path / "plate_impact.gif")
    assert gif.n_frames > 4  # the regular frames and the contact events between them
    assert (tmp_path / "plate_impact.png").stat().st_size > 10_000


def fmi3_texts(fmu3):
    with zipfile.ZipFile(fmu3) as z:
        return z.read("modelDescription.xml").decode(), z.read("documentation/index.html").decode(), z.namelist()


def test_fmi3_logs_its_own_function_names_under_declared_categories(fmu3):
    """The FMI 3.0 FMU speaks FMI 3.0: the trace names fmi3 functions (none of FMI 2.0's), and
    every category it logs under is declared in its model description."""
    unzipdir, md = unzipped(fmu3)
    s = FMU3Slave(guid=md.guid, unzipDirectory=unzipdir, modelIdentifier="PlateImpact", instanceName="t")
    logged = []
    s.instantiate(loggingOn=True, logMessage=lambda env, st, cat, msg: logged.append((cat.decode(), msg.decode())))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s.enterInitializationMode(tolerance=1e-6, startTime=0.0, stopTime=0.01)
    s.exitInitializationMode()
    s.doStep(0.0, 1e-3)
    with pytest.raises(FMICallException):
        s.setInt32([vr["element"]], [2])  # a fixed parameter after initialization: an error
    s.freeInstance()
    messages = [m for _, m in logged]
    for name in (
        "fmi3InstantiateCoSimulation",
        "fmi3EnterInitializationMode",
        "fmi3ExitInitializationMode",
        "fmi3FreeInstance",
    ):
        assert any(m.startswith(name) for m in messages), (name, messages)
    assert any("before fmi3ExitInitializationMode" in m for m in messages), messages
    assert not [m for m in messages if "fmi2" in m], [m for m in messages if "fmi2" in m]
    declared = {c.name for c in md.logCategories}
    assert {c for c, _ in logged} <= declared, ({c for c, _ in logged}, declared)
    assert "logInfo" in {c for c, _ in logged}  # the cost estimate of every initialization


def test_fmi3_description_and_page_are_its_own(fmu3):
    """No FMI 2.0 function in the FMI 3.0 texts, no citation of repository files the FMU does not
    contain, no binary or licence it does not ship; its own page, with the FMI 3.0 variables."""
    xml, html, names = fmi3_texts(fmu3)
    for text in (xml, html):
        assert "fmi2" not in text
        assert "docs/" not in text and ".md" not in text
    assert "win64" not in html and "windows" not in html.lower() or any("windows" in n for n in names)
    assert "FMI 3.0 Co-Simulation" in html and "vertex_displacement" in html and "structuralParameter" in html
    for listed in ("licenses/" + n.split("/")[-1] for n in names if n.startswith("documentation/licenses/")):
        assert listed in html, listed


@pytest.mark.parametrize(
    "switch, items",
    [
        ("element", "(1 = argyris, 2 = fvs)"),
        ("base_drive", "(1 = displacement, 2 = velocity, 3 = acceleration, 4 = force, 5 = tlm)"),
        ("time_scheme", "(1 = newmark, 2 = conserving, 3 = flow)"),
    ],
)
def test_switches_are_int32_with_their_items(fmu3, switch, items):
    md = fmpy.read_model_description(str(fmu3))
    v = {v.name: v for v in md.modelVariables}[switch]
    assert (v.type, v.min, v.declaredType) == ("Int32", "1", None)
    assert v.description.endswith(items)
    assert v.max == str(items.count(" = "))  # max is the last item: no value without a name


@pytest.mark.parametrize("version", ["2.0", "3.0"])
def test_metadata_and_licence_texts(fmu2, fmu3, version):
    """author, license, copyright, version and generationDateAndTime in both descriptions; every
    licence the license attribute names has its text in documentation/licenses/."""
    path = fmu2 if version == "2.0" else fmu3
    md = fmpy.read_model_description(str(path))
    assert md.fmiVersion == version
    for attribute in ("author", "license", "copyright", "version", "generationDateAndTime"):
        assert getattr(md, attribute), attribute
    with zipfile.ZipFile(path) as z:
        texts = {Path(n).stem for n in z.namelist() if n.startswith("documentation/licenses/") and n.endswith(".txt")}
    named = set(re.findall(r"([\w-]+) \(", md.license))
    assert {"CHOLMOD-Core-Cholesky", "AMD", "COLAMD", "Eigen", "xxHash", "GCC-runtime"} <= named
    assert named | {"PlateImpact"} == texts, (named, texts)
