"""Sine sweep of the clamped edge: an external controller drives PlateImpact.fmu.

The controller (`SineSweep`) is a separate object from the plant (the FMU). It knows only the
sweep law and, at every communication point, hands the master the base displacement together
with its first two time derivatives; the master passes all three to the FMU through
`fmi2SetRealInputDerivatives`, so inside a communication step the clamp follows the sweep to
third order instead of being held constant (fmpy's `simulate_fmu` cannot do this, docs/theory.md).

    z(t) = A sin φ(t),  φ(t) = 2π ∫₀ᵗ f(s) ds
    linear:      f(t) = f0 + (f1 − f0) t/T,   φ = 2π (f0 t + (f1 − f0) t²/(2T))
    logarithmic: f(t) = f0 (f1/f0)^(t/T),     φ = 2π f0 T (e^{kt} − 1)/ln(f1/f0),  k = ln(f1/f0)/T

After t = T the frequency stays at f1. Writes <out>/sine_sweep.csv (time, instantaneous
frequency, base, corners, free-edge midpoint, energies) and <out>/sine_sweep.png.

    python examples/sine_sweep.py --amplitude 0.01 --f-start 2 --f-end 40 --duration 8 --law log
"""
from __future__ import annotations

import argparse
import csv
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from plateimpact import PlateImpactFMU  # noqa: E402

CSV_COLUMNS = ("time", "frequency", "base", "corner_1", "corner_2", "free_edge_mid", "energy",
               "energy_dissipated", "energy_input", "contact_vertices")


class SineSweep:
    """A linear or logarithmic sine sweep z(t) = A sin φ(t) with φ' = 2π f(t).

    The controller is stateless and exact: every quantity is a closed-form function of t, so
    the signal handed to the FMU at any communication point is the one a direct evaluation
    gives, whatever the step size."""

    def __init__(self, amplitude, f_start, f_end, duration, law="linear"):
        if law not in ("linear", "log"):
            raise ValueError("law must be 'linear' or 'log'")
        if duration <= 0 or f_start <= 0 or f_end <= 0:
            raise ValueError("duration and frequencies must be positive")
        self.amplitude = float(amplitude)
        self.f0, self.f1, self.T = float(f_start), float(f_end), float(duration)
        self.law = law
        self._ln = math.log(self.f1 / self.f0)  # log law: k = ln(f1/f0)/T

    # -- the law ------------------------------------------------------------------------------
    def frequency(self, t):
        """Instantaneous frequency f(t) in Hz (f1 after the end of the sweep)."""
        s = min(max(t, 0.0), self.T)
        if self.law == "linear" or self._ln == 0.0:
            return self.f0 + (self.f1 - self.f0) * s / self.T
        return self.f0 * math.exp(self._ln * s / self.T)

    def phase(self, t):
        """φ(t), φ'(t) = 2π f(t), φ''(t) = 2π f'(t): phase in rad and its two derivatives."""
        two_pi = 2.0 * math.pi
        s = min(max(t, 0.0), self.T)
        if self.law == "linear" or self._ln == 0.0:
            slope = (self.f1 - self.f0) / self.T
            phi = two_pi * (self.f0 * s + 0.5 * slope * s * s)
            d2 = two_pi * slope
        else:
            k = self._ln / self.T
            phi = two_pi * self.f0 * math.expm1(k * s) / k
            d2 = two_pi * self.f0 * k * math.exp(k * s)
        if t > self.T:  # hold f1: phase grows linearly, no chirp any more
            return phi + two_pi * self.f1 * (t - self.T), two_pi * self.f1, 0.0
        return phi, two_pi * self.frequency(t), d2

    def __call__(self, t):
        """The base signal at t: (z, ż, z̈) — value and the two derivatives the FMU takes."""
        phi, d1, d2 = self.phase(t)
        s, c = math.sin(phi), math.cos(phi)
        a = self.amplitude
        return a * s, a * c * d1, a * (c * d2 - s * d1 * d1)


def run_sweep(fmu, sweep, stop_time, comm_step, progress=None, **parameters):
    """Drive the FMU with the controller for stop_time; returns a list of CSV rows (dicts).

    The master loop: at each communication point t_k the controller is asked for
    (z, ż, z̈)(t_k), the FMU is advanced by comm_step with those inputs, and the outputs at
    t_{k+1} are recorded beside the controller's base value and frequency at t_{k+1}."""
    n = round(stop_time / comm_step)
    if abs(n * comm_step - stop_time) > 1e-9 * stop_time:
        raise ValueError("stop_time must be a whole number of communication steps")
    rows = []

    def record(t, plate):
        o = plate.outputs()
        rows.append({"time": t, "frequency": sweep.frequency(t), "base": sweep(t)[0],
                     **{k: o[k] for k in CSV_COLUMNS[3:]}})

    with PlateImpactFMU(fmu, **parameters) as plate:
        record(0.0, plate)
        for k in range(n):
            plate.step(comm_step, base=sweep(k * comm_step))
            record((k + 1) * comm_step, plate)
            if progress is not None:
                progress.update(1)
    return rows


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
    fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(9, 8), sharex=True,
                                        gridspec_kw={"height_ratios": [3, 2, 1.2]})
    ax1.plot(t, c1, lw=1.2, label="corner_1 (L, 0)")
    ax1.plot(t, c2, lw=0.6, ls="--", label="corner_2 (L, W)")
    ax1.plot(t, [r["base"] for r in rows], color="k", lw=0.6, label="base z(t)")
    for g in gap:
        if g is not None:
            ax1.axhline(g, color="k", lw=0.8)
    ax1.set_ylabel("displacement [m]")
    ax1.legend(loc="upper left", fontsize=8)
    ax1.set_title(f"{sweep.law} sine sweep {sweep.f0:g} → {sweep.f1:g} Hz in {sweep.T:g} s, "
                  f"amplitude {sweep.amplitude:g} m")
    ax2.plot(t, [r["energy"] for r in rows], lw=0.8, label="energy")
    ax2.plot(t, [r["energy_input"] for r in rows], lw=0.8, label="energy_input")
    ax2.plot(t, [r["energy_dissipated"] for r in rows], lw=0.8, label="energy_dissipated")
    ax2.set_ylabel("energy [J]")
    ax2.legend(loc="upper left", fontsize=8)
    ax3.plot(t, f, color="C3")
    ax3.set_ylabel("f(t) [Hz]")
    ax3.set_xlabel("time [s]")
    if sweep.law == "log":
        from matplotlib.ticker import NullFormatter, ScalarFormatter
        ax3.set_yscale("log")
        lo, hi = sorted((sweep.f0, sweep.f1))
        nice = [m * 10.0 ** e for e in range(-2, 5) for m in (1, 2, 5) if lo < m * 10.0 ** e < hi]
        ax3.set_yticks([lo] + [x for x in nice if 1.3 * lo < x < hi / 1.3] + [hi])
        ax3.yaxis.set_major_formatter(ScalarFormatter())
        ax3.yaxis.set_minor_formatter(NullFormatter())
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
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
    ap.add_argument("--gap", type=float, default=0.1,
                    help="obstacles at ±gap, m; 0 switches both obstacles off")
    ap.add_argument("--no-progress", action="store_true")
    ap.add_argument("--quick", action="store_true",
                    help="smoke test: 0.05 s sweep, 6x2 cells, dt 1e-4")
    args = ap.parse_args(argv)
    if args.quick:
        args.duration, args.nx, args.ny, args.dt, args.step = 0.05, 6, 2, 1e-4, 1e-3
        args.f_start, args.f_end, args.amplitude = 20.0, 60.0, 0.09
    stop = args.stop_time if args.stop_time is not None else args.duration

    sweep = SineSweep(args.amplitude, args.f_start, args.f_end, args.duration, args.law)
    params = dict(dt=args.dt, element=args.element, nx=args.nx, ny=args.ny)
    if args.gap > 0:
        params.update(obstacle_lower=-args.gap, obstacle_upper=args.gap)
    else:
        params.update(obstacle_lower_enabled=False, obstacle_upper_enabled=False)

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
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
    print(f"sine sweep ({args.law}, {args.f_start:g} → {args.f_end:g} Hz, A = {args.amplitude:g} m): "
          f"{stop:g} s simulated in {wall:.1f} s wall, max |corner| = "
          f"{max(max(abs(r['corner_1']), abs(r['corner_2'])) for r in rows):.4f} m, "
          f"dissipated {rows[-1]['energy_dissipated']:.2f} J")
    write_csv(out / "sine_sweep.csv", rows)
    gaps = (-args.gap, args.gap) if args.gap > 0 else (None,)
    plot(out / "sine_sweep.png", rows, sweep, gaps)
    print(f"wrote {out / 'sine_sweep.csv'} and {out / 'sine_sweep.png'}")


if __name__ == "__main__":
    main()
