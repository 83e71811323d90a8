"""Does the plate survive a sweep through its first mode between stops? A sine sweep of the clamp
(the SineSweep controller through input derivatives, as examples/sine_sweep.py) across the first
natural frequency, with the obstacles close enough for impacts and Rayleigh damping: the root's
von Mises stress envelope against frequency (and its running peak, tracked by the FMU at every
internal step: docs/theory.md §23), and the transmissibility of a probe — its absolute
displacement amplitude over the base's — at the accelerometer's point (--probe X Y).

Writes <out>/stress_sweep.csv (every communication point: time, frequency, base, root_stress,
root_stress_peak, probe_1, probe_1_acceleration), <out>/stress_envelope.csv (per frequency bin:
the bin's centre, the largest root_stress, root_stress_peak at its end, the transmissibility)
and <out>/stress_sweep.png; --quick writes the same into <out>/quick/, the figure
marked as a smoke run. A parameter the FMU refuses (a probe off the plate, ...) ends the run with
the FMU's message and exit status 2.

    python examples/stress_sweep.py --f-start 3 --f-end 10 --duration 20 --gap 0.02 --probe 0.9 0.2
"""

from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path

import numpy as np

from plateimpact import PlateImpactFMU
from plateimpact.driver import FMUError
from plateimpact.fmufile import output_dir, require_fmu
from plateimpact.sweep import SineSweep, rayleigh_for_band

SERIES = ("time", "frequency", "base", "root_stress", "root_stress_peak", "probe_1", "probe_1_acceleration")
ENVELOPE = ("frequency", "root_stress_max", "root_stress_peak", "transmissibility")


def run(fmu, sweep, stop, step, probe, gap, zeta, **extra):
    a, b = rayleigh_for_band(zeta, sweep.f0, sweep.f1)
    parameters = dict(
        stress_outputs=True,  # the stresses are computed on request (docs/theory.md §23)
        probe_count=1,
        probe_1_x=probe[0],
        probe_1_y=probe[1],
        obstacle_lower=-gap,
        obstacle_upper=gap,
        damping_mass=a,
        damping_stiffness=b,
        **extra,
    )
    rows = []
    n = round(stop / step)
    with PlateImpactFMU(fmu, **parameters) as plate:
        for k in range(n):
            t = k * step
            o = plate.step(step, base=sweep(t))
            t1 = (k + 1) * step
            rows.append(
                {"time": t1, "frequency": sweep.frequency(t1), "base": sweep(t1)[0]} | {c: o[c] for c in SERIES[3:]}
            )
    return rows


def envelope(rows, bins):
    """Per frequency bin: the largest root stress, the peak at the bin's end, and the probe's
    absolute amplitude over the base's (half the peak-to-peak of each)."""
    f = np.array([r["frequency"] for r in rows])
    edges = np.linspace(f.min(), f.max(), bins + 1)
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        inside = [r for r in rows if lo <= r["frequency"] <= hi]
        if len(inside) < 2:
            continue
        base = np.ptp([r["base"] for r in inside])
        probe = np.ptp([r["probe_1"] for r in inside])
        out.append(
            {
                "frequency": 0.5 * (lo + hi),
                "root_stress_max": max(r["root_stress"] for r in inside),
                "root_stress_peak": inside[-1]["root_stress_peak"],
                "transmissibility": probe / base if base > 0 else float("nan"),
            }
        )
    return out


def write_csv(path, columns, rows):
    with Path(path).open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(columns))
        w.writeheader()
        w.writerows(rows)


def plot(path, env, probe, smoke=None):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f = [e["frequency"] for e in env]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    ax1.plot(f, [e["root_stress_max"] / 1e6 for e in env], label="root_stress, largest in the bin")
    ax1.plot(f, [e["root_stress_peak"] / 1e6 for e in env], ls="--", label="root_stress_peak (since t = 0)")
    ax1.set_ylabel("von Mises stress at the clamp (MPa)")
    ax1.legend()
    ax2.plot(f, [e["transmissibility"] for e in env], color="C2")
    ax2.set_ylabel(f"transmissibility at ({probe[0]:g}, {probe[1]:g}) m")
    ax2.set_xlabel("base frequency (Hz)")
    if smoke:
        fig.suptitle(smoke, color="C3")
    fig.tight_layout()
    fig.savefig(path, dpi=90, metadata={"Description": smoke or "stress sweep"})


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--out", default="out", help="directory for the CSV files and the figure")
    ap.add_argument("--quick", action="store_true", help="a 0.05 s smoke run, written to <out>/quick/")
    ap.add_argument("--amplitude", type=float, default=0.005, help="base amplitude, m")
    ap.add_argument("--f-start", type=float, default=3.0)
    ap.add_argument("--f-end", type=float, default=10.0)
    ap.add_argument("--duration", type=float, default=20.0, help="sweep duration, s")
    ap.add_argument("--gap", type=float, default=0.02, help="obstacles at +-gap, m")
    ap.add_argument("--damping-ratio", type=float, default=0.02, help="Rayleigh damping ratio at f-start and f-end")
    ap.add_argument("--probe", type=float, nargs=2, default=(0.9, 0.2), metavar=("X", "Y"))
    ap.add_argument("--step", type=float, default=1e-3, help="communication step, s")
    ap.add_argument("--bins", type=int, default=70)
    args = ap.parse_args(argv)
    fmu = str(require_fmu(args.fmu, "stress_sweep.py"))
    duration = 0.05 if args.quick else args.duration
    sweep = SineSweep(args.amplitude, args.f_start, args.f_end, duration, law="linear")
    try:
        rows = run(fmu, sweep, duration, args.step, args.probe, args.gap, args.damping_ratio)
    except FMUError as e:  # the FMU's own message: what was wrong and what is allowed
        print(f"stress_sweep.py: the FMU refused the run: {'; '.join(e.messages) or e}", file=sys.stderr)
        return 2
    env = envelope(rows, 5 if args.quick else args.bins)
    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never the full sweep's files
    series, envelope_csv, png = (
        out / f"stress_{n}.{e}" for n, e in (("sweep", "csv"), ("envelope", "csv"), ("sweep", "png"))
    )
    write_csv(series, SERIES, rows)
    write_csv(envelope_csv, ENVELOPE, env)
    plot(png, env, args.probe, f"smoke run (--quick): {duration:g} s, not a sweep" if args.quick else None)
    worst = max(env, key=lambda e: e["root_stress_max"])
    print(
        f"root stress peak {rows[-1]['root_stress_peak'] / 1e6:.1f} MPa; largest in a bin at {worst['frequency']:.2f} Hz; "
        f"wrote {series}, {envelope_csv}, {png}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
