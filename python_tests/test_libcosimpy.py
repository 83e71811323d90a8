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
    log_output_level(CosimLogLevel.ERROR)  # its warning that Enumeration variables (element) are ignored
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
