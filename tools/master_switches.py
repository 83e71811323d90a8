"""On demand (not in the suite): the FMU as built in two masters that ignore FMI Enumerations,
ecospy (Equinor's ecos) and mosaik-fmi (fmipp). Each sets the Integer switches element = 2 (fvs)
and base_drive = 2 (velocity) on the unmodified build/PlateImpact.fmu (an ecos parameter set;
mosaik-fmi's create(**params) before initialization), drives base_velocity = d/dt 0.09 sin(2 pi 10 t)
in steps of 1e-4 s for 0.1 s (through impacts), reads the switches back and compares corner_1 at
every step with fmpy's FMU2Slave fed the same values.

    python -m venv /tmp/vm && /tmp/vm/bin/pip install ecospy fmpy numpy
    apt-get install libtbb12          # ecos's native library needs it
    /tmp/vm/bin/python tools/master_switches.py build/PlateImpact.fmu

mosaik-fmi 1.1.0 needs fmipp 2.1.0, whose build wants SWIG, Boost and the pre-6 SUNDIALS API
(Debian ships 6.x): build it without its ODE integrators (Model Exchange only) —
apt-get install swig libboost-filesystem-dev libboost-system-dev; pip download --no-binary :all:
--no-deps fmipp; in its setup.py drop the USE_SUNDIALS macro, -DUSE_SUNDIALS and the two
-lsundials_* libraries; pip install the folder, then pip install mosaik-fmi. Without it the script
runs ecos only.

Measured (ecospy 0.7.2, mosaik-fmi 1.1.0 over fmipp 2.1.0): both read element 2, base_drive 2
back; max |corner_1 - fmpy| = 0.0 in both with max |corner_1| = 0.1 m (the obstacle)."""

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


def with_mosaik(fmu):
    """mosaik-fmi's FmuAdapter driven as mosaik would: parameters at create, the input per step."""
    from mosaik_components.fmi.mosaik_fmi import FmuAdapter

    sim = FmuAdapter()
    sim.init(
        "S0",
        work_dir=str(fmu.parent),
        fmu_name=fmu.stem,
        fmi_type="cs",
        instance_name="plate",
        step_size=1,
        step_factor=H,
        logging_on=False,
    )
    [entity] = sim.create(1, "plate", element=2, base_drive=2)
    eid = entity["eid"]
    out = []
    for k in range(STEPS):
        sim.step(k, {eid: {"base_velocity": {"src": base_velocity(k * H)}}})
        out.append(sim.get_value(eid, "corner_1"))
    slave = sim._entities[eid]
    return (slave.getIntegerValue("element"), slave.getIntegerValue("base_drive")), np.array(out)


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
    reference = with_fmpy(fmu)
    masters = {"ecos": with_ecos}
    try:
        import mosaik_components.fmi.mosaik_fmi  # noqa: F401
    except ImportError:
        print("mosaik-fmi not installed (see the docstring): ecos only")
    else:
        masters["mosaik-fmi"] = with_mosaik
    ok = True
    for name, run in masters.items():
        with tempfile.TemporaryDirectory() as tmp:  # each master unpacks beside the file
            copy = Path(tmp) / fmu.name
            shutil.copy(fmu, copy)
            (element, base_drive), corner = run(copy)
        print(
            f"{name}: element = {element}, base_drive = {base_drive}; max |corner_1 - fmpy| = "
            f"{np.max(np.abs(corner - reference)):.3g} m, max |corner_1| = {np.max(np.abs(reference)):.3g} m"
        )
        ok &= (element, base_drive) == (2, 2)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
