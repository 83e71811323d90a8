"""The default scene (the paper's §5.1 forced oscillation): base 0.09 sin(2π·10 t) m,
obstacles at ±0.1 m, 14×5 Argyris cells, dt = 1e-5 s, 1 s simulated, communication step 1e-4 s
with input derivatives. Writes <out>/default_scene.csv + .png (the 1 s scene the README describes;
--quick writes the same into <out>/quick/, the figure marked as a smoke run) and prints
the wall time; with --bench, also the per-step time beside the time of one solve with A's factor,
measured in the same run."""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import time

from plateimpact import PlateImpactFMU, default_base
from plateimpact.fmufile import output_dir, require_fmu
from plateimpact.scenes import AMPLITUDE, FREQUENCY


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--out", default="out")
    ap.add_argument("--bench", help="path of plate_bench (per-step time against the floor)")
    ap.add_argument("--stop-time", type=float, default=1.0)
    ap.add_argument("--step", type=float, default=1e-4, help="communication step, s")
    ap.add_argument("--dt", type=float, default=1e-5)
    ap.add_argument("--element", default="argyris", choices=("argyris", "fvs"))
    ap.add_argument(
        "--quick",
        action="store_true",
        help="smoke run: --stop-time 0.1 (the first 0.1 s), written to <out>/quick/",
    )
    args = ap.parse_args(argv)
    args.fmu = str(require_fmu(args.fmu, "default_scene"))
    if args.quick:
        args.stop_time = 0.1

    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never the 1 s scene's files
    n = round(args.stop_time / args.step)
    rows = []
    t0 = time.perf_counter()
    with PlateImpactFMU(args.fmu, dt=args.dt, element=args.element) as plate:
        rows.append({"time": 0.0, "base": 0.0, **plate.outputs()})
        for k in range(n):
            t = k * args.step
            plate.step(args.step, base=default_base(t))
            rows.append({"time": (k + 1) * args.step, "base": default_base((k + 1) * args.step)[0], **plate.outputs()})
    wall = time.perf_counter() - t0
    steps = round(args.stop_time / args.dt)
    print(
        f"default scene: {steps} steps of dt = {args.dt:g} s ({args.element}, 14x5 cells) "
        f"simulated {args.stop_time:g} s in {wall:.2f} s wall "
        f"({1e6 * wall / steps:.1f} us/step through fmpy, real-time factor {args.stop_time / wall:.2f})"
    )

    name = "default_scene"
    csv_path = out / f"{name}.csv"
    with csv_path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = [r["time"] for r in rows]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6.5), sharex=True)
    ax1.plot(t, [r["base"] for r in rows], color="0.6", lw=0.8, label="base z(t)")
    ax1.plot(t, [r["corner_1"] for r in rows], lw=1.0, label="corner_1 (L, 0)")
    ax1.plot(t, [r["corner_2"] for r in rows], lw=1.0, ls="--", label="corner_2 (L, W)")
    for g in (-0.1, 0.1):
        ax1.axhline(g, color="k", lw=0.8)
    ax1.set_ylabel("displacement [m]")
    ax1.legend(loc="upper right", fontsize=8)
    ax1.set_title(f"PlateImpact default scene: base {AMPLITUDE:g} sin(2π·{FREQUENCY:g} t), obstacles ±0.1 m")
    ax2.plot(t, [r["energy"] for r in rows], label="energy")
    ax2.plot(t, [r["energy_input"] for r in rows], label="energy_input")
    ax2.plot(t, [r["energy_dissipated"] for r in rows], label="energy_dissipated")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("energy [J]")
    ax2.legend(loc="upper left", fontsize=8)
    smoke = f"smoke run (--quick): the first {args.stop_time:g} s only" if args.quick else None
    if smoke:
        fig.suptitle(smoke, color="C3")
    fig.tight_layout()
    png_path = out / f"{name}.png"
    fig.savefig(png_path, dpi=120, metadata={"Description": smoke or f"the default scene, {args.stop_time:g} s"})
    print(f"wrote {csv_path} and {png_path}")

    if args.bench:
        r = json.loads(
            subprocess.run(
                [args.bench, f"dt={args.dt}", f"element={args.element}", f"steps={steps}"],
                check=True,
                capture_output=True,
                text=True,
            ).stdout
        )
        print(
            f"solver alone, same scene: {1e6 * r['step_s']:.1f} us/step, one solve with the "
            f"factor of A: {1e6 * r['floor_solve_s']:.1f} us (step/floor = {r['step_over_floor']:.2f}); "
            f"{r['wall_s']:.2f} s for {steps} steps"
        )


if __name__ == "__main__":
    main()
