"""A real system model: SineSweep.fmu drives the clamp of PlateImpact.fmu, connected by a
co-simulation master (libcosimpy: its execution, slaves and connections API; and the same system
as an SSP file, run by libcosim and by fmpy's SSP master).

    bash run.sh                                   # builds build/SineSweep.fmu and build/PlateImpact.fmu
    .venv/bin/python examples/system_model.py     # prints the accuracy table, writes out/system_model.csv

The sweep is set to the smooth-start scene of docs/input-accuracy.md (0.09 m at 10 Hz, sin²
ramp-in over 0.05 s), so the coupled run is compared with the run whose base is exact at every
internal step (our driver with value and derivatives at h = dt). The masters pass the sweep's
output as a value at each communication point and nothing else (libcosim and fmpy's SSP master
never call fmi2GetRealOutputDerivatives / fmi2SetRealInputDerivatives): the plate reconstructs
the clamp motion inside each step (base_input_mode, default quadratic).

Use it as a template: swap the sweep for your controller FMU and keep the connection
base_displacement -> base_displacement.
"""
from __future__ import annotations

import argparse
import csv
import shutil
import sys
import tempfile
import zipfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from input_accuracy import DT, FIRST_IMPACT, errors, run_derivatives  # noqa: E402

HERE = Path(__file__).resolve().parent
# The sweep's parameters for the smooth-start scene (a constant 10 Hz with a 0.05 s ramp-in).
SWEEP = {"amplitude": 0.09, "start_frequency": 10.0, "end_frequency": 10.0, "duration": 1.0, "ramp_time": 0.05}


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


def make_ssp(sweep_fmu, plate_fmu, target):
    """examples/system_model.ssd with the two built FMUs, zipped into an SSP file."""
    with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as ssp:
        ssp.write(HERE / "system_model.ssd", "SystemStructure.ssd")
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
    parameters = [SimpleNamespace(name=f"{c.name}.{p.name}", value=p.value)
                  for c in ssd.system.elements for b in c.parameterBindings
                  for s in b.parameterValues for p in s.parameters]
    n = round(stop / h)
    result = simulate_ssp(str(ssp), stop_time=n * h - 0.5 * h, step_size=h,
                          parameter_set=SimpleNamespace(parameters=parameters))
    return np.asarray(result["plate.corner_1"][:n])


def measure(sweep_fmu, plate_fmu, steps, stop, masters):
    ssp = make_ssp(sweep_fmu, plate_fmu, Path(tempfile.mkdtemp()) / "SineSweepPlate.ssp")
    ref = run_derivatives(plate_fmu, "smooth", DT, stop)
    rows, traces = [], {}
    for h in steps:
        for master in masters:
            try:
                if master == "libcosimpy (API)":
                    run = run_libcosim(sweep_fmu, plate_fmu, h, stop)
                elif master == "libcosimpy (SSP)":
                    run = run_libcosim_ssp(ssp, h, stop)
                else:
                    run = run_fmpy_ssp(ssp, h, stop)
            except Exception as e:  # a master that cannot run this system is reported, not hidden
                rows.append({"h": h, "master": master, "before": None, "whole": None, "note": str(e)[:120]})
                print(f"h = {h:g} {master}: FAILED: {e}", file=sys.stderr)
                continue
            before, whole = errors(run, ref, h, "smooth")
            rows.append({"h": h, "master": master, "before": before, "whole": whole, "note": ""})
            traces[(h, master)] = run
            print(f"h = {h:g} {master:18s} before first impact {before:.2e} m, over {stop:g} s {whole:.2e} m",
                  file=sys.stderr)
    shutil.rmtree(ssp.parent, ignore_errors=True)
    return rows, traces, ref


def table(rows, stop):
    lines = [f"| communication step h | master | max error before first impact ({FIRST_IMPACT['smooth']:g} s) | "
             f"max error over {stop:g} s |", "|---|---|---|---|"]
    for r in rows:
        if r["before"] is None:
            lines.append(f"| {r['h']:g} s | {r['master']} | failed: {r['note']} | |")
        else:
            lines.append(f"| {r['h']:g} s | {r['master']} | {r['before']:.2e} m | {r['whole']:.2e} m |")
    return "\n".join(lines)


HEADER = """# The two-FMU system model: what each master passes, and the accuracy it reaches

Generated by `examples/system_model.py --markdown docs/system-model.md`. SineSweep.fmu (0.09 m at
10 Hz with a 0.05 s sin² ramp-in: the smooth-start scene of docs/input-accuracy.md) drives the
clamp of PlateImpact.fmu (default plate, Δt = 1e-5 s). Error = max |corner_1 − reference| over the
communication points, the reference being the plate alone with its base exact at every internal
step.

What the masters pass: libcosim (through its execution/connections API and through
`CosimExecution.from_ssp_file`) and fmpy's SSP master (`fmpy.ssp.simulation.simulate_ssp`) pass
the sweep's output value at each communication point and nothing else — none of them calls
`fmi2GetRealOutputDerivatives` on the sweep (which offers order 2) or
`fmi2SetRealInputDerivatives` on the plate. The plate therefore reconstructs the clamp motion
(default `base_input_mode = quadratic`), and every master reaches the same numbers as
`fmpy.simulate_fmu` with held values in docs/input-accuracy.md. fmpy's SSP master applies
parameter bindings only when given as a parameter set (the script passes the SSD's bindings so).

""" + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sweep-fmu", default="build/SineSweep.fmu")
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--steps", default="1e-4,1e-3", help="communication steps, s")
    ap.add_argument("--stop-time", type=float, default=0.15)
    ap.add_argument("--masters", default="libcosimpy (API),libcosimpy (SSP),fmpy (SSP)")
    ap.add_argument("--out", default="out")
    ap.add_argument("--markdown", help="write the table to this file")
    args = ap.parse_args(argv)
    steps = [float(s) for s in args.steps.split(",")]
    rows, traces, ref = measure(args.sweep_fmu, args.fmu, steps, args.stop_time, args.masters.split(","))
    text = table(rows, args.stop_time)
    print(text)
    if args.markdown:
        Path(args.markdown).write_text(HEADER + text + "\n")
    if traces:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        (h, master), run = next(iter(traces.items()))
        with (out / "system_model.csv").open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["time", "corner_1", "corner_1_reference"])
            stride = round(h / DT)
            for k, c in enumerate(run):
                w.writerow([(k + 1) * h, c, ref[(k + 1) * stride - 1]])
        print(f"wrote {out / 'system_model.csv'} ({master}, h = {h:g} s)")
    return rows


if __name__ == "__main__":
    main()
