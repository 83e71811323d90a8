"""time_scheme = conserving (docs/theory.md §17) through fmpy, as users drive it: the energy
balance closes through impacts at any dt, no reported displacement passes an obstacle, the
reduced model tends to the full engine, the scheme and singular_p0 tend to the same impact
times, the port's identities, FMU states, FMI 3.0 events, and what it refuses."""

from __future__ import annotations

import math
from pathlib import Path

import fmpy
import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from plateimpact import PlateImpactFMU, default_base
from plateimpact.driver import unzipped

pytestmark = pytest.mark.sanitizer  # the conserving engine's code paths (test.sh's sanitizer stage)
# What a test left out of the sanitizer stage names (repeats_paths, conftest.py): every engine's
# stepping and state code under ASan, one configuration each.
STATE = "test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical"

CONSERVING = {"mass": "singular_p0", "time_scheme": "conserving"}
# time_scheme = flow (docs/theory.md §21): exact free flight, contact steps in sub-steps.
FLOW = {"mass": "singular_p0", "time_scheme": "flow"}
# §5.2: released from the static shape under 8600 Pa onto the lower obstacle alone.
RELEASE = {"initial_load": 8600.0, "obstacle_upper_enabled": False}
# The contact solve (docs/theory.md §17): each step's discrete gradient is iterated until its
# energy residual ψ0 − ψ1 − Λ·Δr is below 1e-13 of the step's energies (the plate's kinetic and
# modal strain energy plus the boundary terms). A run of N contact steps can so drift by at most
# N · 1e-13 · E; 1e-8 of the energy scale leaves a factor > 10 for the few thousand contact
# steps below and for the roundoff of the ledger's sums.
LEDGER_TOLERANCE = 1e-8


def ledger_residual(out, e0):
    return out["energy"] - e0 - out["energy_input"] + out["energy_damped"] + out["energy_dissipated"]


def run(fmu_path, stop, h=1e-3, base=None, load=None, every=None, **parameters):
    """Steps of h to stop; the outputs after each (every(k, out) may look at them)."""
    rows = []
    with PlateImpactFMU(fmu_path, **parameters) as plate:
        rows.append(plate.outputs())
        for k in range(int(round(stop / h))):
            t = k * h
            rows.append(plate.step(h, base=base(t) if base else None, load=load(t) if load else None))
    return rows


@pytest.mark.repeats_paths(
    "test_conserving.py::test_no_reported_displacement_passes_an_obstacle[scene1]",  # released, through impacts
    f"{STATE}[conserving]",
)
@pytest.mark.parametrize("dt", [4e-5, 1e-5, 2.5e-6])
@pytest.mark.parametrize("element, nx, ny", [("argyris", 14, 5), ("fvs", 20, 7)])
def test_energy_is_conserved_through_impacts_in_free_vibration(fmu_path, dt, element, nx, ny):
    rows = run(fmu_path, 0.3, dt=dt, element=element, nx=nx, ny=ny, **RELEASE, **CONSERVING)
    e0, last = rows[0]["energy"], rows[-1]
    assert last["contact_onsets_lower"] >= 2, "the window must contain the first two impacts"
    assert last["energy_input"] == 0.0 and last["energy_damped"] == 0.0
    worst = max(abs(ledger_residual(r, e0)) for r in rows)
    assert worst <= LEDGER_TOLERANCE * e0


@pytest.mark.repeats_paths(
    "test_conserving.py::test_no_reported_displacement_passes_an_obstacle[scene0]", f"{STATE}[conserving]"
)
@pytest.mark.parametrize("element, nx, ny", [("argyris", 14, 5), ("fvs", 20, 7)])
@pytest.mark.parametrize("dt", [4e-5, 1e-5])
def test_energy_balance_closes_with_base_load_and_both_obstacles(fmu_path, element, nx, ny, dt):
    # The default scene's base and a pressure varying at 7 Hz: impacts on both obstacles.
    rows = run(
        fmu_path,
        0.25,
        h=1e-4,
        base=default_base,
        load=lambda t: (
            2000.0 * math.sin(2 * math.pi * 7 * t),
            2000.0 * 2 * math.pi * 7 * math.cos(2 * math.pi * 7 * t),
            0.0,
        ),
        dt=dt,
        element=element,
        nx=nx,
        ny=ny,
        **CONSERVING,
    )
    last = rows[-1]
    assert last["contact_onsets_lower"] > 0 and last["contact_onsets_upper"] > 0
    scale = max(r["energy"] for r in rows)
    assert max(abs(ledger_residual(r, 0.0)) for r in rows) <= LEDGER_TOLERANCE * scale


def test_modal_damping_is_booked_in_the_ledger(fmu_path):
    rows = run(fmu_path, 0.3, damping_mass=3.0, damping_stiffness=2e-5, **RELEASE, **CONSERVING)
    e0, last = rows[0]["energy"], rows[-1]
    assert last["energy_damped"] > 0.05 * e0  # it does dissipate
    assert max(abs(ledger_residual(r, e0)) for r in rows) <= LEDGER_TOLERANCE * e0


def within_obstacles(rows, lower, upper, names=("corner_1", "corner_2", "free_edge_mid")):
    return max(max(r[n] - upper, lower - r[n]) for r in rows for n in names)


@pytest.mark.parametrize(
    "scene",
    [
        {"ny": 5},  # the default scene: free_edge_mid between two vertices (a row of its own)
        {"ny": 5, **RELEASE},  # §5.2
        {"ny": 3, "obstacle_lower": -0.012, "obstacle_upper": 0.012, "initial_load": -2000.0},  # near obstacles
    ],
)
def test_no_reported_displacement_passes_an_obstacle(fmu_path, scene):
    lower = scene.get("obstacle_lower", -0.1)
    upper = scene.get("obstacle_upper", 0.1) if scene.get("obstacle_upper_enabled", True) else math.inf
    rows = run(fmu_path, 0.3, h=1e-4, base=default_base if "initial_load" not in scene else None, **scene, **CONSERVING)
    assert sum(r["contact_vertices"] > 0 for r in rows) > 10  # the run presses the plate on an obstacle
    # Roundoff of a row's height G q + p c + z + D λ: a few ulps of the heights (0.1 m).
    assert within_obstacles(rows, lower, upper) <= 1e-14


def test_the_paper_scheme_lets_free_edge_mid_pass_the_obstacle(fmu_path):
    # What the conserving scheme fixes (docs/theory.md §17): on the default scene the paper's
    # scheme holds only the vertices, and free_edge_mid (between two vertices) passes by ~0.5 mm.
    rows = run(fmu_path, 0.3, h=1e-4, base=default_base)
    assert within_obstacles(rows, -0.1, 0.1, ("free_edge_mid",)) > 1e-4


def corner_path(fmu_path, stop, **parameters):
    return np.array([r["corner_1"] for r in run(fmu_path, stop, h=1e-4, **RELEASE, **CONSERVING, **parameters)])


@pytest.mark.repeats_paths(
    "test_conserving.py::test_work_of_the_clamp_force_is_the_energy_input_through_impacts[30]",  # 30 modes
    "test_conserving.py::test_no_reported_displacement_passes_an_obstacle[scene0]",
)
def test_reduced_model_tends_to_the_full_engine(fmu_path):
    # 140 massive modes on 14 x 5 Argyris cells (one per triangle); over 0.1 s (the first impact).
    full = corner_path(fmu_path, 0.1)
    assert np.array_equal(corner_path(fmu_path, 0.1, modes=140), full)  # all modes: the full engine
    errors = [np.max(np.abs(corner_path(fmu_path, 0.1, modes=m) - full)) for m in (10, 40, 120)]
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 0.05 * errors[0]


def second_impact_time(fmu_path, dt, **law):
    """The grid time of the first contact after 0.2 s (the second impact episode of §5.2)."""
    with PlateImpactFMU(fmu_path, dt=dt, **RELEASE, **law) as plate:
        plate.step(0.2)
        for k in range(int(round(0.04 / dt))):
            if plate.step(dt)["contact_vertices"] > 0:
                return 0.2 + (k + 1) * dt
    raise AssertionError("no impact between 0.2 and 0.24 s")


@pytest.mark.repeats_paths(
    "test_conserving.py::test_no_reported_displacement_passes_an_obstacle[scene1]",
    "test_stability.py::test_stability_case[singular_p0_dt_1e-3]",
)
def test_conserving_and_singular_p0_tend_to_the_same_impact_times(fmu_path):
    gaps = [
        abs(second_impact_time(fmu_path, dt, **CONSERVING) - second_impact_time(fmu_path, dt, mass="singular_p0"))
        for dt in (2e-5, 5e-6)
    ]
    # Both schemes converge to the same semi-discrete solution (first order in dt at impacts):
    # the gap shrinks with dt and is a few steps at most.
    assert gaps[1] < gaps[0] or gaps[1] <= 2 * 5e-6
    assert gaps[1] <= 2e-4


def test_static_pressure_gives_the_clamp_force_and_moment_of_statics(fmu_path):
    p, length, width = 300.0, 1.2, 0.4
    with PlateImpactFMU(fmu_path, initial_load=p, load0=p, **CONSERVING) as plate:
        for _ in range(5):
            out = plate.step(10e-5, load=p)
    assert out["contact_vertices"] == 0
    # Roundoff of the modal sums (140 modes, forces ~100 N): 1e-9 relative.
    assert out["clamp_force"] == pytest.approx(p * length * width, rel=1e-9)
    assert out["clamp_moment"] == pytest.approx(p * length * width * length / 2, rel=1e-9)


@pytest.mark.parametrize("modes", [0, 30])
def test_work_of_the_clamp_force_is_the_energy_input_through_impacts(fmu_path, modes):
    # The clamp's force on the plate over step n (at t_{n+½}) times z_{n+1} − z_n is the base's
    # work in the ledger (T.17d); with modes < all, the clamp-carried mass's inertia is at t_n and
    # its work pairs with (z_{n+1} − z_{n−1})/2 (§17), so the identity holds with both pairings.
    dt = 1e-5
    w = 2 * math.pi * 10.0

    # A base that starts at rest (no velocity jump at t = 0): the two pairings of the reduced
    # model's clamp-carried part then differ by Σ m_c z̈² dt²/2, O(ω² dt T) ~ 3e-3 of the work.
    def smooth(t):
        return (0.045 * (1 - math.cos(w * t)), 0.045 * w * math.sin(w * t), 0.045 * w * w * math.cos(w * t))

    rows = run(fmu_path, 0.07, h=dt, base=smooth, modes=modes, **CONSERVING)
    z = np.array([r["clamp_displacement"] for r in rows])
    force_on_plate = -np.array([r["clamp_force"] for r in rows[1:]])
    work = np.cumsum(force_on_plate * np.diff(z))
    energy_input = np.array([r["energy_input"] for r in rows[1:]])
    assert rows[-1]["contact_onsets_upper"] + rows[-1]["contact_onsets_lower"] > 0
    if modes == 0:
        assert np.max(np.abs(work - energy_input)) <= 1e-9 * np.max(np.abs(energy_input))
    else:  # the clamp-carried part is paired at another level: O(dt) relative
        assert np.max(np.abs(work - energy_input)) <= 1e-2 * np.max(np.abs(energy_input))


def test_momentum_balance_of_the_port(fmu_path):
    # Summed over the steps, the forces on the plate (clamp, contacts; no load) change its
    # momentum: with every mode kept the plate's momentum is b_mᵀP (docs/theory.md §17), and at
    # rest at both ends of a window in free flight the impulses cancel. Here: the mean clamp
    # force over a base period with the plate in contact balances the mean contact force.
    rows = run(fmu_path, 0.2, h=1e-5, base=default_base, **CONSERVING)
    clamp = -np.array([r["clamp_force"] for r in rows[1:]])  # on the plate
    contact = np.array([r["contact_force_lower"] + r["contact_force_upper"] for r in rows[1:]])
    impulse = rows[-1]["contact_impulse_lower"] + rows[-1]["contact_impulse_upper"]
    assert impulse == pytest.approx(contact.sum() * 1e-5, rel=1e-12)
    # Momentum change = Σ (clamp + contact) dt; the plate's momentum from the probes' motion is
    # not an output, so check the bound it implies: |Σ| ≤ m · (max velocity) · 2.
    total = (clamp + contact).sum() * 1e-5
    assert abs(total) <= 2 * 37.3 * 10.0


def test_fmu_states_continue_bit_identically(fmu_path):
    with PlateImpactFMU(fmu_path, **RELEASE, **CONSERVING) as plate:
        plate.step(0.068)  # just before the first impact
        state = plate.fmu.serializeFMUstate(plate.fmu.getFMUstate())
        first = [plate.step(1e-3) for _ in range(20)]
        plate.time = 0.068
        plate.fmu.setFMUstate(plate.fmu.deSerializeFMUstate(state))
        again = [plate.step(1e-3) for _ in range(20)]
    assert first == again
    assert first[-1]["contact_onsets_lower"] > 0


def test_fmi3_early_return_stops_at_contact_events(fmu_path):
    fmu3 = Path(fmu_path).parent / "fmi3" / "PlateImpact.fmu"
    start = {"mass": 2, "time_scheme": 2, **RELEASE}
    unzipdir, md = unzipped(fmu3)  # extracted once per process, its library kept loaded
    early = fmpy.simulate_fmu(
        unzipdir,
        model_description=md,
        stop_time=0.1,
        output_interval=1e-3,
        start_values=start,
        output=["contact_vertices", "corner_1"],
        early_return_allowed=True,
        use_event_mode=True,
    )
    off_regular = [t for t in early["time"] if abs(t / 1e-3 - round(t / 1e-3)) > 1e-9]
    assert off_regular, "the impact at 0.0677 s is an early return"
    k = list(early["time"]).index(off_regular[0])
    assert early["contact_vertices"][k] > 0 and early["contact_vertices"][k - 1] == 0
    assert early["corner_1"].min() >= -0.1 - 1e-14


@pytest.mark.parametrize(
    "parameters, named",
    [
        ({"time_scheme": "conserving"}, "mass"),
        ({**CONSERVING, "restitution": 0.5}, "restitution"),
        ({"mass": "singular_p0", "modes": 20}, "modes"),
        ({**CONSERVING, "base_drive": 4, "armature_mass": 20.0}, "base_drive"),
        ({"time_scheme": "flow"}, "mass"),
        ({**FLOW, "contact_substeps": 0}, "contact_substeps"),
        ({**FLOW, "contact_substeps": 65}, "contact_substeps"),
    ],
)
def test_what_it_cannot_take_is_refused_with_a_message(fmu_path, parameters, named):
    plate = PlateImpactFMU(fmu_path, initialize=False)
    try:
        plate.enter_initialization(parameters)
        with pytest.raises(FMICallException):
            plate.exit_initialization()
        assert any(f"invalid parameter {named}" in m for m in plate.errors()), plate.errors()
    finally:
        plate.free()


def test_memory_estimate_refuses_beyond_the_budget(fmu_path):
    # 28 x 10 cells: 560 massive coordinates, 319 rows; estimated ~35 MB (docs/performance.md).
    plate = PlateImpactFMU(fmu_path, initialize=False)
    try:
        plate.fmu.setupExperiment(startTime=0.0)
        plate.fmu.enterInitializationMode()
        for name, value in {"nx": 28, "ny": 10, "memory_limit": 5.0, **CONSERVING}.items():
            plate.set(name, value)
        with pytest.raises(FMICallException):
            plate.fmu.exitInitializationMode()
        assert any("memory_limit" in m for m in plate.errors()), plate.errors()
    finally:
        plate.free()


def test_velocity_drive_and_off_grid_steps(fmu_path):
    # The clamp driven by its velocity through steps of 1.5 dt (the grid leads, outputs are
    # interpolated, docs/theory.md §15): the same plate as the displacement drive on the grid,
    # and the ledger closes at every communication point.
    a, h, n = 5.0, 1.5e-5, 5000  # to 0.075 s: the §5.2 release's first impact (0.068 s)
    runs = {}
    for drive in ("displacement", "velocity"):
        with PlateImpactFMU(fmu_path, base_drive=drive, **RELEASE, **CONSERVING) as plate:
            rows = [plate.outputs()]
            for k in range(n):
                t = k * h
                if drive == "displacement":
                    rows.append(plate.step(h, base=(0.5 * a * t * t, a * t, a)))
                else:
                    plate.set("base_velocity", a * t)
                    plate.fmu.setRealInputDerivatives([plate.vars["base_velocity"].valueReference], [1], [a])
                    rows.append(plate.step(h))
            runs[drive] = rows
    last = runs["velocity"][-1]
    assert last["clamp_displacement"] == pytest.approx(0.5 * a * (n * h) ** 2, rel=1e-9)
    assert last["contact_onsets_lower"] > 0
    for name in ("corner_1", "energy", "energy_input"):
        assert last[name] == pytest.approx(runs["displacement"][-1][name], rel=1e-9, abs=1e-12)
    e0 = runs["velocity"][0]["energy"]
    assert max(abs(ledger_residual(r, e0)) for r in runs["velocity"]) <= LEDGER_TOLERANCE * e0


# time_scheme = flow through the FMU: the same energy identity at three dt with its sub-steps
# (base, load and both obstacles), every reported point within the obstacles.
@pytest.mark.parametrize("dt", [4e-5, 2e-5, 1e-5])
def test_flow_scheme_closes_the_ledger_through_impacts(fmu_path, dt):
    rows = run(
        fmu_path,
        0.2,
        h=1e-4,
        base=default_base,
        load=lambda t: 300.0 * math.sin(2 * math.pi * 3 * t),
        dt=dt,
        damping_mass=1.0,
        **FLOW,
    )
    e0 = rows[0]["energy"]
    assert sum(r["contact_vertices"] > 0 for r in rows) > 10
    assert max(abs(ledger_residual(r, e0)) for r in rows) <= LEDGER_TOLERANCE * max(r["energy"] for r in rows)
    assert within_obstacles(rows, -0.1, 0.1) <= 1e-14


def test_flow_scheme_free_flight_does_not_depend_on_dt(fmu_path):
    """Before the first impact the flow is exact: §5.2's corner_1 over its first 0.06 s (the
    first impact is at 0.0677 s) is the same at dt = 4e-5 and 1e-5 to roundoff (1e-12 m), where
    the midpoint rule of time_scheme = conserving differs by its phase error."""

    def corner(dt, law):
        return np.array([r["corner_1"] for r in run(fmu_path, 0.06, h=2e-4, dt=dt, **RELEASE, **law)])

    flow = np.abs(corner(4e-5, FLOW) - corner(1e-5, FLOW)).max()
    midpoint = np.abs(corner(4e-5, CONSERVING) - corner(1e-5, CONSERVING)).max()
    assert flow <= 1e-12
    assert midpoint > 1e4 * flow
