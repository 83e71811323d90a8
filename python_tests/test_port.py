"""The plate as a mechanical port (docs/theory.md §14–16), through fmpy as users drive it:
the clamp's force and moment, the contact sums, the clamp's motion inputs and communication
steps that are no multiple of dt."""

from __future__ import annotations

import math

import numpy as np
import pytest
from fmpy import simulate_fmu

from plateimpact import PlateImpactFMU, default_base
from plateimpact.scenes import AMPLITUDE, FREQUENCY

# The sanitizer stage of test.sh runs this file against the ASan+UBSan build (pytest.ini).
pytestmark = pytest.mark.sanitizer
# What a test left out of the sanitizer stage names (repeats_paths, conftest.py): every engine's
# stepping and state code under ASan, one configuration each.
STATE = "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical"

DT = 1e-5


@pytest.mark.parametrize(
    "element, nx, ny, mass",
    [
        ("argyris", 14, 5, "consistent"),
        ("argyris", 3, 2, "consistent"),
        ("fvs", 20, 7, "consistent"),
        ("argyris", 14, 5, "singular_p0"),
        ("fvs", 5, 3, "singular_p0"),
    ],
)
def test_static_pressure_gives_the_clamp_force_and_moment_of_statics(fmu_path, element, nx, ny, mass):
    # At rest under a uniform pressure p, the clamp carries p·L·W and p·L·W·L/2 exactly: the
    # load vector integrates the polynomials 1 and x the space holds (any element, any mesh).
    p, length, width = 300.0, 1.2, 0.4
    with PlateImpactFMU(fmu_path, element=element, nx=nx, ny=ny, mass=mass, initial_load=p, load0=p) as plate:
        for _ in range(5):
            out = plate.step(10 * DT, load=p)
    force, moment = p * length * width, p * length * width * length / 2
    assert out["contact_vertices"] == 0  # 300 Pa bends the tip ~ mm: no obstacle touched
    # Roundoff: the force is a second difference of momenta over dt²; a static state's w has
    # roundoff eps·|w| ~ 2e-19 m, times the plate's mass (37 kg) over dt² (1e-10 s²): ~1e-7 N.
    assert abs(out["clamp_force"] - force) <= 1e-9 * force + 1e-6
    assert abs(out["clamp_moment"] - moment) <= 1e-9 * moment + 1e-6


def run_every_step(fmu_path, steps, **parameters):
    """The default base (0.09 sin 2π·10 t) with a communication step of one dt: every internal
    step's outputs."""
    rows = []
    with PlateImpactFMU(fmu_path, **parameters) as plate:
        rows.append(plate.outputs())
        for k in range(steps):
            rows.append(plate.step(DT, base=default_base(k * DT)))
    return rows


LAWS = {
    "paper": {},
    "singular_p0": {"mass": "singular_p0"},
    "restitution": {"restitution": 0.5},
    "damping": {"damping_mass": 5.0, "damping_stiffness": 1e-5},
}


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.repeats_paths(
    "test_conserving.py::test_work_of_the_clamp_force_is_the_energy_input_through_impacts[0]",  # the port sums
    f"{STATE}[singular_laws]",  # the laws
    f"{STATE}[modal_restitution_damping]",
)
def test_work_of_the_clamp_force_is_the_energy_input_through_impacts(fmu_path, law):
    # Σ_n F_n (z_{n+1} − z_{n−1})/2 over the steps, F_n the force the clamp exerts on the plate
    # (−clamp_force, centred at t_n), is the ledger's energy_input (load 0) identically (§14).
    rows = run_every_step(fmu_path, 7000, **LAWS[law])
    z = np.array([r["clamp_displacement"] for r in rows])
    z_before = np.concatenate(([z[0]], z[:-2]))  # z_{n−1}, the plate at rest before t = 0
    force_on_plate = -np.array([r["clamp_force"] for r in rows[1:]])
    work = np.cumsum(force_on_plate * (z[1:] - z_before) / 2)
    energy_input = np.array([r["energy_input"] for r in rows[1:]])
    assert rows[-1]["impacts_lower"] + rows[-1]["impacts_upper"] > 0, "the window must contain impacts"
    # Roundoff: F_n is a second difference of momenta (~10 kg·m/s) over dt², relative ~1e-11
    # per step; 7000 steps and a margin of 10 give the bound below.
    scale = np.max(np.abs(energy_input))
    assert np.max(np.abs(work - energy_input)) <= 1e-8 * scale


@pytest.mark.repeats_paths(
    "test_port.py::test_port_outputs_at_t0_describe_the_initial_state[scene0-law0]", f"{STATE}[argyris]"
)
def test_contact_sums_are_consistent(fmu_path):
    rows = run_every_step(fmu_path, 7000)
    lower = np.array([r["contact_force_lower"] for r in rows])
    upper = np.array([r["contact_force_upper"] for r in rows])
    # Up to 0.07 s the base's first rise throws the plate onto the upper obstacle only.
    assert lower.min() >= 0 and upper.max() <= 0 and upper.min() < 0
    # The impulse is the force summed over the steps; onsets are the steps where a force starts.
    assert rows[-1]["contact_impulse_lower"] == pytest.approx(lower.sum() * DT, rel=1e-12)
    assert rows[-1]["contact_impulse_upper"] == pytest.approx(upper.sum() * DT, rel=1e-12)
    onsets = int(np.sum((upper[1:] < 0) & (upper[:-1] == 0)))
    assert rows[-1]["contact_onsets_upper"] == onsets > 0


def test_probe_velocity_and_acceleration_are_the_differences_of_the_displacements(fmu_path):
    rows = run_every_step(fmu_path, 3000)
    u = np.array([r["corner_1"] for r in rows])
    k = np.arange(2, len(rows))
    assert np.allclose(
        [rows[i]["corner_1_velocity"] for i in k], (3 * u[k] - 4 * u[k - 1] + u[k - 2]) / (2 * DT), rtol=1e-9, atol=1e-9
    )
    assert np.allclose(
        [rows[i]["corner_1_acceleration"] for i in k], (u[k] - 2 * u[k - 1] + u[k - 2]) / DT**2, rtol=1e-6, atol=1e-3
    )
    # The clamp's acceleration is the base's at t − dt (the scheme's level), to O(dt²).
    t = 0.02 - DT
    assert abs(rows[2000]["clamp_acceleration"] - default_base(t)[2]) < 1e-3


@pytest.mark.parametrize("drive", ["velocity", "acceleration"])
def test_velocity_and_acceleration_drives_give_the_displacement_drive(fmu_path, drive):
    # z = a t²: exact in each drive's polynomial, so the clamp paths agree to roundoff.
    a = 2.0
    runs = {}
    for mode in ("displacement", drive):
        with PlateImpactFMU(fmu_path, base_drive=mode) as plate:
            for k in range(300):
                t = k * 1e-4
                if mode == "displacement":
                    plate.step(1e-4, base=(a * t * t, 2 * a * t, 2 * a))
                elif mode == "velocity":
                    plate.set("base_velocity", 2 * a * t)
                    plate.fmu.setRealInputDerivatives([plate.vars["base_velocity"].valueReference], [1], [2 * a])
                    plate.step(1e-4)
                else:
                    plate.set("base_acceleration", 2 * a)
                    plate.step(1e-4)
            runs[mode] = plate.outputs()
    assert runs[drive]["clamp_displacement"] == pytest.approx(a * 0.03**2, rel=1e-12)
    for name in ("corner_1", "energy", "energy_input"):
        assert runs[drive][name] == pytest.approx(runs["displacement"][name], rel=1e-9, abs=1e-12)
    # A force is a second difference over dt²: roundoff ~1e-7 N (see the static test).
    assert runs[drive]["clamp_force"] == pytest.approx(runs["displacement"]["clamp_force"], rel=1e-9, abs=1e-6)


def test_a_step_of_half_dt_interpolates_the_grid(fmu_path):
    # Outputs between grid points are the linear interpolation of their neighbours (§15): a
    # quadratic base is the same signal from any communication point, so both runs take the
    # same grid steps.
    def base(t):
        return (0.5 * t * t, t, 1.0)

    fine, grid = [], []
    with PlateImpactFMU(fmu_path) as plate:
        for k in range(40):
            fine.append(plate.step(DT / 2, base=base(k * DT / 2)))
    with PlateImpactFMU(fmu_path) as plate:
        for k in range(20):
            grid.append(plate.step(DT, base=base(k * DT)))
    for j in range(1, 19):
        mid = fine[2 * j]  # t = (j + 1/2) dt
        for name in ("corner_1", "energy", "energy_input", "clamp_force"):
            want = 0.5 * (grid[j - 1][name] + grid[j][name])
            assert mid[name] == pytest.approx(want, rel=1e-9, abs=1e-15), name


def smooth_base(t):
    """0.09 (1 − cos 2π·10 t)/2: starts at rest, so held values lose nothing at the start."""
    w, a = 2 * math.pi * FREQUENCY, AMPLITUDE / 2
    return (a * (1 - math.cos(w * t)), a * w * math.sin(w * t), a * w * w * math.cos(w * t))


def test_2048_hz_signal_through_simulate_fmu(fmu_path):
    # A DAQ rate: 1/2048 s is no multiple of dt = 1e-5 s. fmpy passes held values; the FMU
    # reconstructs them and steps its grid, outputs interpolated at the communication points.
    rate, stop = 2048, 0.04
    t = np.arange(0, stop + 1 / rate, 1 / rate)
    signal = np.array([(x, smooth_base(x)[0]) for x in t], dtype=[("time", float), ("base_displacement", float)])
    result = simulate_fmu(
        str(fmu_path),
        stop_time=stop,
        output_interval=1 / rate,
        input=signal,
        output=["corner_1", "energy", "energy_input", "energy_dissipated", "energy_damped"],
    )
    assert result["time"][-1] == pytest.approx(stop, abs=1 / rate)
    # Against the exact base on the grid, before the first impact.
    grid = [PlateImpactFMU(fmu_path)]
    with grid[0] as plate:
        exact = [plate.outputs()["corner_1"]] + [
            plate.step(DT, base=smooth_base(k * DT))["corner_1"] for k in range(4100)
        ]
    reference = np.interp(result["time"], np.arange(len(exact)) * DT, exact)
    off_grid = np.max(np.abs(result["corner_1"] - reference))
    # The same held values at a grid-aligned step of comparable length (5e-4 s) for scale.
    with PlateImpactFMU(fmu_path) as plate:
        aligned = [
            (plate.step(5e-4, base=smooth_base(k * 5e-4), derivatives=False)["corner_1"], plate.time) for k in range(80)
        ]
    aligned_error = max(abs(c - np.interp(t, np.arange(len(exact)) * DT, exact)) for c, t in aligned)
    print(f"2048 Hz off-grid error {off_grid:.3g} m, grid-aligned 5e-4 s error {aligned_error:.3g} m")
    assert off_grid < 1e-4 and off_grid < 3 * aligned_error + 1e-6, (off_grid, aligned_error)
    ledger = result["energy"] - result["energy_input"] + result["energy_dissipated"] + result["energy_damped"]
    assert np.max(np.abs(ledger - ledger[0])) <= 1e-9 * np.max(np.abs(result["energy_input"]))


def test_states_between_grid_points_round_trip_bit_identically(fmu_path):
    """A state taken between grid points (h = 1/2048 s is no multiple of dt), serialized and
    restored, continues bit for bit through an impact. The plate starts pressed onto the upper
    obstacle by 8600 Pa (held), the base's first rise pulls it off and it strikes the obstacle
    again in the window (at the 9th step of 1/2048 s) — issue 54: the default scene reaches its
    first impact at 0.0495 s, 160 steps of 1/2048 s and 7,800 internal steps, 25 s of the
    sanitizer stage's CPU; now 22 steps."""
    h, pressed = 1 / 2048, 8600.0
    with PlateImpactFMU(fmu_path, initial_load=pressed, load0=pressed) as plate:
        for k in range(2):
            plate.step(h, base=default_base(k * h))
        state = plate.fmu.getFMUstate()
        serialized = plate.fmu.serializeFMUstate(state)
        t0 = plate.time
        first = [plate.step(h, base=default_base(t0 + k * h)) for k in range(20)]
        plate.fmu.setFMUstate(plate.fmu.deSerializeFMUstate(serialized))
        plate.time = t0
        again = [plate.step(h, base=default_base(t0 + k * h)) for k in range(20)]
    assert first == again
    assert any(r["contact_vertices"] > 0 for r in first)
    assert first[0]["contact_vertices"] == 0  # it left the obstacle: the contact is an impact


def test_bad_port_inputs_are_refused_with_a_message(fmu_path):
    with PlateImpactFMU(fmu_path, base_drive="velocity") as plate:
        with pytest.raises(Exception):
            plate.set("base_velocity", 2e3)
        assert any("base_velocity" in m and "1000" in m for m in plate.errors())
    with PlateImpactFMU(fmu_path) as plate:
        with pytest.raises(Exception):
            plate.step(1e-16)
        assert any("shorter than the smallest step" in m for m in plate.errors())
    with PlateImpactFMU(fmu_path, initialize=False) as plate:
        plate.fmu.setupExperiment(startTime=0.0)
        plate.fmu.enterInitializationMode()
        with pytest.raises(Exception):
            plate.fmu.setInteger([plate.vars["base_drive"].valueReference], [6])  # 4, 5: force, tlm
        assert any("base_drive" in m for m in plate.errors())


@pytest.mark.parametrize(
    "law",
    [
        {},
        {"mass": "singular_p0"},
        {"mass": "singular_p0", "time_scheme": "conserving"},
        {"mass": "singular_p0", "time_scheme": "conserving", "modes": 20},
    ],
)
@pytest.mark.parametrize(
    "scene",
    [
        {"initial_load": 1000.0},  # free: the reaction is p·L·W = 480 N
        {"initial_load": -2000.0, "obstacle_lower": -0.012, "obstacle_upper": 0.012},  # pressed on an obstacle
    ],
)
def test_port_outputs_at_t0_describe_the_initial_state(fmu_path, law, scene):
    # Before any step the port reports the initial static state: the clamp carries what the load
    # and the obstacles put on the plate. Held under the same load the state stays static, so the
    # value is the one the steps then report (a second difference over dt²: roundoff ~1e-6 N).
    p = scene["initial_load"]
    with PlateImpactFMU(fmu_path, load0=p, **scene, **law) as plate:
        at0 = plate.outputs()
        later = [plate.step(DT, load=p) for _ in range(3)][-1]
    if "obstacle_lower" not in scene:
        assert at0["clamp_force"] == pytest.approx(p * 1.2 * 0.4, rel=1e-9)
        assert at0["clamp_moment"] == pytest.approx(p * 1.2 * 0.4 * 0.6, rel=1e-9)
    else:
        assert at0["contact_vertices"] > 0
    assert at0["clamp_force"] == pytest.approx(later["clamp_force"], rel=1e-6, abs=1e-5)
    assert at0["clamp_moment"] == pytest.approx(later["clamp_moment"], rel=1e-6, abs=1e-5)
    assert at0["corner_1_acceleration"] == 0.0 and at0["energy_input"] == 0.0
