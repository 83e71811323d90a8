"""What the FMU's cache of discretizations saves, measured in one run (README, "Performance";
docs/instance_setup.json). Three measurements:

- the CPU an instance spends in ExitInitializationMode, first and next instances of one plate in
  one process (issue 54 asks the next ones for at most 5 % of the first one's CPU);
- the same through fmpy's simulate_fmu, in a fresh interpreter: each call extracts the FMU anew
  and loads and unloads its own copy of the library, which forwards to the process's first copy
  (fmu/core/PrimaryCopy.h; issue 71 asks the next calls for at most 5 % of the first one's CPU);
- a response map on Dask (plateimpact.response_map, as examples/frequency_response.py runs it):
  its points' setup summed and the map's wall time with the cache on and with it off
  (PLATEIMPACT_CACHE_MB=0 in the workers), and whether the two maps' results agree bit for bit.

Prints one line per instance and per map; --json FILE also writes the numbers (docs/instance_setup.json,
which tools/render_docs.py quotes in the README).

    .venv/bin/python tools/instance_setup.py [--fmu FMU] [--instances 4] [--simulate-fmu-calls 4] \\
        [--map-points 16] [--json docs/instance_setup.json] [key=value ...]
    .venv/bin/python tools/render_docs.py

key=value: parameters of the plate (nx=20 ny=7 mass=2 time_scheme=2 ...); the default plate
without any. --map-points 0 leaves the map out. PLATEIMPACT_CACHE_MB=0 in the environment turns
the cache off for the instances too (every instance then pays the first one's CPU)."""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys
import time

from checkout import add_checkout_arguments, fmu_path

from plateimpact import PlateImpactFMU

TIMING = ("wall_s", "setup_s", "plate_shared")  # a map point's fields that are not its result
SIMULATE_FMU_STOP_TIME = 0.01  # s simulated per simulate_fmu call
SHARED = re.compile(r"discretization: (\d+) of (\d+) parts shared from the process's cache")


def setup_cpu(fmu, parameters):
    """(CPU s, wall s) of one instance's ExitInitializationMode; the instance is freed after."""
    plate = PlateImpactFMU(fmu, initialize=False)
    try:
        plate.enter_initialization(parameters)
        cpu, wall = time.process_time(), time.perf_counter()
        plate.exit_initialization()
        cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    finally:
        plate.close()
    return cpu, wall


def simulate_fmu_setups(fmu, calls, parameters):
    """CPU s of ExitInitializationMode in each of `calls` simulate_fmu calls of this process (fmpy
    calls fmi_call_logger after each FMI call returns: the CPU between the call before and it),
    whether each instance shared its plate from the cache (its log line), and each whole call's CPU
    (extracting the FMU, loading its library, SIMULATE_FMU_STOP_TIME simulated)."""
    from fmpy import simulate_fmu

    cpu, shared, whole = [], [], []
    for _ in range(calls):
        start = time.process_time()
        last, exit_cpu, lines = [time.process_time()], [], []

        def calls_logged(message, last=last, exit_cpu=exit_cpu):
            now = time.process_time()
            if "ExitInitializationMode" in message:
                exit_cpu.append(now - last[0])
            last[0] = now

        simulate_fmu(
            fmu,
            stop_time=0.01,
            output_interval=1e-3,
            start_values=parameters,
            debug_logging=True,
            fmi_call_logger=calls_logged,
            logger=lambda *a, lines=lines: lines.append(str(a[-1])),
        )
        whole.append(time.process_time() - start)
        cpu.append(exit_cpu[0])
        parts = [SHARED.search(m).groups() for m in lines if SHARED.search(m)]
        shared.append(bool(parts) and parts[0][0] == parts[0][1])
    return {"cpu_s": cpu, "shared": shared, "call_cpu_s": whole, "stop_time": SIMULATE_FMU_STOP_TIME}


def simulate_fmu_in_a_new_process(fmu, calls, parameters):
    """simulate_fmu_setups in a fresh interpreter (this one has loaded the FMU already)."""
    done = subprocess.run(
        [sys.executable, __file__, "--fmu", fmu, "--simulate-fmu-child", str(calls)]
        + [f"{k}={v}" for k, v in parameters.items()],
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(done.stdout.splitlines()[-1])


def map_points(count):
    """`count` points of a frequency × gap grid (as square as it comes), the gaps above the amplitude."""
    from plateimpact.response_map import grid

    columns = math.ceil(math.sqrt(count))
    rows = math.ceil(count / columns)
    frequencies = [5.0 * (i + 1) for i in range(columns)]
    gaps = [0.02 + 0.02 * j for j in range(rows)]
    return grid(frequencies, gaps)[:count]


def timed_map(fmu, points, workers, stop_time, cache_mb):
    """The response map on a fresh LocalCluster whose workers see PLATEIMPACT_CACHE_MB=cache_mb
    (None: unset): (results, wall s from the cluster's start to the last result)."""
    from distributed import Client, LocalCluster

    from plateimpact.response_map import dask_map

    saved = os.environ.get("PLATEIMPACT_CACHE_MB")
    if cache_mb is None:
        os.environ.pop("PLATEIMPACT_CACHE_MB", None)
    else:
        os.environ["PLATEIMPACT_CACHE_MB"] = str(cache_mb)  # the worker processes inherit it
    try:
        t0 = time.perf_counter()
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        try:
            results = dask_map(client, fmu, points, progress=False, stop_time=stop_time, settle=stop_time / 2)
        finally:
            client.close()
            cluster.close()
        wall = time.perf_counter() - t0
    finally:
        if saved is None:
            os.environ.pop("PLATEIMPACT_CACHE_MB", None)
        else:
            os.environ["PLATEIMPACT_CACHE_MB"] = saved
    return results, wall


def map_summary(results, wall):
    return {
        "setup_s": sum(r["setup_s"] for r in results),
        "built": sum(not r["plate_shared"] for r in results),
        "shared": sum(bool(r["plate_shared"]) for r in results),
        "wall_s": wall,
    }


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_checkout_arguments(ap)
    ap.add_argument("--instances", type=int, default=4)
    ap.add_argument("--simulate-fmu-calls", type=int, default=4, help="simulate_fmu calls in a fresh process (0: none)")
    ap.add_argument("--simulate-fmu-child", type=int, default=0, help=argparse.SUPPRESS)
    ap.add_argument("--map-points", type=int, default=16, help="points of the response map (0: no map)")
    ap.add_argument("--map-workers", type=int, default=2, help="the map's Dask worker processes")
    ap.add_argument("--map-stop-time", type=float, default=0.1, help="s simulated per map point")
    ap.add_argument("--json", help="also write the numbers here")
    ap.add_argument("parameters", nargs="*", help="key=value")
    args = ap.parse_args(argv)
    parameters = {}
    for item in args.parameters:
        key, value = item.split("=", 1)
        parameters[key] = float(value) if "." in value or "e" in value else int(value)
    fmu = str(os.path.abspath(fmu_path(args)))
    if args.simulate_fmu_child:
        print(json.dumps(simulate_fmu_setups(fmu, args.simulate_fmu_child, parameters)))
        return 0
    runs = [setup_cpu(fmu, parameters) for _ in range(args.instances)]
    for i, (cpu, wall) in enumerate(runs):
        print(f"instance {i + 1}: ExitInitializationMode {cpu:.4f} s CPU ({wall:.4f} s wall)", flush=True)
    first, rest = runs[0][0], statistics.median(cpu for cpu, _ in runs[1:])
    print(f"next instances (median): {rest:.4f} s CPU = {100 * rest / first:.1f} % of the first one's", flush=True)
    report = {
        "command": "tools/instance_setup.py",
        "parameters": parameters,
        "cpu_s": [c for c, _ in runs],
        "wall_s": [w for _, w in runs],
        "first_cpu_s": first,
        "next_cpu_s": rest,
        "next_over_first": rest / first,
    }
    if args.simulate_fmu_calls > 1:
        sim = simulate_fmu_in_a_new_process(fmu, args.simulate_fmu_calls, parameters)
        for i, (cpu, shared, whole) in enumerate(zip(sim["cpu_s"], sim["shared"], sim["call_cpu_s"])):
            plate = "shared from the cache" if shared else "built"
            print(
                f"simulate_fmu call {i + 1}: ExitInitializationMode {cpu:.4f} s CPU, its plate {plate} "
                f"(the whole call {whole:.3f} s CPU)",
                flush=True,
            )
        first_call, next_calls = sim["cpu_s"][0], statistics.median(sim["cpu_s"][1:])
        print(
            f"next simulate_fmu calls (median): {next_calls:.4f} s CPU = {100 * next_calls / first_call:.1f} % "
            "of the first one's",
            flush=True,
        )
        report["simulate_fmu"] = {
            **sim,
            "first_cpu_s": first_call,
            "next_cpu_s": next_calls,
            "next_over_first": next_calls / first_call,
        }
    if args.map_points > 0:
        points = map_points(args.map_points)
        maps = {}
        for name, cache_mb in (("cache_on", None), ("cache_off", 0)):
            results, wall = timed_map(fmu, points, args.map_workers, args.map_stop_time, cache_mb)
            maps[name] = (results, map_summary(results, wall))
            s = maps[name][1]
            print(
                f"map, {name.replace('_', ' ')}: {len(points)} points, {s['built']} built the plate, "
                f"{s['shared']} shared it; setup {s['setup_s']:.2f} s in all, {s['wall_s']:.2f} s wall",
                flush=True,
            )
        strip = lambda rs: [{k: v for k, v in r.items() if k not in TIMING} for r in rs]  # noqa: E731
        identical = strip(maps["cache_on"][0]) == strip(maps["cache_off"][0])
        print(f"map results with and without the cache {'identical' if identical else 'DIFFER'}")
        report["map"] = {
            "points": len(points),
            "frequencies": sorted({f for f, _ in points}),
            "gaps": sorted({g for _, g in points}),
            "stop_time": args.map_stop_time,
            "workers": args.map_workers,
            "cache_on": maps["cache_on"][1],
            "cache_off": maps["cache_off"][1],
            "identical": identical,
        }
    if args.json:
        report.update(
            commit=subprocess.run(
                ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True
            ).stdout.strip(),
            date=time.strftime("%Y-%m-%d"),
            load_average=os.getloadavg()[0],
            cores=os.cpu_count(),
        )
        with open(args.json, "w") as f:
            json.dump(report, f, indent=1)
            f.write("\n")
        print(f"wrote {args.json}")
    return 0 if args.map_points == 0 or report["map"]["identical"] else 1


if __name__ == "__main__":
    sys.exit(main())
