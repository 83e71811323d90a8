"""The plate between its stops, from the FMI 3.0 FMU's array output: the default scene (base
0.09 sin(2π·10 t) m, obstacles at ±0.1 m) run with fmpy.simulate_fmu(early_return_allowed=True),
so that every contact onset and release is a frame of its own; vertex_displacement (the
deflection at every mesh vertex, [vertex_output = 1][vertices_x][vertices_y]) drawn as a surface, the vertices on
an obstacle in red. Writes a GIF (Pillow) of the first impacts and a still PNG.

    python examples/animate.py --fmu build/fmi3/PlateImpact.fmu --out docs/figures   # plate_impact.gif and .png
"""

from __future__ import annotations

import argparse
from pathlib import Path

import fmpy
import numpy as np

from plateimpact.fmufile import output_dir, require_fmu


def simulate(fmu, start, stop, interval):
    """The default scene with early return: rows at every interval and at every contact event."""
    t = np.arange(round(stop / 1e-4) + 1) * 1e-4
    signal = np.zeros(len(t), dtype=[("time", np.float64), ("base_displacement", np.float64)])
    signal["time"] = t
    signal["base_displacement"] = 0.09 * np.sin(2 * np.pi * 10.0 * t)
    result = fmpy.simulate_fmu(
        str(fmu),
        stop_time=stop,
        output_interval=interval,
        input=signal,
        output=["vertex_displacement", "contact_vertices", "corner_1"],
        early_return_allowed=True,
    )
    return result[result["time"] >= start]


def parameters(fmu):
    md = fmpy.read_model_description(str(fmu))
    return {v.name: float(v.start) for v in md.modelVariables if v.type == "Float64" and v.causality == "parameter"}


def draw(ax, row, p, tol=1e-9):
    """One frame: the deflected plate, its vertices on an obstacle (within tol) in red."""
    w = row["vertex_displacement"][0]  # [vertex_output = 1][i along x][j along y]
    nx, ny = w.shape[0] - 1, w.shape[1] - 1
    x, y = np.meshgrid(np.linspace(0, p["length"], nx + 1), np.linspace(0, p["width"], ny + 1), indexing="ij")
    on = (np.abs(w - p["obstacle_upper"]) < tol) | (np.abs(w - p["obstacle_lower"]) < tol)
    ax.clear()
    ax.plot_surface(x, y, w, color="#9ab", edgecolor="#567", linewidth=0.3, alpha=0.85)
    ax.scatter(x[on], y[on], w[on], color="red", s=18, depthshade=False)
    for z in (p["obstacle_lower"], p["obstacle_upper"]):
        ax.plot_surface(
            np.array([[p["length"] * 0.6, p["length"]]] * 2),
            np.array([[0, 0], [p["width"], p["width"]]]),
            np.full((2, 2), z),
            color="#444",
            alpha=0.12,
        )
    ax.set_xlim(0, p["length"])
    ax.set_ylim(0, p["width"])
    ax.set_zlim(1.2 * p["obstacle_lower"], 1.2 * p["obstacle_upper"])
    ax.set_box_aspect((3, 1, 1))
    ax.set_xlabel("x, m")
    ax.set_ylabel("y, m")
    ax.set_zlabel("w, m")
    ax.set_title(f"t = {row['time'] * 1e3:.2f} ms, {int(row['contact_vertices'])} vertices on an obstacle")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="build/fmi3/PlateImpact.fmu")
    ap.add_argument(
        "--out", default="out", help="plate_impact.gif and plate_impact.png go here (the README's: --out docs/figures)"
    )
    ap.add_argument("--start", type=float, default=0.04)
    ap.add_argument("--stop", type=float, default=0.1)
    ap.add_argument("--interval", type=float, default=2e-3, help="regular frame interval, s")
    ap.add_argument(
        "--quick",
        action="store_true",
        help="smoke run: --stop 0.06 (0.04 to 0.06 s), --interval 5e-3 (a frame every 5 ms)",
    )
    args = ap.parse_args(argv)
    args.fmu = str(require_fmu(args.fmu, "animate"))
    if args.quick:
        args.stop, args.interval = 0.06, 5e-3
    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never the README's figures
    args.gif, args.png = (str(out / f"plate_impact.{ext}") for ext in ("gif", "png"))

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    p = parameters(args.fmu)
    rows = simulate(args.fmu, args.start, args.stop, args.interval)
    events = np.flatnonzero(np.diff((rows["contact_vertices"] > 0).astype(int))) + 1
    print(f"animate: {len(rows)} frames from {args.start:g} s to {args.stop:g} s, {len(events)} contact events")

    fig = plt.figure(figsize=(8, 4.2))
    ax = fig.add_subplot(projection="3d")
    animation = FuncAnimation(fig, lambda k: draw(ax, rows[k], p), frames=len(rows))
    Path(args.gif).parent.mkdir(parents=True, exist_ok=True)
    animation.save(args.gif, writer=PillowWriter(fps=10), dpi=60)
    print(f"animate: wrote {args.gif}")

    # The still: the frame of the first contact onset (an early return: the impact's grid time).
    onset = next((k for k in events if rows["contact_vertices"][k] > 0), len(rows) - 1)
    draw(ax, rows[onset], p)
    Path(args.png).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.png, dpi=110, bbox_inches="tight")
    print(f"animate: wrote {args.png} (t = {rows['time'][onset]:.6f} s)")


if __name__ == "__main__":
    main()
