"""Accuracy on the path users take: the clamp driven by masters that hold inputs and give no
derivatives (fmpy.simulate_fmu, libcosimpy), against our derivative-giving driver.

Two scenes on the default plate (14x5 Argyris, dt = 1e-5 s, obstacles at +-0.1 m):
  smooth  base 0.09 sin(2 pi 10 t) s(t), s = sin^2(pi t / 0.1) for t < 0.05 s, 1 after
          (z, z', z'' all start at 0: a causal master loses nothing at the start)
  paper   base 0.09 sin(2 pi 10 t) from t = 0 (a kink out of rest: c w = 5.7 m/s at t = 0+)
For each communication step h and each way of passing the base, the largest |corner_1 - ref|
over the communication points before the first impact and over 0.15 s, where ref is the run
whose base is exact at every internal step (our driver with value and derivatives at h = dt).

    python examples/input_accuracy.py --fmu build/PlateImpact.fmu [--out docs/figures]   # then tools/render_docs.py

Ways of passing the base (each a row):
  derivatives           our driver: value, first and second derivative at every point
  fmpy <mode>           fmpy.simulate_fmu with an input table (held values), base_input_mode=<mode>
  libcosimpy            libcosim with an override manipulator (held values; the default
                        base_input_mode, quadratic)
  quadratic-jumps      prototype through the derivative inputs: the quadratic extrapolation
                        without the FMU's continuity (each step starts at the communicated value,
                        so the clamp jumps by the miss at every point) — kept to show what the
                        continuity buys
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from plateimpact import PlateImpactFMU, unzipped
from plateimpact.fmufile import output_dir, require_fmu
from plateimpact.scenes import DT, FIRST_IMPACT, base, errors, run_derivatives

MODES = {"hold": 1, "linear": 2, "quadratic": 3}


def run_jumps(fmu, scene, h, stop):
    """Quadratic extrapolation of the held values, each step starting at the communicated
    value (the clamp jumps by the miss at every communication point)."""
    n = round(stop / h)
    out = np.empty(n)
    ts, zs = [], []
    with PlateImpactFMU(fmu, dt=DT) as plate:
        for k in range(n):
            t = k * h
            ts.insert(0, t)
            zs.insert(0, base(scene, t)[0])
            del ts[3:], zs[3:]
            d1 = d2 = 0.0
            if len(ts) >= 2:
                d01 = (zs[0] - zs[1]) / (ts[0] - ts[1])
                d1 = d01
                if len(ts) == 3:
                    d012 = (d01 - (zs[1] - zs[2]) / (ts[1] - ts[2])) / (ts[0] - ts[2])
                    d1 += d012 * (ts[0] - ts[1])
                    d2 = 2 * d012
            out[k] = plate.step(h, base=(zs[0], d1, d2))["corner_1"]
    return out


def run_fmpy(fmu, scene, h, stop, mode):
    from fmpy import simulate_fmu

    n = round(stop / h)
    grid = np.arange(0, round(stop / DT) + 1) * DT
    signal = np.array([(t, base(scene, t)[0]) for t in grid], dtype=[("time", float), ("base_displacement", float)])
    result = simulate_fmu(
        fmu,
        start_time=0.0,
        stop_time=n * h,
        output_interval=h,
        input=signal,
        start_values={"base_input_mode": MODES[mode], "dt": DT},
        output=["corner_1"],
        fmi_type="CoSimulation",
    )
    return np.asarray(result["corner_1"][1 : n + 1])


def run_libcosim(fmu, scene, h, stop):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    step_ns = round(h * 1e9)
    n = round(stop / h)
    _, md = unzipped(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    execution = CosimExecution.from_step_size(step_ns)
    slave = CosimLocalSlave(fmu_path=str(Path(fmu).resolve()), instance_name="plate")
    index = execution.add_local_slave(slave)
    manipulator = CosimManipulator.create_override()
    observer = CosimObserver.create_last_value()
    execution.add_manipulator(manipulator)
    execution.add_observer(observer)
    out = np.empty(n)
    for k in range(n):
        manipulator.slave_real_values(index, [vr["base_displacement"]], [base(scene, k * step_ns * 1e-9)[0]])
        if not execution.step():
            raise RuntimeError(f"libcosim step {k} failed")
        out[k] = observer.last_real_values(index, [vr["corner_1"]])[0]
    del execution, manipulator, observer, slave
    return out


def measure(fmu, steps, stop, scenes, ways):
    rows = []
    for scene in scenes:
        t0 = time.perf_counter()
        ref = run_derivatives(fmu, scene, DT, stop)
        print(f"[{scene}] reference (derivatives at h = dt): {time.perf_counter() - t0:.1f} s", file=sys.stderr)
        for h in steps:
            for way in ways:
                if way == "derivatives" and h == DT:
                    continue  # it is the reference
                t0 = time.perf_counter()
                if way == "derivatives":
                    run = run_derivatives(fmu, scene, h, stop)
                elif way == "libcosimpy":
                    run = run_libcosim(fmu, scene, h, stop)
                elif way == "quadratic-jumps":
                    run = run_jumps(fmu, scene, h, stop)
                else:
                    run = run_fmpy(fmu, scene, h, stop, way.split()[1])
                before, whole = errors(run, ref, h, scene)
                rows.append({"scene": scene, "h": h, "way": way, "before": before, "whole": whole})
                print(
                    f"[{scene}] h = {h:g} {way:16s} before first impact {before:.2e} m, "
                    f"over {stop:g} s {whole:.2e} m ({time.perf_counter() - t0:.1f} s)",
                    file=sys.stderr,
                )
    return rows


def speed(fmu, h=1e-4, stop=0.5, repeats=3):
    """CPU time per internal step of fmi2DoStep on the paper scene without obstacles at
    communication step h:
    values with derivatives (the reconstruction is skipped), values only with the default
    quadratic reconstruction, values only held. The reconstruction runs once per
    communication step, not per internal step; the ratios show whether that is measurable.
    Best of `repeats` runs each (process CPU time, robust to a shared machine)."""
    n = round(stop / h)
    samples = [base("paper", k * h) for k in range(n)]
    cases = {"derivatives": (True, 3), "quadratic (values only)": (False, 3), "hold (values only)": (False, 1)}
    best = {}
    for _ in range(repeats):
        for name, (derivatives, mode) in cases.items():
            # No obstacles: every run does the same work per internal step (no contact QPs
            # on trajectories that differ), so the ratios isolate the input handling.
            with PlateImpactFMU(
                fmu, dt=DT, base_input_mode=mode, obstacle_lower_enabled=False, obstacle_upper_enabled=False
            ) as plate:
                vr = plate.vars["base_displacement"].valueReference
                fmu2 = plate.fmu
                t0 = time.process_time()
                for k, (z, zd, zdd) in enumerate(samples):
                    fmu2.setReal([vr], [z])
                    if derivatives:
                        fmu2.setRealInputDerivatives([vr, vr], [1, 2], [zd, zdd])
                    fmu2.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
                cpu = (time.process_time() - t0) / round(stop / DT)
            best[name] = min(best.get(name, math.inf), cpu)
    return best


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--steps", default="1e-5,1e-4,1e-3", help="communication steps, s")
    ap.add_argument("--stop-time", type=float, default=0.15)
    ap.add_argument("--scenes", default="smooth,paper")
    ap.add_argument("--ways", default="derivatives,fmpy hold,fmpy linear,fmpy quadratic,libcosimpy,quadratic-jumps")
    ap.add_argument("--out", default="out", help="input_accuracy.json goes here (docs: docs/figures)")
    ap.add_argument("--quick", action="store_true", help="smoke run: smooth scene, h = 1e-3 s, 0.07 s, no cost")
    ap.add_argument("--no-speed", action="store_true", help="skip the cost measurement")
    args = ap.parse_args(argv)
    args.fmu = str(require_fmu(args.fmu, "input_accuracy"))
    steps = [1e-3] if args.quick else [float(s) for s in args.steps.split(",")]
    stop = 0.07 if args.quick else args.stop_time
    scenes = ["smooth"] if args.quick else args.scenes.split(",")
    rows = measure(args.fmu, steps, stop, scenes, args.ways.split(","))
    cost = None if args.no_speed or args.quick else speed(args.fmu)
    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never a full run's files
    data = dict(stop=stop, dt=DT, first_impact=FIRST_IMPACT, rows=rows, cost=cost)
    (out / "input_accuracy.json").write_text(json.dumps(data, indent=1))
    print(
        f"wrote {out / 'input_accuracy.json'} (docs/input-accuracy.md: --out docs/figures, then tools/render_docs.py)"
    )
    return rows


if __name__ == "__main__":
    main()
