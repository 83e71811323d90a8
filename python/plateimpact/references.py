"""The reference experiments inside the FMU (FMI-LS-REF): defined here once, generated at build
time from the FMU itself (tools/write_references.py), replayed by `plateimpact.validate`.

Each experiment is a file set under extra/org.fmi-standard.fmi-ls-ref/ of both FMUs:

  <name>.xml      the experiment: start, stop, communication step, its parameters, stimuli and
                  reference result, and the tolerance of every compared output
  <name>.ssv      the parameters (SSP 1.0 parameter set; the FMU's defaults for the rest)
  <name>_in.csv   the stimuli at every communication point (fmpy's and fmusim's input CSV)
  <name>_ref.csv  the reference result: the compared outputs at every communication point

and fmi-ls-manifest.xml lists them by role, each with its SHA3-256 checksum (an annotation). How a
reference and its tolerances are made, and what they cover: tools/write_references.py.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

LS_DIR = "extra/org.fmi-standard.fmi-ls-ref"
MANIFEST = f"{LS_DIR}/fmi-ls-manifest.xml"
DOCUMENT = "documentation/fmi-ls-ref.html"
EXPERIMENT_TYPE = "application/x-plateimpact-experiment+xml"
CHECKSUM_ANNOTATION = "org.plateimpact.checksum"
NOISE = 2.0**-50  # the stimuli's rounding-level noise of the spreads, relative to the input's scale

AMPLITUDE, FREQUENCY = 0.09, 10.0  # the paper's §5.1 base, m and Hz
W = 2.0 * math.pi * FREQUENCY

# The outputs every experiment compares: the three observation points, the energy ledger, the
# clamp port, the obstacles' impulses and the stresses (the root now and its peak, the plate's largest).
COMMON = (
    "corner_1",
    "corner_2",
    "free_edge_mid",
    "energy",
    "energy_dissipated",
    "energy_input",
    "clamp_force",
    "contact_impulse_lower",
    "contact_impulse_upper",
    "root_stress",
    "root_stress_peak",
    "max_stress",
)
# Three probes (the forced scene): one inside the plate, one at corner_1's point, one near the free
# edge; their absolute motion as the corners' (docs/theory.md §23). Named as the FMI 2.0 FMU's
# scalars; the FMI 3.0 FMU runs them as its arrays (simulate_probe_arrays).
PROBE = {
    "probe_count": 3,
    "probe_1_x": 0.9,
    "probe_1_y": 0.1,
    "probe_2_x": 1.2,
    "probe_2_y": 0.0,
    "probe_3_x": 1.05,
    "probe_3_y": 0.3,
}
# The stress outputs are computed on request (stress_outputs, docs/theory.md §23): every experiment asks.
STRESS = {"stress_outputs": True}
PROBE_OUTPUTS = ("probe_1", "probe_1_velocity", "probe_1_acceleration", "probe_2", "probe_3", "probe_3_velocity")


def forced_base(t):
    return AMPLITUDE * np.sin(W * t)


@dataclass(frozen=True)
class Experiment:
    name: str
    role: str  # smoke-test | validation
    description: str
    stop: float
    step: float  # communication step, s
    parameters: dict
    stimuli: dict[str, Callable] = field(default_factory=dict)  # input -> f(t array)
    outputs: tuple = COMMON
    perturb: str | None = None  # the parameter the noise goes on when no stimulus varies


# Quadratic extrapolation of the communicated inputs inside each step (generic masters give no
# input derivatives): base_input_mode = load_input_mode = quadratic.
QUADRATIC = {"base_input_mode": 3}

EXPERIMENTS = (
    Experiment(
        "smoke",
        "smoke-test",
        "The default scene for 0.1 s: the default plate (14x5 Argyris cells, dt = 1e-5 s, obstacles at "
        "+-0.1 m) on the base 0.09 sin(2 pi 10 t) m, communicated every 1e-4 s; first impact near 0.0496 s",
        0.1,
        1e-4,
        dict(QUADRATIC, **STRESS),
        {"base_displacement": forced_base},
    ),
    Experiment(
        "forced",
        "validation",
        "The paper's section 5.1 forced oscillation (figure 6): 14x5 Argyris cells, dt = 1e-4 s, base 0.09 "
        "sin(2 pi 10 t) m, obstacles at +-0.1 m, 0.1 s communicated every 1e-3 s: impacts on both obstacles; "
        "three probes at (0.9, 0.1), (1.2, 0) (corner_1's point) and (1.05, 0.3) m",
        0.1,
        1e-3,
        dict(QUADRATIC, **STRESS, nx=14, ny=5, dt=1e-4, **PROBE),
        {"base_displacement": forced_base},
        outputs=COMMON + PROBE_OUTPUTS,
    ),
    Experiment(
        "release",
        "validation",
        "The paper's section 5.2 free vibration (figures 12-16): 16x5 Argyris cells released at rest from the "
        "static shape under 8600 Pa, lower obstacle only (-0.1 m), dt = 1e-5 s, 0.1 s communicated every 1e-3 s",
        0.1,
        1e-3,
        dict(STRESS, nx=16, ny=5, dt=1e-5, initial_load=8600.0, obstacle_upper_enabled=False),
        perturb="initial_load",
    ),
    Experiment(
        "conserving",
        "validation",
        "The conserving law (time_scheme = conserving, mass = singular_p0) on the forced scene: the energy ledger "
        "closes through impacts; 14x5 Argyris cells, dt = 1e-4 s, 0.1 s communicated every 1e-3 s",
        0.1,
        1e-3,
        dict(QUADRATIC, **STRESS, nx=14, ny=5, dt=1e-4, time_scheme=2, mass=2),
        {"base_displacement": forced_base},
    ),
    Experiment(
        "velocity",
        "validation",
        "Velocity-driven clamp (base_drive = velocity): base_velocity = 0.09 (2 pi 10) cos(2 pi 10 t) m/s, "
        "integrated inside the FMU; the forced scene's plate at dt = 1e-4 s, 0.1 s communicated every 1e-3 s",
        0.1,
        1e-3,
        dict(QUADRATIC, **STRESS, nx=14, ny=5, dt=1e-4, base_drive=2),
        {"base_velocity": lambda t: AMPLITUDE * W * np.cos(W * t)},
        outputs=COMMON + ("clamp_displacement",),
    ),
    Experiment(
        "load",
        "validation",
        "Load-driven plate: clamp at rest, uniform pressure 6000 sin(2 pi 10 t) Pa (load_input_mode = "
        "quadratic), obstacles at +-0.05 m, 14x5 Argyris cells, dt = 1e-4 s, 0.1 s communicated every 1e-3 s",
        0.1,
        1e-3,
        dict(STRESS, nx=14, ny=5, dt=1e-4, load_input_mode=3, obstacle_lower=-0.05, obstacle_upper=0.05),
        {"load": lambda t: 6000.0 * np.sin(W * t)},
    ),
    Experiment(
        "fvs",
        "validation",
        "The FVS element (element = fvs, 20x7 quadrilaterals) on the forced scene: dt = 1e-4 s, base 0.09 "
        "sin(2 pi 10 t) m, obstacles at +-0.1 m, 0.1 s communicated every 1e-3 s",
        0.1,
        1e-3,
        dict(QUADRATIC, **STRESS, element=2, nx=20, ny=7, dt=1e-4),
        {"base_displacement": forced_base},
    ),
    Experiment(
        "stop",
        "validation",
        "Stop under the tip (docs/theory.md section 25): the forced scene's plate and base with the lower obstacle a "
        "stop over x >= 1.0 m at -0.05 m (obstacle_lower_x_min = 1.0), the upper obstacle off; the tip hits the "
        "stop while the clamp swings past its height; dt = 1e-4 s, 0.1 s communicated every 1e-3 s",
        0.1,
        1e-3,
        dict(
            QUADRATIC,
            **STRESS,
            nx=14,
            ny=5,
            dt=1e-4,
            obstacle_lower=-0.05,
            obstacle_lower_x_min=1.0,
            obstacle_upper_enabled=False,
        ),
        {"base_displacement": forced_base},
    ),
)


# The serialized-state experiment: the state of `base` after its first STATE_AT seconds, serialized
# (FMI 2.0 and 3.0 write the same bytes), restored in a new process and run on to base's stop.
@dataclass(frozen=True)
class StateExperiment:
    name: str
    base: str
    at: float
    platforms: tuple = ("linux64", "x86_64-linux")  # where the state was written (FMI 2.0, 3.0 names)


STATES = (StateExperiment("forced_state", "forced", 0.05),)


def serialized_state(fmu, exp: Experiment, at: float) -> bytes:
    """The FMU's serialized state after `at` seconds of the experiment through fmpy."""
    from fmpy import instantiate_fmu

    from .driver import unzipped

    unzipdir, md = unzipped(fmu)  # extracted once per process, its library kept loaded (simulate)
    if md.fmiVersion.startswith("3") and uses_probes(exp.parameters, exp.outputs):
        import contextlib
        import io

        with contextlib.redirect_stdout(io.StringIO()):
            stimuli = stimuli_table(exp)
            _, data = simulate_probe_arrays(
                fmu, 0.0, at, exp.step, exp.parameters, stimuli, exp.outputs, serialize=True
            )
        return data
    inst = instantiate_fmu(unzipdir, md, "CoSimulation")
    try:
        import contextlib
        import io

        from fmpy import simulate_fmu

        with contextlib.redirect_stdout(io.StringIO()):
            simulate_fmu(
                unzipdir,
                start_time=0.0,
                stop_time=at,
                output_interval=exp.step,
                start_values=dict(exp.parameters),
                input=stimuli_table(exp),
                output=list(exp.outputs),
                fmu_instance=inst,
                terminate=False,
                model_description=md,
            )
        data = serialized(inst)
    finally:
        inst.freeInstance()
    return data


def serialized(inst) -> bytes:
    """The instance's FMU state, serialized; the instance terminated after it."""
    state = inst.getFMUState()
    data = bytes(inst.serializeFMUState(state))
    inst.freeFMUState(state)
    inst.terminate()
    return data


# --- files and running ---------------------------------------------------------------------


def read_csv(path) -> np.ndarray:
    lines = Path(path).read_text().splitlines()
    names = [n.strip().strip('"') for n in lines[0].split(",")]
    data = np.array([[float(x) for x in line.split(",")] for line in lines[1:] if line.strip()], dtype=float)
    data = data.reshape(-1, len(names))
    return np.rec.fromarrays(data.T, names=names)


SSV_NS = "http://ssp-standard.org/SSP1/SystemStructureParameterValues"


def read_ssv(path) -> dict:
    """{name: (ssv type, text value)} of an SSP parameter set."""
    from lxml import etree

    root = etree.parse(str(path)).getroot()
    out = {}
    for p in root.iter(f"{{{SSV_NS}}}Parameter"):
        for child in p:
            if isinstance(child.tag, str):
                out[p.get("name")] = (etree.QName(child).localname, child.get("value"))
                break
    return out


def grid(exp: Experiment) -> np.ndarray:
    n = round(exp.stop / exp.step)
    return np.arange(n + 1) * exp.step


def stimuli_table(exp: Experiment, noise_seed=None) -> np.ndarray | None:
    if not exp.stimuli:
        return None
    t = grid(exp)
    cols = {"time": t}
    rng = np.random.default_rng(noise_seed) if noise_seed is not None else None
    for name, f in exp.stimuli.items():
        x = np.asarray(f(t), dtype=float)
        if rng is not None:
            x = x + NOISE * np.max(np.abs(x)) * rng.uniform(-1.0, 1.0, size=x.shape)
        cols[name] = x
    return np.rec.fromarrays(list(cols.values()), names=list(cols))


def typed(value_text: str, kind: str, variable) -> object:
    """An SSV value as the FMU variable's type wants it (fmpy's start_values)."""
    if kind == "Boolean":
        return value_text.strip().lower() in ("true", "1")
    if variable is not None and variable.type in ("Real", "Float64", "Float32"):
        return float(value_text)
    if kind in ("Integer", "Enumeration") or (variable is not None and variable.type not in ("Real", "Float64")):
        return int(float(value_text))
    return float(value_text)


# The FMI 2.0 FMU's scalar probes: probe_count, probe_<k>_x, probe_<k>_y and the outputs probe_<k>,
# probe_<k>_velocity, probe_<k>_acceleration. The FMI 3.0 FMU has them as arrays (docs/fmi3.md).
SCALAR_PROBE = re.compile(r"probe_(\d+)(_x|_y|_velocity|_acceleration)?$")
ARRAY_OF = {None: "probe", "_velocity": "probe_velocity", "_acceleration": "probe_acceleration"}


def uses_probes(parameters: dict, outputs) -> bool:
    return "probe_count" in parameters or any(SCALAR_PROBE.match(n) for n in (*parameters, *outputs))


def simulate_probe_arrays(fmu, start, stop, step, parameters: dict, stimuli, outputs, fmu_state=None, serialize=False):
    """An experiment written with the FMI 2.0 FMU's scalar probes on the FMI 3.0 FMU: probe_count set
    in Configuration Mode, the places as probe_x and probe_y, the outputs probe_<k>... read from the
    arrays after each communication step; the rest through simulate_fmu as simulate() does. A state
    carries the count and the places. serialize: (the result, the serialized state at `stop`)."""
    from fmpy import instantiate_fmu, simulate_fmu
    from fmpy.simulation import Input, apply_start_values, settable_in_initialization_mode, settable_in_instantiated

    from .driver import unzipped

    unzipdir, md = unzipped(fmu)  # extracted once per process, its library kept loaded (simulate)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    inst = instantiate_fmu(unzipdir, md, "CoSimulation")
    rest = {k: v for k, v in parameters.items() if k != "probe_count" and not SCALAR_PROBE.match(k)}
    probe_outputs = [n for n in outputs if SCALAR_PROBE.match(n)]
    columns = {}  # name -> values at the communication points
    try:
        if fmu_state is None:
            count = int(parameters.get("probe_count", 0))
            inst.enterConfigurationMode()
            inst.setUInt64([vr["probe_count"]], [count])
            inst.exitConfigurationMode()
            places = [parameters.get(f"probe_{k + 1}{axis}", 0.0) for axis in ("_x", "_y") for k in range(count)]
            if count:
                inst.setFloat64([vr["probe_x"], vr["probe_y"]], [float(x) for x in places])
            values = apply_start_values(inst, md, rest, settable=settable_in_instantiated)
            inst.enterInitializationMode(startTime=start)
            values = apply_start_values(inst, md, values, settable=settable_in_initialization_mode)
            if values:
                raise ValueError(f"start values not set: {sorted(values)}")
            if stimuli is not None:
                Input(fmu=inst, modelDescription=md, signals=stimuli).apply(start)
            inst.exitInitializationMode()
        else:
            inst.setFMUState(inst.deserializeFMUState(fmu_state))
            count = inst.getUInt64([vr["probe_count"]])[0]

        def sample():
            for name in probe_outputs:
                k, kind = SCALAR_PROBE.match(name).groups()
                array = inst.getFloat64([vr[ARRAY_OF[kind]]], nValues=count)
                columns.setdefault(name, []).append(array[int(k) - 1])

        sample()  # the first communication point (simulate_fmu samples it before stepping)
        result = simulate_fmu(
            unzipdir,
            start_time=start,
            stop_time=stop,
            output_interval=step,
            input=stimuli,
            output=[n for n in outputs if not SCALAR_PROBE.match(n)],
            fmi_type="CoSimulation",
            fmu_instance=inst,
            initialize=False,
            model_description=md,
            step_finished=lambda time, recorder: sample() or True,
            terminate=not serialize,
        )
        data = serialized(inst) if serialize else None
    finally:
        inst.freeInstance()
    names = list(result.dtype.names) + probe_outputs
    arrays = [result[n] for n in result.dtype.names] + [np.asarray(columns[n], dtype=float) for n in probe_outputs]
    table = np.rec.fromarrays(arrays, names=names)
    return (table, data) if serialize else table


def simulate(fmu, start, stop, step, parameters: dict, stimuli, outputs, fmu_state=None) -> np.ndarray:
    """The experiment through fmpy's simulate_fmu: a fixed communication step, the stimuli applied
    at every communication point; the outputs at every communication point. fmu_state: a
    serialized FMU state set right after instantiation instead of initializing (the parameters
    are the state's). An experiment with the FMI 2.0 FMU's scalar probes runs on an FMI 3.0 FMU
    through its probe arrays (simulate_probe_arrays).

    The FMU is extracted once per process and its library stays loaded (driver.unzipped), so that
    the experiments of one plate share its discretization (the FMU's cache, README "Performance"):
    the validator's and the generator's runs of the default plate build it once, not once per run
    (issue 54; the results are the same bits, docs/theory.md)."""
    import contextlib
    import io

    from fmpy import simulate_fmu

    from .driver import unzipped

    unzipdir, md = unzipped(fmu)
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):  # fmpy prints a warning per input the CSV leaves out
        if uses_probes(parameters, outputs) and md.fmiVersion.startswith("3"):
            return simulate_probe_arrays(fmu, start, stop, step, parameters, stimuli, outputs, fmu_state)
        result = simulate_fmu(
            unzipdir,
            model_description=md,
            start_time=start,
            stop_time=stop,
            output_interval=step,
            start_values=dict(parameters),
            input=stimuli,
            output=list(outputs),
            fmi_type="CoSimulation",
            fmu_state=fmu_state,
        )
    for line in printed.getvalue().splitlines():
        if not line.startswith("Warning: missing input for variable"):
            print(line)
    return result


def deviation(result, reference, name) -> float:
    """max over the reference's times of |result - reference| (the result interpolated linearly
    onto the reference's times when they differ)."""
    t_ref = np.asarray(reference["time"], dtype=float)
    t = np.asarray(result["time"], dtype=float)
    y = np.asarray(result[name], dtype=float)
    y_ref = np.asarray(reference[name], dtype=float)
    if len(t) != len(t_ref) or np.max(np.abs(t - t_ref)) > 1e-9 * max(1.0, t_ref[-1]):
        y = np.interp(t_ref, t, y)
    d = np.abs(y - y_ref)
    return float(np.max(d)) if d.size else 0.0


def uninterrupted_from(table, t0):
    keep = np.asarray(table["time"]) >= t0 - 1e-12
    return table[keep]
