"""The two-FMU system model: SineSweep.fmu (the controller) drives PlateImpact.fmu's clamp.

- SineSweep's output derivatives (fmi2GetRealOutputDerivatives, maxOutputDerivativeOrder = 2)
  are the derivatives of its output: checked against central differences of the output itself
  (error O(δ²), bounded below by a justified tolerance), for both sweep laws with a ramp-in;
- its bad parameters are rejected with the allowed range in the log;
- the coupled system through libcosimpy (execution, slaves, connections) and through the SSP
  file with libcosim's and fmpy's SSP masters runs and reaches, before the first impact, the
  accuracy of the held-input reconstruction measured in docs/input-accuracy.md (smooth scene,
  h = 1e-4: 1.15e-7 m; the bound 2e-7 m is the issue's goal, 1.7× above the measurement).
"""

from pathlib import Path

import cosim
import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
from fmpy.validation import validate_fmu
from fmpy_callbacks import callbacks as own_callbacks

from plateimpact.scenes import AMPLITUDE, DT, errors, run_derivatives

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def sweep_fmu(fmu_path):
    path = fmu_path.parent / "SineSweep.fmu"
    assert path.is_file(), f"SineSweep.fmu not built next to {fmu_path}"
    return path


def sweep_instance(path, **parameters):
    md = read_model_description(str(path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(path)), modelIdentifier="SineSweep", instanceName="sweep")
    # Callbacks of the instance's own, kept alive with it (fmpy_callbacks.py says why).
    callbacks = own_callbacks(lambda *args: None)
    fmu.keepAlive = callbacks
    fmu.instantiate(callbacks=callbacks)
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    for name, value in parameters.items():
        if name == "law":
            fmu.setInteger([vr[name]], [value])
        else:
            fmu.setReal([vr[name]], [value])
    fmu.exitInitializationMode()
    return fmu, vr


def test_sweep_fmu_validates(sweep_fmu):
    assert validate_fmu(str(sweep_fmu)) == []


@pytest.mark.parametrize("law", [1, 2], ids=["linear", "logarithmic"])
def test_sweep_output_derivatives_are_the_derivatives_of_the_output(sweep_fmu, law):
    fmu, vr = sweep_instance(
        sweep_fmu, amplitude=AMPLITUDE, start_frequency=5.0, end_frequency=40.0, duration=0.2, law=law, ramp_time=0.05
    )
    delta, t, values, derivs = 1e-5, 0.0, [], []
    while t < 0.3:  # through the ramp, the sweep and past its end
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=delta)
        t += delta
        values.append(fmu.getReal([vr["base_displacement"]])[0])
        derivs.append(fmu.getRealOutputDerivatives([vr["base_displacement"]] * 2, [1, 2]))
    fmu.terminate()
    fmu.freeInstance()
    z, d = np.array(values), np.array(derivs)
    central1 = (z[2:] - z[:-2]) / (2 * delta)
    central2 = (z[2:] - 2 * z[1:-1] + z[:-2]) / delta**2
    # z'' jumps where the ramp ends (0.05 s) and where the sweep ends (0.2 s; the frequency's
    # slope drops to 0): central differences straddling those points are not O(δ²).
    times = delta * np.arange(2, len(z))
    smooth = (np.abs(times - 0.05) > 3 * delta) & (np.abs(times - 0.2) > 3 * delta)
    central1, central2, d = central1[smooth], central2[smooth], d[1:-1][smooth]
    # Central differences err by δ²/6 z''' and δ²/12 z'''' : with ω ≤ 2π·40 and a = 0.09,
    # |z'''| ≤ a ω³ (1 + ramp terms) ~ 2e6 and |z''''| ~ 6e8 → 3e-5 and 5e-3; roundoff of z''
    # ~ 4 eps a / δ² ~ 1e-3. Tolerances 1e-4 and 2e-2 leave a margin of about 3 over both,
    # against derivatives of size up to 23 m/s and 5.7e3 m/s².
    assert np.abs(central1 - d[:, 0]).max() < 1e-4
    assert np.abs(central2 - d[:, 1]).max() < 2e-2
    assert np.abs(d[:, 1]).max() > 1e3  # the check is not vacuous


@pytest.mark.parametrize("name, value", [("start_frequency", 0.0), ("duration", -1.0), ("ramp_time", -0.1)])
def test_sweep_rejects_bad_parameters(sweep_fmu, name, value):
    with pytest.raises(FMICallException):
        sweep_instance(sweep_fmu, **{name: value})


@pytest.mark.parametrize("master", ["libcosimpy (API)", "libcosimpy (SSP)", "fmpy (SSP)"])
def test_coupled_system_reaches_the_held_input_accuracy(sweep_fmu, fmu_path, master, tmp_path):
    pytest.importorskip("libcosimpy.CosimExecution")
    h, stop = 1e-4, 0.06
    if master == "libcosimpy (API)":
        run = cosim.run_libcosim(sweep_fmu, fmu_path, h, stop)
    else:
        ssp = cosim.make_ssp(sweep_fmu, fmu_path, tmp_path / "SineSweepPlate.ssp", REPO / "demos" / "system_model.ssd")
        run = (cosim.run_libcosim_ssp if "libcosim" in master else cosim.run_fmpy_ssp)(ssp, h, stop)
    reference = run_derivatives(fmu_path, "smooth", DT, stop)
    before, _ = errors(run, reference, h, "smooth")
    assert before <= 2e-7, before
