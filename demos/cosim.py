"""The two-FMU system model (SineSweep.fmu driving PlateImpact.fmu's clamp) run by real masters:
libcosimpy's execution/connections API, and an SSP file (demos/system_model.ssd) run by
libcosim and by fmpy's SSP master. Each runner returns corner_1 of the plate after every
communication step (demos/system_model.py is the command line)."""

from __future__ import annotations

import shutil
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from plateimpact.fmufile import fmu_file
from plateimpact.scenes import AMPLITUDE, DT, FREQUENCY, RAMP

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

    sweep_fmu, plate_fmu = fmu_file(sweep_fmu), fmu_file(plate_fmu)  # checked before any master sees them
    log_output_level(CosimLogLevel.ERROR)
    sv, pv = variables(sweep_fmu), variables(plate_fmu)
    execution = CosimExecution.from_step_size(round(h * 1e9))  # libcosim's time: integer ns
    sweep = execution.add_local_slave(CosimLocalSlave(fmu_path=str(sweep_fmu), instance_name="sweep"))
    plate = execution.add_local_slave(CosimLocalSlave(fmu_path=str(plate_fmu), instance_name="plate"))
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
    """The system structure file `ssd` (demos/system_model.ssd) with the two built FMUs,
    zipped into an SSP file at `target`."""
    sweep_fmu, plate_fmu = fmu_file(sweep_fmu), fmu_file(plate_fmu)
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


# ---------------------------------------------------------------------------------------------
# The two-way system model (issue 20, item 4; demos/shaker.py): SineSweep.fmu's signal is the
# drive force of Shaker.fmu, whose armature carries PlateImpact's clamp (armature_velocity ->
# base_velocity, base_drive = velocity) and feels the plate (clamp_force -> plate_force).

# What each slave's step is recorded with (Real; the plate's impact counters are Integers).
SHAKER_RECORD = (
    "armature_displacement",
    "armature_velocity",
    "armature_acceleration",
    "energy",
    "drive_work",
    "plate_work",
    "damper_loss",
    "drive_force",
    "plate_force",
)
PLATE_RECORD = (
    "clamp_force",
    "clamp_displacement",
    "clamp_acceleration",
    "corner_1",
    "energy",
    "energy_input",
    "energy_dissipated",
    "energy_damped",
    "contact_force_lower",
    "contact_force_upper",
)
PLATE_COUNTERS = ("impacts_lower", "impacts_upper", "contact_onsets_lower", "contact_onsets_upper")
BASE_DRIVE_VELOCITY = 2  # PlateImpact's base_drive switch: 2 = velocity


def _set_initial_values(execution, slave, vrs, values):
    for name, value in values.items():
        if isinstance(value, int) and not isinstance(value, bool):
            ok = execution.integer_initial_value(slave, vrs[name], value)
        else:
            ok = execution.real_initial_value(slave, vrs[name], float(value))
        if not ok:
            raise RuntimeError(f"libcosim refused the initial value {name} = {value}")


def _connect(execution, source, source_vr, target, target_vr, what):
    if execution.connect_real_variables(source, source_vr, target, target_vr) != 0:  # the C status: 0 on success
        raise RuntimeError(f"libcosim could not connect {what}")


def energy_closure(run):
    """The coupled system's energy balance over a run: drive work = shaker and plate energies +
    losses + the coupling error, the energy the port created (each side's port work has its own
    discretization): coupling_error = -(shaker.plate_work + plate.energy_input). Also each
    FMU's own ledger residual (roundoff)."""
    drive = run["shaker.drive_work"]
    shaker_stored = run["shaker.energy"]
    plate_stored = run["plate.energy"]  # the plate starts at rest, unloaded: energy 0 at t = 0
    losses = run["shaker.damper_loss"] + run["plate.energy_dissipated"] + run["plate.energy_damped"]
    coupling = -(run["shaker.plate_work"] + run["plate.energy_input"])
    return {
        "drive_work": drive,
        "stored": shaker_stored + plate_stored,
        "losses": losses,
        "coupling_error": coupling,
        "closure": drive - (shaker_stored + plate_stored + losses),
        "shaker_ledger": shaker_stored - (drive + run["shaker.plate_work"] - run["shaker.damper_loss"]),
        "plate_ledger": plate_stored
        - (run["plate.energy_input"] - run["plate.energy_dissipated"] - run["plate.energy_damped"]),
    }


# ---------------------------------------------------------------------------------------------
# The shaker system with a choice of coupling (issue 27; docs/theory.md §18–19, demos/shaker.py):
#   "force"      Shaker.fmu <-> PlateImpact.fmu, motion in / force out with held values (as above);
#   "tlm"        Shaker.fmu <-> PlateImpact.fmu through a transmission line: each side sends its mean
#                outgoing wave (tlm_wave_out -> the partner's tlm_wave_in), both with tlm_impedance;
#   "monolithic" PlateImpact.fmu alone with the armature inside (base_drive = force), the sweep
#                driving its drive_force: the exact coupling, the reference.
# `values` maps "sweep", "shaker", "plate" to initial values; the shaker's mass, stiffness and
# damping become the plate's armature_* in the monolithic run.

COUPLINGS = ("force", "tlm", "monolithic")
BASE_DRIVE = {"force": 4, "tlm": 5}  # PlateImpact's base_drive items for a carried clamp
SYSTEM_RECORD = {
    "force": {"shaker": SHAKER_RECORD, "plate": PLATE_RECORD},
    "tlm": {
        "shaker": SHAKER_RECORD + ("tlm_wave_out", "tlm_transit", "tlm_line_loss"),
        "plate": PLATE_RECORD + ("tlm_wave_out", "tlm_transit", "tlm_line_loss"),
    },
    "monolithic": {
        "plate": PLATE_RECORD + ("armature_energy", "armature_drive_work", "armature_damped", "armature_port_work")
    },
}


def system_plan(values, coupling):
    """What a master must build for the shaker system with `coupling` (COUPLINGS), whatever the
    master: the slaves in order, each one's initial values (the switches as Integers), and the
    connections (source slave, output, target slave, input)."""
    if coupling not in COUPLINGS:
        raise ValueError(f"coupling = {coupling!r}; allowed: {', '.join(COUPLINGS)}")
    plate_values = dict(values.get("plate", {}))
    shaker_values = dict(values.get("shaker", {}))
    if coupling == "monolithic":
        plate_values["base_drive"] = BASE_DRIVE["force"]
        for key in ("mass", "stiffness", "damping"):
            if key in shaker_values:
                plate_values[f"armature_{key}"] = shaker_values[key]
    elif coupling == "tlm":
        plate_values["base_drive"] = BASE_DRIVE["tlm"]
        shaker_values["coupling"] = 2
        impedance = shaker_values.get("tlm_impedance", plate_values.get("tlm_impedance"))
        if impedance is not None:
            shaker_values["tlm_impedance"] = plate_values["tlm_impedance"] = impedance
    else:
        plate_values["base_drive"] = BASE_DRIVE_VELOCITY
    if coupling != "tlm":  # the line's impedance means nothing to the other couplings
        plate_values.pop("tlm_impedance", None)
        shaker_values.pop("tlm_impedance", None)
    if coupling == "monolithic":
        slaves = {"sweep": dict(values.get("sweep", {})), "plate": plate_values}
        connections = [("sweep", "base_displacement", "plate", "drive_force")]
    else:
        slaves = {"sweep": dict(values.get("sweep", {})), "shaker": shaker_values, "plate": plate_values}
        connections = [("sweep", "base_displacement", "shaker", "drive_force")]
        if coupling == "tlm":
            connections += [
                ("shaker", "tlm_wave_out", "plate", "tlm_wave_in"),
                ("plate", "tlm_wave_out", "shaker", "tlm_wave_in"),
            ]
        else:
            connections += [
                ("shaker", "armature_velocity", "plate", "base_velocity"),
                ("plate", "clamp_force", "shaker", "plate_force"),
            ]
    return slaves, connections


def system_execution(fmus, values, coupling, h=None, ecco=None):
    """A libcosim execution of the shaker system with `coupling` (COUPLINGS); fixed step `h` or
    ECCO (force coupling only: its power bond is velocity/force). Returns ((execution,
    algorithm), observer, slaves, value references)."""
    from libcosimpy.CosimAlgorithm import CosimAlgorithm, EccoParams
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    plan, connections = system_plan(values, coupling)
    fmus = {name: fmu_file(fmus[name]) for name in plan}  # every file checked before libcosim sees one
    if ecco is not None and coupling != "force":
        raise ValueError("ECCO runs the force coupling only (its power bond pairs a velocity with a force)")
    log_output_level(CosimLogLevel.ERROR)
    algorithm = None
    if ecco is None:
        execution = CosimExecution.from_step_size(round(h * 1e9))  # libcosim's time: integer ns
    else:
        algorithm = CosimAlgorithm.create_ecco_algorithm(EccoParams(**ecco))
        execution = CosimExecution.from_algorithm(algorithm)
    slaves = {
        name: execution.add_local_slave(CosimLocalSlave(fmu_path=str(fmus[name]), instance_name=name)) for name in plan
    }
    vrs = {name: variables(fmus[name]) for name in plan}
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    for name, initial in plan.items():
        _set_initial_values(execution, slaves[name], vrs[name], initial)
    for source, output, target, input_ in connections:
        _connect(
            execution,
            slaves[source],
            vrs[source][output],
            slaves[target],
            vrs[target][input_],
            f"{source}.{output} -> {target}.{input_}",
        )
    if algorithm is not None:
        shaker, s, plate, p = slaves["shaker"], vrs["shaker"], slaves["plate"], vrs["plate"]
        if (
            algorithm.add_power_bond(
                shaker, s["armature_velocity"], s["plate_force"], plate, p["clamp_force"], p["base_velocity"]
            )
            != 0
        ):
            raise RuntimeError("libcosim could not add the power bond")
    return (execution, algorithm), observer, slaves, vrs


def system_ssd(fmus, values, coupling, stop):
    """The shaker system with `coupling` as an SSP 1.0 system structure (text of
    SystemStructure.ssd): the components (resources/<slave>.fmu) with their initial values as
    parameter bindings, a connector for every connection end and every recorded output
    (SYSTEM_RECORD, the impact counters), and the connections."""
    from xml.sax.saxutils import quoteattr

    plan, connections = system_plan(values, coupling)
    record = {name: list(SYSTEM_RECORD[coupling].get(name, ())) for name in plan}
    record["plate"] += list(PLATE_COUNTERS)
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<ssd:SystemStructureDescription version="1.0" name="Shaker_{coupling}"',
        '    xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon"',
        '    xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription"',
        '    xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues">',
        f'  <ssd:System name="Shaker_{coupling}">',
        "    <ssd:Elements>",
    ]
    for name, initial in plan.items():
        kinds = {}
        for source, output, target, input_ in connections:
            if source == name:
                kinds[output] = "output"
            if target == name:
                kinds[input_] = "input"
        for output in record[name]:
            kinds.setdefault(output, "output")
        lines.append(
            f'      <ssd:Component name="{name}" source="resources/{name}.fmu" type="application/x-fmu-sharedlibrary">'
        )
        lines.append("        <ssd:Connectors>")
        for connector, kind in kinds.items():
            element = "ssc:Integer" if connector in PLATE_COUNTERS else "ssc:Real"
            lines.append(f'          <ssd:Connector name="{connector}" kind="{kind}"><{element}/></ssd:Connector>')
        lines.append("        </ssd:Connectors>")
        lines.append("        <ssd:ParameterBindings><ssd:ParameterBinding><ssd:ParameterValues>")
        lines.append(f'          <ssv:ParameterSet version="1.0" name="{name}"><ssv:Parameters>')
        for key, value in initial.items():
            integer = isinstance(value, int) and not isinstance(value, bool)
            typed = f'<ssv:Integer value="{value}"/>' if integer else f'<ssv:Real value="{float(value)!r}"/>'
            lines.append(f"            <ssv:Parameter name={quoteattr(key)}>{typed}</ssv:Parameter>")
        lines.append("          </ssv:Parameters></ssv:ParameterSet>")
        lines.append("        </ssd:ParameterValues></ssd:ParameterBinding></ssd:ParameterBindings>")
        lines.append("      </ssd:Component>")
    lines.append("    </ssd:Elements>")
    lines.append("    <ssd:Connections>")
    for source, output, target, input_ in connections:
        lines.append(
            f'      <ssd:Connection startElement="{source}" startConnector="{output}" '
            f'endElement="{target}" endConnector="{input_}"/>'
        )
    lines += [
        "    </ssd:Connections>",
        "  </ssd:System>",
        f'  <ssd:DefaultExperiment startTime="0" stopTime="{stop!r}"/>',
    ]
    lines.append("</ssd:SystemStructureDescription>")
    return "\n".join(lines) + "\n"


def run_system_fmpy_ssp(fmus, values, stop, coupling, h):
    """The shaker system with `coupling` (not ECCO) as an SSP file (system_ssd) run by fmpy's
    SSP master (fixed step h, held values, every slave stepped from the values of the last
    communication point): the same dict as run_system. fmpy's master applies the parameter
    bindings only when passed as its parameter set (run_fmpy_ssp), so they go both ways."""
    from types import SimpleNamespace

    from fmpy.ssp.simulation import simulate_ssp

    plan, _ = system_plan(values, coupling)
    folder = Path(tempfile.mkdtemp())
    try:
        ssp = folder / f"Shaker_{coupling}.ssp"
        with zipfile.ZipFile(ssp, "w", zipfile.ZIP_DEFLATED) as archive:
            archive.writestr("SystemStructure.ssd", system_ssd(fmus, values, coupling, stop))
            for name in plan:
                archive.write(fmus[name], f"resources/{name}.fmu")
        parameters = [
            SimpleNamespace(name=f"{n}.{k}", value=v) for n, initial in plan.items() for k, v in initial.items()
        ]
        n = round(stop / h)
        result = simulate_ssp(
            str(ssp), stop_time=n * h - 0.5 * h, step_size=h, parameter_set=SimpleNamespace(parameters=parameters)
        )
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    run = {"time": np.asarray(result["time"][:n]) + h}  # fmpy stamps a row with the step's start
    for slave, names in SYSTEM_RECORD[coupling].items():
        for name in names:
            run[f"{slave}.{name}"] = np.asarray(result[f"{slave}.{name}"][:n], dtype=float)
    for name in PLATE_COUNTERS:
        run[f"plate.{name}"] = np.asarray(result[f"plate.{name}"][:n], dtype=float)
    return run


def run_system(fmus, values, stop, coupling, h=None, ecco=None):
    """Runs the shaker system with `coupling` to `stop` (s); a dict of arrays over the
    communication points: "time", "<slave>.<name>" for SYSTEM_RECORD[coupling] and the plate's
    impact counters. Raises RuntimeError (with the time) if a step fails."""
    # The switches are Integer parameters: libcosim sets them on the FMU as built.
    (execution, _algorithm), observer, slaves, vrs = system_execution(fmus, values, coupling, h, ecco)
    record = SYSTEM_RECORD[coupling]
    real = [(slave, [vrs[slave][n] for n in names]) for slave, names in record.items()]
    counters = [vrs["plate"][n] for n in PLATE_COUNTERS]
    rows = []
    stop_ns = round(stop * 1e9)
    while True:
        now = execution.status().current_time
        if now >= stop_ns - (round(h * 1e9) // 2 if h else 0):
            break
        if not execution.step():
            raise RuntimeError(f"libcosim step at t = {now * 1e-9:.6f} s failed")
        row = [execution.status().current_time * 1e-9]
        for slave, refs in real:
            row += list(observer.last_real_values(slaves[slave], refs))
        row += list(observer.last_integer_values(slaves["plate"], counters))
        rows.append(row)
    data = np.array(rows)
    names = ["time"]
    for slave, fields in record.items():
        names += [f"{slave}.{n}" for n in fields]
    names += [f"plate.{n}" for n in PLATE_COUNTERS]
    return {name: data[:, i] for i, name in enumerate(names)}


def system_energy(run, coupling):
    """The coupled system's energy balance over a run (arrays over the communication points):
    drive work = stored + losses + coupling error, where for a line its energy in transit counts
    as stored and its loss (what the mean waves cannot carry, >= 0) as a loss; `ledgers` is the
    largest residual of the FMUs' own ledgers (roundoff)."""
    if coupling == "monolithic":
        drive = run["plate.armature_drive_work"]
        stored = run["plate.energy"] + run["plate.armature_energy"]
        losses = run["plate.armature_damped"] + run["plate.energy_dissipated"] + run["plate.energy_damped"]
        # The armature's port work is the plate's energy input with the sign turned: no error by construction.
        coupling_error = -(run["plate.armature_port_work"] + run["plate.energy_input"])
        line = np.zeros_like(drive)
        line_loss = np.zeros_like(drive)
        ledgers = np.abs(stored - (drive - losses - coupling_error)).max()
    else:
        e = energy_closure(run)
        drive, losses = e["drive_work"], e["losses"]
        stored = e["stored"]
        coupling_error = e["coupling_error"]
        ledgers = max(np.abs(e["shaker_ledger"]).max(), np.abs(e["plate_ledger"]).max())
        if coupling == "tlm":
            line = run["shaker.tlm_transit"] + run["plate.tlm_transit"]
            line_loss = run["shaker.tlm_line_loss"] + run["plate.tlm_line_loss"]
            coupling_error = coupling_error - (line + line_loss)
        else:
            line = np.zeros_like(drive)
            line_loss = np.zeros_like(drive)
    return {
        "drive_work": drive,
        "stored": stored,
        "line": line,
        "line_loss": line_loss,
        "losses": losses,
        "coupling_error": coupling_error,
        "ledgers": ledgers,
    }
