"""A real system model: SineSweep.fmu drives the clamp of PlateImpact.fmu, connected by a
co-simulation master (libcosimpy: its execution, slaves and connections API; and the same system
as an SSP file, run by libcosim and by fmpy's SSP master).

    bash run.sh                                   # builds build/SineSweep.fmu and build/PlateImpact.fmu
    .venv/bin/python demos/system_model.py     # the accuracy per master: out/system_model.json, .csv
    .venv/bin/python demos/system_model.py --out docs/figures && .venv/bin/python tools/render_docs.py system-model.md

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
import json
import shutil
import sys
import tempfile
from pathlib import Path

from cosim import make_ssp, run_fmpy_ssp, run_libcosim, run_libcosim_ssp

from plateimpact.fmufile import output_dir
from plateimpact.scenes import DT, FIRST_IMPACT, errors, run_derivatives

HERE = Path(__file__).resolve().parent


def measure(sweep_fmu, plate_fmu, steps, stop, masters):
    ssp = make_ssp(sweep_fmu, plate_fmu, Path(tempfile.mkdtemp()) / "SineSweepPlate.ssp", HERE / "system_model.ssd")
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
            print(
                f"h = {h:g} {master:18s} before first impact {before:.2e} m, over {stop:g} s {whole:.2e} m",
                file=sys.stderr,
            )
    shutil.rmtree(ssp.parent, ignore_errors=True)
    return rows, traces, ref


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sweep-fmu", default="build/SineSweep.fmu")
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--steps", default="1e-4,1e-3", help="communication steps, s")
    ap.add_argument("--stop-time", type=float, default=0.15)
    ap.add_argument("--masters", default="libcosimpy (API),libcosimpy (SSP),fmpy (SSP)")
    ap.add_argument("--out", default="out", help="system_model.json and system_model.csv go here")
    ap.add_argument("--quick", action="store_true", help="smoke run: h = 1e-3 s, 0.07 s")
    args = ap.parse_args(argv)
    steps = [1e-3] if args.quick else [float(s) for s in args.steps.split(",")]
    stop = 0.07 if args.quick else args.stop_time
    rows, traces, ref = measure(args.sweep_fmu, args.fmu, steps, stop, args.masters.split(","))
    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never a full run's files
    data = dict(stop=stop, first_impact=FIRST_IMPACT["smooth"], dt=DT, rows=rows)
    (out / "system_model.json").write_text(json.dumps(data, indent=1))
    print(f"wrote {out / 'system_model.json'} (docs/system-model.md: --out docs/figures, then tools/render_docs.py)")
    if traces:
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
