"""A second, independent importer: libcosimpy (the Python binding of the Open Simulation
Platform's libcosim, a pip wheel with its own FMI loader, FMI Library) loads and steps
PlateImpact.fmu and gets the same outputs as fmpy.

The default scene (14 x 5 Argyris cells, dt = 1e-5 s, obstacles at +-0.1 m, base
0.09 sin(2 pi 10 t)) for 0.06 s, past the first impacts, with a communication step of 1e-4 s
(libcosim counts time in integer nanoseconds: 100000 ns). libcosim sets inputs only as values
(no fmi2SetRealInputDerivatives), so both importers set z(t_k) at point k and nothing else: the
FMU reconstructs the base inside each step (base_input_mode, default quadratic) for both.
Every output after every step must agree to 1e-12 (relative to max(1, |value|)); in fact they
are bit for bit identical, which the test reports.
"""

import numpy as np
import pytest
from fmpy import read_model_description
from plate_fmu import PlateRun

from plateimpact.scenes import default_base

cosim = pytest.importorskip("libcosimpy.CosimExecution", reason="libcosimpy is not installed (requirements.txt)")
from libcosimpy.CosimExecution import CosimExecution  # noqa: E402
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level  # noqa: E402
from libcosimpy.CosimManipulator import CosimManipulator  # noqa: E402
from libcosimpy.CosimObserver import CosimObserver  # noqa: E402
from libcosimpy.CosimSlave import CosimLocalSlave  # noqa: E402

# The sanitizer stage of test.sh runs this file against the ASan+UBSan build (pytest.ini).
pytestmark = pytest.mark.sanitizer


def interface(fmu_path):
    """Output value references by name (Real and Integer), and every variable's, from the FMU."""
    variables = read_model_description(str(fmu_path)).modelVariables
    outputs = {
        t: {v.name: v.valueReference for v in variables if v.causality == "output" and v.type == t}
        for t in ("Real", "Integer")
    }
    return outputs["Real"], outputs["Integer"], {v.name: v.valueReference for v in variables}


STEP_NS = 100_000  # 1e-4 s
H = STEP_NS * 1e-9
STEPS = 600  # 0.06 s: the plate first hits an obstacle after about 0.05 s


def base(k):
    """The held base displacement over communication step k."""
    return default_base(k * H)[0]


def run_libcosim(fmu_path):
    REAL_OUTPUTS, INTEGER_OUTPUTS, VR = interface(fmu_path)
    log_output_level(CosimLogLevel.ERROR)
    execution = CosimExecution.from_step_size(STEP_NS)
    slave = CosimLocalSlave(fmu_path=str(fmu_path), instance_name="plate")
    index = execution.add_local_slave(slave)
    assert index >= 0, "libcosim could not load the FMU"
    manipulator = CosimManipulator.create_override()
    observer = CosimObserver.create_last_value()
    assert execution.add_manipulator(manipulator) and execution.add_observer(observer)
    names = {v.name.decode() for v in execution.slave_variables(index)}
    assert set(REAL_OUTPUTS) | set(INTEGER_OUTPUTS) <= names
    assert execution.real_initial_value(index, VR["dt"], 1e-5)  # the default, set explicitly
    reals, ints = list(REAL_OUTPUTS.values()), list(INTEGER_OUTPUTS.values())
    trace = []
    for k in range(STEPS):
        assert manipulator.slave_real_values(index, [VR["base_displacement"]], [base(k)])
        assert execution.step(), f"libcosim step {k} failed: {execution.status()}"
        trace.append(list(observer.last_real_values(index, reals)) + list(observer.last_integer_values(index, ints)))
    assert execution.status().current_time == STEPS * STEP_NS
    del execution, manipulator, observer, slave  # libcosim frees the instance
    return np.array(trace, dtype=float)


def run_fmpy(fmu_path):
    REAL_OUTPUTS, INTEGER_OUTPUTS, _ = interface(fmu_path)
    trace = []
    with PlateRun(fmu_path, dt=1e-5) as run:
        for k in range(STEPS):
            out = run.step(H, base=base(k), derivatives=False)  # a value only, as libcosim
            trace.append([out[n] for n in REAL_OUTPUTS] + [out[n] for n in INTEGER_OUTPUTS])
    return np.array(trace, dtype=float)


def test_libcosimpy_and_fmpy_give_the_same_outputs(fmu_path):
    assert fmu_path.is_file(), f"FMU not built: {fmu_path} (build it or set PLATEIMPACT_FMU)"
    theirs = run_libcosim(fmu_path)
    ours = run_fmpy(fmu_path)
    REAL_OUTPUTS, INTEGER_OUTPUTS, _ = interface(fmu_path)
    names = list(REAL_OUTPUTS) + list(INTEGER_OUTPUTS)
    assert theirs.shape == ours.shape == (STEPS, len(names))
    assert np.isfinite(ours).all()
    column = {n: i for i, n in enumerate(names)}
    assert ours[:, column["contact_vertices"]].max() > 0, "no impact within the horizon"
    assert ours[-1, column["energy_dissipated"]] > 0
    error = np.abs(theirs - ours) / np.maximum(1.0, np.abs(ours))
    worst = {n: float(error[:, i].max()) for n, i in column.items()}
    assert max(worst.values()) <= 1e-12, worst
    print(
        f"libcosimpy vs fmpy over {STEPS} steps: bit-identical: {bool((theirs == ours).all())}, "
        f"worst relative difference {max(worst.values()):.1e}"
    )


SWITCH_STEPS = 100  # 0.01 s
CLAMP_SPEED = 0.5  # m/s: the clamp rises 5 mm, far from the obstacles


def switched_fmpy(fmu_path, element):
    """corner_1 and clamp_displacement after SWITCH_STEPS through fmpy, the clamp driven by
    base_velocity = CLAMP_SPEED (base_drive = 2, velocity) on the given element."""
    import fmpy

    result = fmpy.simulate_fmu(
        str(fmu_path),
        stop_time=SWITCH_STEPS * H,
        step_size=H,
        output_interval=H,
        start_values={"base_drive": 2, "element": element, "base_velocity": CLAMP_SPEED},
        output=["corner_1", "clamp_displacement"],
    )
    return float(result["corner_1"][-1]), float(result["clamp_displacement"][-1])


def test_libcosimpy_sets_the_integer_switches_on_the_unmodified_fmu(fmu_path):
    """base_drive and element are Integers with min/max (libcosim skips Enumeration variables):
    libcosim sets base_drive = 2 (velocity) and element = 2 (fvs) as initial values on the FMU as
    built, and both take effect — the clamp follows the integrated base_velocity and corner_1 is
    the FVS plate's (fmpy with the same switches), not the Argyris plate's."""
    _, _, VR = interface(fmu_path)
    log_output_level(CosimLogLevel.ERROR)
    execution = CosimExecution.from_step_size(STEP_NS)
    index = execution.add_local_slave(CosimLocalSlave(fmu_path=str(fmu_path), instance_name="plate"))
    observer = CosimObserver.create_last_value()
    assert execution.add_observer(observer)
    names = {v.name.decode() for v in execution.slave_variables(index)}
    assert {"base_drive", "element"} <= names, "libcosim does not see the switches"
    assert execution.integer_initial_value(index, VR["base_drive"], 2)
    assert execution.integer_initial_value(index, VR["element"], 2)
    assert execution.real_initial_value(index, VR["base_velocity"], CLAMP_SPEED)
    for k in range(SWITCH_STEPS):
        assert execution.step(), f"libcosim step {k} failed: {execution.status()}"
    switches = list(observer.last_integer_values(index, [VR["base_drive"], VR["element"]]))
    corner, clamp = observer.last_real_values(index, [VR["corner_1"], VR["clamp_displacement"]])
    del execution, observer
    assert switches == [2, 2]
    assert clamp == pytest.approx(CLAMP_SPEED * SWITCH_STEPS * H, rel=1e-9)  # the velocity drove the clamp
    fvs_corner, fvs_clamp = switched_fmpy(fmu_path, element=2)
    argyris_corner, _ = switched_fmpy(fmu_path, element=1)
    assert clamp == fvs_clamp
    assert corner == pytest.approx(fvs_corner, rel=1e-12, abs=1e-15)
    assert abs(fvs_corner - argyris_corner) > 1e3 * abs(corner - fvs_corner) + 1e-9, "element had no effect"
