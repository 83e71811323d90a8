"""On demand (not in the suite): the FMU as built in a second master that ignores Enumerations,
ecospy (Equinor's ecos). Sets the Integer switches element = 2 (fvs) and base_drive = 2
(velocity) through an ecos parameter set on the unmodified build/PlateImpact.fmu, drives
base_velocity = d/dt 0.09 sin(2 pi 10 t) in steps of 1e-4 s for 0.1 s (through impacts), reads the
switches back and compares corner_1 at every step with fmpy's FMU2Slave fed the same values.

    python -m venv /tmp/vm && /tmp/vm/bin/pip install ecospy fmpy numpy
    apt-get install libtbb12          # ecos's native library needs it
    /tmp/vm/bin/python tools/ecos_switches.py build/PlateImpact.fmu

Measured (ecospy 0.7.2): element 2, base_drive 2 read back; max |corner_1 ecos - fmpy| = 0.0 with
max |corner_1| = 0.1 m (the obstacle)."""

import shutil
import sys
import tempfile
from pathlib import Path

import fmpy
import numpy as np
from ecospy import EcosSimulation, EcosSimulationStructure
from fmpy.fmi2 import FMU2Slave

H, STEPS = 1e-4, 1000


def base_velocity(t):
    return 0.09 * 2 * np.pi * 10 * np.cos(2 * np.pi * 10 * t)


def with_ecos(fmu):
    out = []
    with EcosSimulationStructure() as ss:
        ss.add_model("plate", str(fmu))
        ss.add_parameter_set("cfg", {"plate::element": 2, "plate::base_drive": 2})
        with EcosSimulation(structure=ss, step_size=H) as sim:
            sim.init(parameter_set="cfg")
            switches = sim.get_integer("plate::element"), sim.get_integer("plate::base_drive")
            for k in range(STEPS):
                sim.set_real("plate::base_velocity", base_velocity(k * H))
                sim.step()
                out.append(sim.get_real("plate::corner_1"))
            sim.terminate()
    return switches, np.array(out)


def with_fmpy(fmu):
    md = fmpy.read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    folder = fmpy.extract(str(fmu))
    s = FMU2Slave(guid=md.guid, unzipDirectory=folder, modelIdentifier="PlateImpact", instanceName="p")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.setInteger([vr["element"], vr["base_drive"]], [2, 2])
    s.enterInitializationMode()
    s.exitInitializationMode()
    out = []
    for k in range(STEPS):
        s.setReal([vr["base_velocity"]], [base_velocity(k * H)])
        s.doStep(k * H, H)
        out.append(s.getReal([vr["corner_1"]])[0])
    s.terminate()
    s.freeInstance()
    shutil.rmtree(folder, ignore_errors=True)
    return np.array(out)


def main():
    fmu = Path(sys.argv[1] if len(sys.argv) > 1 else "build/PlateImpact.fmu").resolve()
    with tempfile.TemporaryDirectory() as tmp:  # ecos unpacks beside the file
        copy = Path(tmp) / fmu.name
        shutil.copy(fmu, copy)
        (element, base_drive), ecos = with_ecos(copy)
    reference = with_fmpy(fmu)
    print(f"ecos: element = {element}, base_drive = {base_drive}")
    print(
        f"max |corner_1 ecos - fmpy| = {np.max(np.abs(ecos - reference)):.3g} m, max |corner_1| = "
        f"{np.max(np.abs(reference)):.3g} m"
    )
    return 0 if (element, base_drive) == (2, 2) else 1


if __name__ == "__main__":
    sys.exit(main())
