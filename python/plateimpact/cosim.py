"""The two-FMU system model (SineSweep.fmu driving PlateImpact.fmu's clamp) run by real masters:
libcosimpy's execution/connections API, and an SSP file (examples/system_model.ssd) run by
libcosim and by fmpy's SSP master. Each runner returns corner_1 of the plate after every
communication step (examples/system_model.py is the command line)."""

from __future__ import annotations

import shutil
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from .scenes import AMPLITUDE, DT, FREQUENCY, RAMP

# The sweep's parameters for the smooth-start scene (a constant 10 Hz with a 0.05 s ramp-in).
SWEEP = {
    "amplitude": AMPLITUDE,
    "start_frequency": FREQUENCY,
    "end_frequency": FREQUENCY,
    "duration": 1.0,
    "ramp_time": RAMP,
}


def variables(fmu):
    from fmpy import read_model_description

    return {v.name: v.valueReference for v in read_model_description(str(fmu)).modelVariables}


def run_libcosim(sweep_fmu, plate_fmu, h, stop):
    """The two FMUs as slaves of one libcosim execution, sweep.base_displacement connected to
    plate.base_displacement; corner_1 of the plate after every step."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    sv, pv = variables(sweep_fmu), variables(plate_fmu)
    execution = CosimExecution.from_step_size(round(h * 1e9))  # libcosim's time: integer ns
    sweep = execution.add_local_slave(CosimLocalSlave(fmu_path=str(Path(sweep_fmu).resolve()), instance_name="sweep"))
    plate = execution.add_local_slave(CosimLocalSlave(fmu_path=str(Path(plate_fmu).resolve()), instance_name="plate"))
    for name, value in SWEEP.items():
        assert execution.real_initial_value(sweep, sv[name], value), name
    assert execution.real_initial_value(plate, pv["dt"], DT)
    # returns the C status: 0 on success
    if execution.connect_real_variables(sweep, sv["base_displacement"], plate, pv["base_displacement"]) != 0:
        raise RuntimeError("libcosim could not connect sweep.base_displacement to plate.base_displacement")
    return step_and_observe(execution, plate, pv["corner_1"], round(stop / h))


def step_and_observe(execution, plate, corner_vr, steps):
    """Steps a libcosim execution; the plate's corner_1 after every step."""
    from libcosimpy.CosimObserver import CosimObserver

    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    out = np.empty(steps)
    for k in range(steps):
        if not execution.step():
            raise RuntimeError(f"libcosim step {k} failed: {execution.status()}")
        out[k] = observer.last_real_values(plate, [corner_vr])[0]
    return out


def make_ssp(sweep_fmu, plate_fmu, target, ssd):
    """The system structure file `ssd` (examples/system_model.ssd) with the two built FMUs,
    zipped into an SSP file at `target`."""
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as ssp:
        ssp.write(ssd, "SystemStructure.ssd")
        ssp.write(sweep_fmu, "resources/SineSweep.fmu")
        ssp.write(plate_fmu, "resources/PlateImpact.fmu")
    return target


def run_libcosim_ssp(ssp, h, stop):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level

    log_output_level(CosimLogLevel.ERROR)
    unpacked = Path(tempfile.mkdtemp())
    try:
        with zipfile.ZipFile(ssp) as archive:
            archive.extractall(unpacked)
        execution = CosimExecution.from_ssp_file(str(unpacked), round(h * 1e9))
        plate = execution.slave_index_from_instance_name("plate")
        corner = [v.reference for v in execution.slave_variables(plate) if v.name.decode() == "corner_1"][0]
        return step_and_observe(execution, plate, corner, round(stop / h))
    finally:
        shutil.rmtree(unpacked, ignore_errors=True)


def run_fmpy_ssp(ssp, h, stop):
    """fmpy's SSP master reads the component's parameter bindings but applies only the
    parameter set it is given, with names prefixed by the component: pass the bindings so."""
    from types import SimpleNamespace

    from fmpy.ssp.simulation import simulate_ssp
    from fmpy.ssp.ssd import read_ssd

    ssd = read_ssd(str(ssp))
    parameters = [
        SimpleNamespace(name=f"{c.name}.{p.name}", value=p.value)
        for c in ssd.system.elements
        for b in c.parameterBindings
        for s in b.parameterValues
        for p in s.parameters
    ]
    n = round(stop / h)
    result = simulate_ssp(
        str(ssp), stop_time=n * h - 0.5 * h, step_size=h, parameter_set=SimpleNamespace(parameters=parameters)
    )
    return np.asarray(result["plate.corner_1"][:n])
