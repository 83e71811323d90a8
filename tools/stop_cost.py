"""What a stop saves (docs/theory.md §25, issue 52 item 3), measured in one run: plate_bench on the
same mesh and drive with the lower obstacle over the whole plate and as a stop under the tip
(x >= 1.0 m), for every law, interleaved rounds, the best of each. Prints the contact rows, the CPU
per simulated second of the stepping loop and the CPU of the setup (assembly, modal basis or
condensed operators, static state), and the ratios tip / whole from the same run.

The whole-plate obstacle holds the clamp too (§25): the drive must stay above its height, so the
scene is the default plate driven by 0.045 sin(2 pi 10 t) m with the lower obstacle at -0.05 m and
the upper one off; both variants hit the obstacle (contact_onsets_lower > 0 is printed).

    .venv/bin/python tools/stop_cost.py --json docs/stop_cost.json   # the numbers docs/performance.md quotes
    .venv/bin/python tools/render_docs.py performance.md            # the section "Stops"
"""

from __future__ import annotations

import argparse
import json
import subprocess
from pathlib import Path

LAWS = {
    "newmark (consistent)": ("mass=consistent",),
    "newmark sparse": ("mass=consistent", "engine=sparse"),
    "conserving (singular_p0)": ("mass=singular_p0", "scheme=conserving"),
    "flow (singular_p0)": ("mass=singular_p0", "scheme=flow"),
}
SCENE = ("amplitude=0.045", "lower=-0.05", "lower_only=1", "floor_repeats=20")
STOPS = {"whole plate": (), "tip stop": ("lower_x_min=1.0",)}


def bench(binary, steps, nx, ny, extra):
    out = subprocess.run(
        [binary, f"steps={steps}", f"nx={nx}", f"ny={ny}", *SCENE, *extra], check=True, capture_output=True, text=True
    ).stdout
    return json.loads(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default="build/solver/bench/plate_bench")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--steps", type=int, default=20000, help="internal steps of 1e-5 s (20000: 0.2 s)")
    ap.add_argument("--mesh", default="14x5", help="nx x ny (the default plate: 14x5)")
    ap.add_argument("--laws", default=",".join(LAWS), help="comma-separated subset of the laws")
    ap.add_argument("--json", type=Path, help="also write the table as JSON (docs/stop_cost.json)")
    args = ap.parse_args(argv)
    nx, ny = (int(v) for v in args.mesh.split("x"))
    laws = [law for law in args.laws.split(",") if law]
    best: dict[tuple[str, str], dict] = {}
    for _ in range(args.rounds):
        for law in laws:
            for stop, keys in STOPS.items():
                r = bench(args.bench, args.steps, nx, ny, LAWS[law] + keys)
                key = (law, stop)
                if key not in best:
                    best[key] = r
                else:
                    for field in ("step_cpu_s", "setup_cpu_s"):
                        best[key][field] = min(best[key][field], r[field])
    dt = 1e-5
    table = []
    print(f"mesh {nx}x{ny}, {args.steps} steps of {dt} s, best of {args.rounds} rounds (CPU time)")
    header = (
        f"{'law':>26} {'stop':>12} {'rows':>5} {'onsets':>6} {'engine':>16} {'CPU s/sim s':>12} {'setup CPU s':>12}"
    )
    print(header)
    for law in laws:
        for stop in STOPS:
            r = best[(law, stop)]
            print(
                f"{law:>26} {stop:>12} {r['contact_vertices']:>5} {r['contact_onsets_lower']:>6.0f} {r['engine']:>16} "
                f"{r['step_cpu_s'] / dt:>12.4f} {r['setup_cpu_s']:>12.4f}"
            )
        whole, tip = best[(law, "whole plate")], best[(law, "tip stop")]
        table.append(
            dict(
                law=law,
                engine=[whole["engine"], tip["engine"]],
                rows=[whole["contact_vertices"], tip["contact_vertices"]],
                onsets=[whole["contact_onsets_lower"], tip["contact_onsets_lower"]],
                qp_iterations=[whole["qp_iterations_total"], tip["qp_iterations_total"]],
                cpu_per_simulated_s=[whole["step_cpu_s"] / dt, tip["step_cpu_s"] / dt],
                setup_cpu_s=[whole["setup_cpu_s"], tip["setup_cpu_s"]],
                step_ratio=tip["step_cpu_s"] / whole["step_cpu_s"],
                setup_ratio=tip["setup_cpu_s"] / whole["setup_cpu_s"],
            )
        )
        print(
            f"{law:>26} {'tip/whole':>12} {tip['contact_vertices'] / whole['contact_vertices']:>5.2f} {'':>6} {'':>16} "
            f"{tip['step_cpu_s'] / whole['step_cpu_s']:>12.3f} {tip['setup_cpu_s'] / whole['setup_cpu_s']:>12.3f}"
        )
    if args.json:
        command = f"tools/stop_cost.py --mesh {args.mesh} --steps {args.steps} --rounds {args.rounds}"
        data = dict(command=command, mesh=[nx, ny], steps=args.steps, dt=dt, scene=list(SCENE), laws=table)
        args.json.write_text(json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    main()
