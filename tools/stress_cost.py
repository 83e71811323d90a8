"""What the stress and the probes (docs/theory.md §23) cost per step, measured in one run: plate_bench
on a scene reading the ordinary outputs every communication step of 1e-4 s with the recovery off
(the defaults: "off"), on but nothing of it read (stress=1 probes=4: the root's peak tracked every
step, "on, nothing read"), the probes and root_stress read too (field=1: "points read"), and
everything — max_stress and the vertex_stress array as well (field=2: "all read") — beside a
plate_bench built from a commit before them (--baseline), interleaved rounds, the best of each.
Prints the numbers and the ratios.

    .venv/bin/python tools/stress_cost.py --bench build/solver/bench/plate_bench \\
        --baseline /tmp/old/build/solver/bench/plate_bench [--scene element=fvs ...]
"""

from __future__ import annotations

import argparse

from port_cost import step_cpu_us


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default="build/solver/bench/plate_bench")
    ap.add_argument("--baseline", help="plate_bench of a commit before the stress outputs")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--steps", type=int, default=50000)
    ap.add_argument("--scene", nargs="*", default=[], help="plate_bench key=value pairs of the scene")
    args = ap.parse_args(argv)
    scene = tuple(args.scene)
    on = (*scene, "stress=1", "probes=4")
    runs = {
        "off": (args.bench, scene),
        "on, nothing read": (args.bench, on),
        "points read": (args.bench, (*on, "field=1")),
        "all read": (args.bench, (*on, "field=2")),
    }
    if args.baseline:
        runs = {"before": (args.baseline, scene), **runs}
    best = {name: float("inf") for name in runs}
    for _ in range(args.rounds):
        for name, (bench, extra) in runs.items():
            best[name] = min(best[name], step_cpu_us(bench, args.steps, extra))
    reference = best.get("before", best["off"])
    for name, us in best.items():
        print(f"{name:>13}: {us:.3f} us/step (CPU, best of {args.rounds}), ratio {us / reference:.3f}")


if __name__ == "__main__":
    main()
