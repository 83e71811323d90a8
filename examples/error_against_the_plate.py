"""The error against the plate on the paper's §5.2 (docs/theory.md §26): the plate released from
its shape under 8600 Pa onto the lower obstacle, run twice with discretization_check on — the
FMU's default configuration and the cheapest one within 1e-3 m of the converged plate over the
first 0.1 s (docs/performance.md, "The error against the plate"; README, "How close to the plate").
Writes <out>/error_against_the_plate.csv (time, corner_1 and discretization_error of both) and
prints each one's estimate, its CPU and what the FMU said; --quick: the first 0.05 s, into
<out>/quick/.

The parameters a user copies: ACCURATE (the configuration), discretization_check."""

from __future__ import annotations

import argparse
import csv
import time

from plateimpact import PlateImpactFMU
from plateimpact.fmufile import output_dir, require_fmu

RELEASE = dict(initial_load=8600.0, obstacle_upper_enabled=False)  # §5.2: no input moves anything
# The cheapest configuration within 1e-3 m of the plate over §5.2's first 0.1 s
# (docs/plate_front.json, scenes.s52.choices["0.1"]; python -m plateimpact.sizing finds it for a scene).
ACCURATE = {"nx": 28, "ny": 10, "modes": 40, "time_scheme": "flow", "mass": "singular_p0", "contact_substeps": 4}
CONFIGURATIONS = {"default": {}, "accurate": ACCURATE}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--out", default="out")
    ap.add_argument("--stop-time", type=float, default=0.1)
    ap.add_argument("--step", type=float, default=5e-4, help="communication step, s")
    ap.add_argument("--quick", action="store_true", help="smoke run: --stop-time 0.05, written to <out>/quick/")
    args = ap.parse_args(argv)
    args.fmu = str(require_fmu(args.fmu, "error_against_the_plate"))
    if args.quick:
        args.stop_time = 0.05
    out = output_dir(args.out, args.quick)
    n = round(args.stop_time / args.step)
    columns = {"time": [k * args.step for k in range(n + 1)]}
    for name, config in CONFIGURATIONS.items():
        with PlateImpactFMU(args.fmu, logger=lambda *a: None, discretization_check=True, **RELEASE, **config) as plate:
            first = plate.outputs()
            corner, estimate = [first["corner_1"]], [first["discretization_error"]]
            cpu = time.process_time()
            for _ in range(n):
                o = plate.step(args.step)
                corner.append(o["corner_1"])
                estimate.append(o["discretization_error"])
            cpu = time.process_time() - cpu
            said = [m for s, _, m in plate.log if s == 1]
        columns[f"corner_1 {name}"], columns[f"discretization_error {name}"] = corner, estimate
        print(
            f"{name:8s} {config or 'the FMU default'}: discretization_error {estimate[-1]:.2e} m after "
            f"{args.stop_time:g} s, {cpu / args.stop_time:.2f} s of CPU per simulated second"
            + (f"; the FMU said: {said[0]}" if said else "")
        )
    path = out / "error_against_the_plate.csv"
    with path.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(list(columns))
        writer.writerows(zip(*columns.values()))
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
