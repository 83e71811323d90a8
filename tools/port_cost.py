"""What the port's outputs (docs/theory.md §14) cost per step, measured in one run: plate_bench on
the default scene reading the ordinary outputs every communication step (port=0) and the port's
too (port=1), optionally beside a baseline plate_bench built from a commit before the port
(--baseline), interleaved rounds, the best of each. Prints the numbers and the ratios.

    .venv/bin/python tools/port_cost.py --bench build/solver/bench/plate_bench \\
        --baseline /tmp/old/build/solver/bench/plate_bench
"""

from __future__ import annotations

import argparse
import json
import subprocess


def step_cpu_us(bench, steps, extra=()):
    out = subprocess.run(
        [bench, f"steps={steps}", "floor_repeats=200", *extra], check=True, capture_output=True, text=True
    ).stdout
    return 1e6 * json.loads(out)["step_cpu_s"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default="build/solver/bench/plate_bench")
    ap.add_argument("--baseline", help="plate_bench of a commit before the port")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--steps", type=int, default=50000)
    args = ap.parse_args(argv)
    runs = {"port not read": (args.bench, ()), "port read": (args.bench, ("port=1",))}
    if args.baseline:
        runs = {"before the port": (args.baseline, ()), **runs}
    best = {name: float("inf") for name in runs}
    for _ in range(args.rounds):
        for name, (bench, extra) in runs.items():
            best[name] = min(best[name], step_cpu_us(bench, args.steps, extra))
    reference = best.get("before the port", best["port not read"])
    for name, us in best.items():
        print(f"{name:>16}: {us:.3f} us/step (CPU, best of {args.rounds}), ratio {us / reference:.3f}")


if __name__ == "__main__":
    main()
