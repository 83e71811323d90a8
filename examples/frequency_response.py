"""Response map of the impacting plate: excitation frequency × obstacle gap, on Dask distributed.

Every map point is an independent FMU simulation — base z(t) = A sin(2πf t) given with its
derivatives, obstacles at ±gap — run as one Dask task. Each task loads the FMU itself into its
own extraction directory and frees it at the end, so tasks share nothing. By default the tasks
run on a LocalCluster of worker *processes* (one thread each); --scheduler ADDRESS uses an
existing cluster instead (the workers must be able to read --fmu, or pass --ship-fmu to send
the FMU's bytes to them).

Per point:
  max_abs_corner              max over the run of |corner_1|, |corner_2| (absolute, m)
  energy_dissipated_per_cycle impact losses over [settle, stop] divided by the number of
                              excitation cycles in that window (J/cycle)
  contact_fraction            share of communication points in [settle, stop] with a vertex
                              on an obstacle

Writes <out>/frequency_response.csv and <out>/frequency_response.png (two heat maps).

    python examples/frequency_response.py                       # LocalCluster, 2 workers
    python examples/frequency_response.py --scheduler tcp://host:8786 --ship-fmu
"""

from __future__ import annotations

import argparse
import csv
import statistics
import time
from pathlib import Path

from plateimpact.fmufile import output_dir, require_fmu
from plateimpact.response_map import CSV_COLUMNS, dask_map, grid


def write_csv(path, results):
    with Path(path).open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(CSV_COLUMNS))
        w.writeheader()
        w.writerows(results)


def plot(path, results, frequencies, gaps, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.colors import LogNorm

    shape = (len(gaps), len(frequencies))
    amax = np.array([r["max_abs_corner"] for r in results]).reshape(shape)
    ediss = np.array([r["energy_dissipated_per_cycle"] for r in results]).reshape(shape)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.6))
    rows = np.arange(len(gaps))  # one band per gap, whatever their spacing
    m1 = ax1.pcolormesh(frequencies, rows, amax, shading="nearest", cmap="viridis")
    fig.colorbar(m1, ax=ax1, label="max |corner| [m]")
    ax1.set_title("max |corner displacement|", fontsize=10)
    positive = ediss[ediss > 0]
    masked = np.ma.masked_less_equal(ediss, 0.0)
    norm = LogNorm(vmin=positive.min(), vmax=positive.max()) if positive.size else None
    m2 = ax2.pcolormesh(frequencies, rows, masked, shading="nearest", cmap="inferno", norm=norm)
    fig.colorbar(m2, ax=ax2, label="J / cycle (white: no impact)")
    ax2.set_title("energy dissipated by impacts per excitation cycle", fontsize=10)
    for ax in (ax1, ax2):
        ax.set_xlabel("excitation frequency [Hz]")
        ax.set_ylabel("obstacle gap ± [m]")
        ax.set_yticks(rows, [f"{g:g}" for g in gaps])
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def setup_report(results):
    """What the FMU's cache of discretizations saved (README, "Performance"): the setup of the
    points that built the plate (the first of each worker process) against those that shared it."""
    built = [r["setup_s"] for r in results if not r["plate_shared"]]
    shared = [r["setup_s"] for r in results if r["plate_shared"]]
    if not built or not shared:
        return f"setup: {len(results)} points, {len(shared)} shared the plate, {sum(built) + sum(shared):.2f} s in all"
    full, cheap = statistics.median(built), statistics.median(shared)
    return (
        f"setup: {len(built)} point(s) built the plate ({full:.3f} s median), {len(shared)} shared it from the "
        f"FMU's cache ({cheap:.4f} s median): about {len(shared) * (full - cheap):.1f} s of setup saved "
        f"(PLATEIMPACT_CACHE_MB=0 turns the cache off)"
    )


def _floats(text):
    return [float(x) for x in text.split(",")]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--out", default="out")
    ap.add_argument("--scheduler", help="address of an existing Dask scheduler")
    ap.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    ap.add_argument("--ship-fmu", action="store_true", help="send the FMU's bytes to the workers instead of its path")
    ap.add_argument("--frequencies", type=_floats, default=[2.0 * i for i in range(1, 21)], help="Hz, comma separated")
    ap.add_argument(
        "--gaps", type=_floats, default=[0.015, 0.02, 0.03, 0.05, 0.07, 0.1], help="obstacle gaps, m, comma separated"
    )
    ap.add_argument("--amplitude", type=float, default=0.01, help="base amplitude, m")
    ap.add_argument("--stop-time", type=float, default=2.0)
    ap.add_argument(
        "--settle", type=float, default=1.0, help="the per-cycle dissipation is taken over [settle, stop-time]"
    )
    ap.add_argument("--dt", type=float, default=1e-4)
    ap.add_argument("--step", type=float, default=1e-3, help="communication step, s")
    ap.add_argument("--element", choices=("argyris", "fvs"), default="argyris")
    ap.add_argument("--nx", type=int, default=14)
    ap.add_argument("--ny", type=int, default=5)
    ap.add_argument("--no-progress", action="store_true")
    ap.add_argument(
        "--quick",
        action="store_true",
        help="smoke test, a 2×2 map: --frequencies 8,30 --gaps 0.012,0.05 --stop-time 0.1 --settle 0.05 --nx 6 --ny 2",
    )
    args = ap.parse_args(argv)
    args.fmu = str(require_fmu(args.fmu, "frequency_response"))
    if args.quick:
        args.frequencies, args.gaps = [8.0, 30.0], [0.012, 0.05]
        args.stop_time, args.settle, args.nx, args.ny = 0.1, 0.05, 6, 2
    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never a full run's files
    points = grid(args.frequencies, args.gaps)
    kw = dict(
        amplitude=args.amplitude,
        stop_time=args.stop_time,
        settle=args.settle,
        dt=args.dt,
        comm_step=args.step,
        element=args.element,
        nx=args.nx,
        ny=args.ny,
    )
    fmu = Path(args.fmu).read_bytes() if args.ship_fmu else str(Path(args.fmu).resolve())

    from distributed import Client, LocalCluster

    t0 = time.perf_counter()
    if args.scheduler:
        client, cluster = Client(args.scheduler), None
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    try:
        print(f"{len(points)} simulations on {client}")
        results = dask_map(client, fmu, points, progress=not args.no_progress, **kw)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    wall = time.perf_counter() - t0
    cpu = sum(r["wall_s"] for r in results)
    print(f"map done in {wall:.1f} s wall ({cpu:.1f} s summed over the tasks)")
    print(setup_report(results))
    write_csv(out / "frequency_response.csv", results)
    plot(
        out / "frequency_response.png",
        results,
        args.frequencies,
        args.gaps,
        f"{args.element} {args.nx}×{args.ny}, base {args.amplitude:g} sin(2πf t) m, "
        f"{args.stop_time:g} s per point (dissipation over the last "
        f"{args.stop_time - args.settle:g} s), Δt = {args.dt:g} s",
    )
    print(f"wrote {out / 'frequency_response.csv'} and {out / 'frequency_response.png'}")


if __name__ == "__main__":
    main()
