"""Sine sweep of the clamped edge: an external controller drives PlateImpact.fmu.

The controller (`SineSweep`) is a separate object from the plant (the FMU). It knows only the
sweep law and, at every communication point, hands the master the base displacement together
with its first two time derivatives; the master passes all three to the FMU through
`fmi2SetRealInputDerivatives`, so inside a communication step the clamp follows the sweep to
third order instead of being held constant (fmpy's `simulate_fmu` cannot do this, docs/theory.md).

    z(t) = A sin φ(t),  φ(t) = 2π ∫₀ᵗ f(s) ds
    linear:      f(t) = f0 + (f1 − f0) t/T,   φ = 2π (f0 t + (f1 − f0) t²/(2T))
    logarithmic: f(t) = f0 (f1/f0)^(t/T),     φ = 2π f0 T (e^{kt} − 1)/ln(f1/f0),  k = ln(f1/f0)/T

After t = T the frequency stays at f1. The plate has structural damping (Rayleigh, a damping ratio
--damping-ratio at f0 and at f1; docs/theory.md §13), so the resonance amplitude is set by the
damping and the impacts, not by impact artefacts of the mesh alone; --mass singular_p0 gives
impacts that keep their energy as dt -> 0 (docs/impact-laws.md). Writes <out>/sine_sweep.csv (time, instantaneous
frequency, base, corners, free-edge midpoint, energies) and <out>/sine_sweep.png.

    python examples/sine_sweep.py --amplitude 0.01 --f-start 2 --f-end 40 --duration 8 --law log
"""

from __future__ import annotations

import argparse
import csv
import time
from pathlib import Path

from plateimpact.fmufile import output_dir, require_fmu
from plateimpact.scenes import AMPLITUDE
from plateimpact.sweep import CSV_COLUMNS, SineSweep, rayleigh_for_band, run_sweep


def write_csv(path, rows):
    with Path(path).open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(CSV_COLUMNS))
        w.writeheader()
        w.writerows(rows)


def plot(path, rows, sweep, gap):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    matplotlib.rcParams["lines.antialiased"] = False  # dense curves: keeps the PNG small

    t = np.array([r["time"] for r in rows])
    f = np.array([r["frequency"] for r in rows])
    c1 = np.array([r["corner_1"] for r in rows])
    c2 = np.array([r["corner_2"] for r in rows])
    fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(9, 8), sharex=True, gridspec_kw={"height_ratios": [3, 2, 1.2]})
    ax1.plot(t, c1, lw=1.2, label="corner_1 (L, 0)")
    ax1.plot(t, c2, lw=0.6, ls="--", label="corner_2 (L, W)")
    ax1.plot(t, [r["base"] for r in rows], color="k", lw=0.6, label="base z(t)")
    for g in gap:
        if g is not None:
            ax1.axhline(g, color="k", lw=0.8)
    ax1.set_ylabel("displacement [m]")
    ax1.legend(loc="upper left", fontsize=8)
    ax1.set_title(
        f"{sweep.law} sine sweep {sweep.f0:g} → {sweep.f1:g} Hz in {sweep.T:g} s, amplitude {sweep.amplitude:g} m"
    )
    ax2.plot(t, [r["energy"] for r in rows], lw=0.8, label="energy")
    ax2.plot(t, [r["energy_input"] for r in rows], lw=0.8, label="energy_input")
    ax2.plot(t, [r["energy_dissipated"] for r in rows], lw=0.8, label="energy_dissipated")
    ax2.plot(t, [r["energy_damped"] for r in rows], lw=0.8, label="energy_damped")
    ax2.set_ylabel("energy [J]")
    ax2.legend(loc="upper left", fontsize=8)
    ax3.plot(t, f, color="C3")
    ax3.set_ylabel("f(t) [Hz]")
    ax3.set_xlabel("time [s]")
    if sweep.law == "log":
        from matplotlib.ticker import NullFormatter, ScalarFormatter

        ax3.set_yscale("log")
        lo, hi = sorted((sweep.f0, sweep.f1))
        nice = [m * 10.0**e for e in range(-2, 5) for m in (1, 2, 5) if lo < m * 10.0**e < hi]
        ax3.set_yticks([lo] + [x for x in nice if 1.3 * lo < x < hi / 1.3] + [hi])
        ax3.yaxis.set_major_formatter(ScalarFormatter())
        ax3.yaxis.set_minor_formatter(NullFormatter())
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--out", default="out")
    ap.add_argument("--amplitude", type=float, default=0.01, help="base amplitude A, m")
    ap.add_argument("--f-start", type=float, default=2.0, help="start frequency f0, Hz")
    ap.add_argument("--f-end", type=float, default=40.0, help="end frequency f1, Hz")
    ap.add_argument("--duration", type=float, default=8.0, help="sweep duration T, s")
    ap.add_argument("--law", choices=("linear", "log"), default="log")
    ap.add_argument("--stop-time", type=float, help="simulated time, s (default: duration)")
    ap.add_argument("--step", type=float, default=1e-3, help="communication step, s")
    ap.add_argument("--dt", type=float, default=1e-5, help="internal time step, s")
    ap.add_argument("--element", choices=("argyris", "fvs"), default="argyris")
    ap.add_argument("--nx", type=int, default=14)
    ap.add_argument("--ny", type=int, default=5)
    ap.add_argument("--gap", type=float, default=0.1, help="obstacles at ±gap, m; 0 switches both obstacles off")
    ap.add_argument("--damping-ratio", type=float, default=0.02, help="Rayleigh damping ratio at f0 and f1 (0: none)")
    ap.add_argument("--mass", choices=("consistent", "singular_p0", "singular_p1dg"), default="consistent")
    ap.add_argument("--restitution", type=float, default=0.0, help="restitution coefficient e in [0, 1]")
    ap.add_argument("--no-progress", action="store_true")
    ap.add_argument(
        "--quick",
        action="store_true",
        help="smoke test: --duration 0.05 --nx 6 --ny 2 --dt 1e-4 --step 1e-3 --f-start 20 --f-end 60 --amplitude 0.09",
    )
    args = ap.parse_args(argv)
    args.fmu = str(require_fmu(args.fmu, "sine_sweep"))
    if args.quick:
        args.duration, args.nx, args.ny, args.dt, args.step = 0.05, 6, 2, 1e-4, 1e-3
        args.f_start, args.f_end, args.amplitude = 20.0, 60.0, AMPLITUDE
    stop = args.stop_time if args.stop_time is not None else args.duration

    sweep = SineSweep(args.amplitude, args.f_start, args.f_end, args.duration, args.law)
    a, b = rayleigh_for_band(args.damping_ratio, *sorted((args.f_start, args.f_end)))
    params = dict(
        dt=args.dt,
        element=args.element,
        nx=args.nx,
        ny=args.ny,
        mass=args.mass,
        restitution=args.restitution,
        damping_mass=a,
        damping_stiffness=b,
    )
    if args.gap > 0:
        params.update(obstacle_lower=-args.gap, obstacle_upper=args.gap)
    else:
        params.update(obstacle_lower_enabled=False, obstacle_upper_enabled=False)

    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never a full run's files
    n = round(stop / args.step)
    bar = None
    if not args.no_progress and n * args.step / args.dt >= 1e5:  # long runs only
        from tqdm import tqdm

        bar = tqdm(total=n, unit="step", desc="sweep", mininterval=0.5)
    t0 = time.perf_counter()
    try:
        rows = run_sweep(args.fmu, sweep, stop, args.step, progress=bar, **params)
    finally:
        if bar is not None:
            bar.close()
    wall = time.perf_counter() - t0
    print(
        f"sine sweep ({args.law}, {args.f_start:g} → {args.f_end:g} Hz, A = {args.amplitude:g} m): "
        f"{stop:g} s simulated in {wall:.1f} s wall, max |corner| = "
        f"{max(max(abs(r['corner_1']), abs(r['corner_2'])) for r in rows):.4f} m, "
        f"dissipated {rows[-1]['energy_dissipated']:.2f} J in impacts, {rows[-1]['energy_damped']:.2f} J by damping "
        f"(zeta = {args.damping_ratio:g} at {args.f_start:g} and {args.f_end:g} Hz: a = {a:.4g} 1/s, b = {b:.4g} s)"
    )
    write_csv(out / "sine_sweep.csv", rows)
    gaps = (-args.gap, args.gap) if args.gap > 0 else (None,)
    plot(out / "sine_sweep.png", rows, sweep, gaps)
    print(f"wrote {out / 'sine_sweep.csv'} and {out / 'sine_sweep.png'}")


if __name__ == "__main__":
    main()
