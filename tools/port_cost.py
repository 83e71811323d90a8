"""What the port's outputs (docs/theory.md §14) cost per step, measured in one run: plate_bench on
the default scene reading the ordinary outputs every communication step (port=0) and the port's
too (port=1), optionally beside a baseline plate_bench built from a commit before the port
(--baseline), interleaved rounds, the best of each. Prints the numbers and the ratios; --json
writes them (docs/port_cost.json: the table of docs/performance.md, "The port's outputs").

    .venv/bin/python tools/port_cost.py --bench build/solver/bench/plate_bench \\
        [--baseline /tmp/old/build/solver/bench/plate_bench] [--json docs/port_cost.json]
    .venv/bin/python tools/render_docs.py performance.md
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import time

COMMUNICATION_STEP = 1e-4  # s, plate_bench's default (comm=)
NOT_READ, READ = "port outputs not read", "port outputs read every communication step"


def bench_run(bench, steps, extra=()):
    out = subprocess.run(
        [bench, f"steps={steps}", "floor_repeats=200", *extra], check=True, capture_output=True, text=True
    ).stdout
    return json.loads(out)


def step_cpu_us(bench, steps, extra=()):
    return 1e6 * bench_run(bench, steps, extra)["step_cpu_s"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default="build/solver/bench/plate_bench")
    ap.add_argument("--baseline", help="plate_bench of a commit before the port")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--steps", type=int, default=50000)
    ap.add_argument("--json", help="also write the numbers here (docs/port_cost.json)")
    args = ap.parse_args(argv)
    runs = {NOT_READ: (args.bench, ()), READ: (args.bench, ("port=1",))}
    if args.baseline:
        runs = {"before the port": (args.baseline, ()), **runs}
    best = {name: float("inf") for name in runs}
    for _ in range(args.rounds):
        for name, (bench, extra) in runs.items():
            best[name] = min(best[name], step_cpu_us(bench, args.steps, extra))
    reference = best.get("before the port", best[NOT_READ])
    for name, us in best.items():
        print(f"{name:>44}: {us:.3f} us/step (CPU, best of {args.rounds}), ratio {us / reference:.3f}")
    dt = bench_run(args.bench, 1)["dt"]
    per_comm = round(COMMUNICATION_STEP / dt)
    read_us = (best[READ] - best[NOT_READ]) * per_comm
    print(f"reading the port: {read_us:.1f} us per communication step of {COMMUNICATION_STEP:g} s ({per_comm} steps)")
    if args.json:
        data = {
            "command": "tools/port_cost.py" + (" --baseline ..." if args.baseline else ""),
            "rounds": args.rounds,
            "steps": args.steps,
            "dt": dt,
            "communication_step": COMMUNICATION_STEP,
            "steps_per_communication_step": per_comm,
            "rows": [{"run": name, "step_us": us, "ratio": us / reference} for name, us in best.items()],
            "reference": "before the port" if "before the port" in best else NOT_READ,
            "read_us_per_communication_step": read_us,
            "read_over_not_read": best[READ] / best[NOT_READ],
            "commit": subprocess.run(
                ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True
            ).stdout.strip(),
            "load_average": os.getloadavg()[0],
            "date": time.strftime("%Y-%m-%d"),
        }
        with open(args.json, "w") as f:
            json.dump(data, f, indent=1)
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
