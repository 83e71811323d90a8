"""The CPU an instance spends in ExitInitializationMode, first and next instances of one plate in
one process: what the FMU's cache of discretizations saves (README, "Performance"; issue 54 asks
the second instance for at most 5 % of the first one's CPU). Prints one line per instance and the
ratio, measured in this run; --json FILE also writes them.

    .venv/bin/python tools/instance_setup.py [--fmu FMU] [--instances 4] [key=value ...]

key=value: parameters of the plate (nx=20 ny=7 mass=2 time_scheme=2 ...); the default plate
without any. PLATEIMPACT_CACHE_MB=0 in the environment turns the cache off (every instance then
pays the first one's CPU)."""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time

from checkout import add_checkout_arguments, fmu_path

from plateimpact import PlateImpactFMU


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


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_checkout_arguments(ap)
    ap.add_argument("--instances", type=int, default=4)
    ap.add_argument("--json", help="also write the numbers here")
    ap.add_argument("parameters", nargs="*", help="key=value")
    args = ap.parse_args(argv)
    parameters = {}
    for item in args.parameters:
        key, value = item.split("=", 1)
        parameters[key] = float(value) if "." in value or "e" in value else int(value)
    fmu = fmu_path(args)
    runs = [setup_cpu(fmu, parameters) for _ in range(args.instances)]
    for i, (cpu, wall) in enumerate(runs):
        print(f"instance {i + 1}: ExitInitializationMode {cpu:.4f} s CPU ({wall:.4f} s wall)")
    first, rest = runs[0][0], statistics.median(cpu for cpu, _ in runs[1:])
    print(f"next instances (median): {rest:.4f} s CPU = {100 * rest / first:.1f} % of the first one's")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"parameters": parameters, "cpu_s": [c for c, _ in runs], "wall_s": [w for _, w in runs]}, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
