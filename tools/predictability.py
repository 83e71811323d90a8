"""The predictability horizon (issue 38, item 4): how long a trajectory means something, and what
still converges beyond it, for four scenes driven through the FMU with fmpy.

    python tools/predictability.py                       # ~6 min of one core; writes docs/predictability.json
    python tools/render_docs.py performance.md           # the section "The predictability horizon"
    python tools/predictability.py --quick --out /tmp/p.json   # a smoke run (short windows)
    python tools/predictability.py --tolerance 1e-5 --ladder tolerance   # once the FMU has `tolerance`

Scenes (SCENES below): the default scene (the paper's §5.1: Argyris 14x5, obstacles +-0.1 m, base
0.09 sin(2 pi 10 t) m), §5.2 (released from its static shape under 8600 Pa onto the lower obstacle,
no base motion), the FVS near-obstacle case of issue 38 (FVS 20x7, obstacles +-0.01 m, base
0.009 sin(2 pi 35 t) m) and the stop under the tip of issue 52 (Argyris 12x4, so that x = 1.0 m is
a mesh line; a lower stop over x >= 1.0 m at -0.05 m, the upper obstacle off, the default base;
its convergence before the horizon: tools/stop_convergence.py). The law is the flow scheme by default (mass = singular_p0, time_scheme =
flow), with its knobs as options; --compare-law adds the horizon of a second law (conserving).

Measured, per scene:

  - twins: the run and runs whose input differs at roundoff level (base amplitude, or §5.2's
    initial_load, times 1 + k 1e-14; the lower obstacle times 1 + 1e-15; with --tolerance also the
    tolerance times 1 + 1e-14). For a pair, t*(eps) = the first output time (communication step h)
    at which |corner_1 - corner_1'| > eps, for eps in EPS (1e-4, 1e-5, 1e-6 m, and the tolerance
    when one is given). The separation's growth: t* at every decade 1e-12 ... 1e-5 m above the
    pair's roundoff floor, a least-squares line ln(eps) = a + lambda t* (a finite-time Lyapunov
    exponent), clean when it fits (R^2 >= 0.97 over at least 4 decades).
  - the ladder: the same scene under refinement (dt halved, or the tolerance halved with
    --ladder tolerance); t*(eps) of each pair of neighbours is the horizon of the discretisation,
    and its shift per halving, lambda dt*/ln 2, is the order of the error the chaos amplifies.
  - statistics over a window beyond t* (the scene's `window`, checked to start after every twin
    has parted from its run by 1e-4 m): impact rates (contact onsets per second per obstacle, the
    FMU's contact_onsets_lower / contact_onsets_upper, and impact episodes: onsets at least QUIET after the
    previous one), the energy envelope (mean and max of `energy`), the RMS of corner_1 and its
    spectrum (Welch PSD: dominant frequency, spectral centroid, band shares). At every ladder level
    but the finest (run only to the horizon) the run and its N_TWINS roundoff twins form an
    ensemble; a level's mean is compared with the finest level's. Verdict per statistic:
    'converges within X %' when every difference is below 3 standard errors of the two ensembles'
    means (X = that resolution relative to the finest mean), 'converges' when the differences
    exceed it but shrink (ratio <= 0.75), 'does not converge' otherwise; 'identical' when every run
    agrees to 1e-9 relative (§5.2's energy: conserved).

Cost of the default run: about 450 s CPU of one core; the statistics' windows (default 0.7-2 s,
§5.2 10-14 s, FVS 0.2-1 s, tip stop 2-5 s) and ensembles of 5 set it.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from checkout import add_checkout_arguments, fmu_path

from plateimpact.driver import PlateImpactFMU

EPS = (1e-4, 1e-5, 1e-6)  # m, the separations whose first time is the horizon
DECADES = tuple(10.0**-k for k in range(12, 4, -1))  # 1e-12 ... 1e-5 m, for the growth rate
H = 1e-4  # s, communication step: the outputs (and t*) are read on this grid
N_TWINS = 4  # perturbed twins besides the run itself (amplitude x (1 + k 1e-14), k = 1..N_TWINS)
ROUNDOFF = 1e-14  # relative perturbation of the twins
QUIET = 2e-3  # s without a contact onset before an onset starts a new impact episode
BANDS = (0.0, 25.0, 50.0, 100.0, 200.0, 400.0, 800.0, 5000.0)  # Hz, the spectrum's bands
LAWS = {"flow": {"mass": 2, "time_scheme": 3}, "conserving": {"mass": 2, "time_scheme": 2}}


@dataclass(frozen=True)
class Scene:
    key: str
    title: str
    params: dict
    amplitude: float  # m, base amplitude (0: no base motion)
    frequency: float  # Hz
    perturbed: str  # what the twins perturb: "amplitude" or a parameter's name
    horizon_stop: float  # s, length of the finest ladder run and of the second law's runs
    window: tuple  # s, the statistics' window (beyond t*)


SCENES = {
    "default": Scene(
        "default",
        "default scene (§5.1): Argyris 14×5, obstacles ±0.1 m, base 0.09 sin(2π·10 t) m",
        {},
        0.09,
        10.0,
        "amplitude",
        0.8,
        (0.7, 2.0),
    ),
    "5.2": Scene(
        "5.2",
        "§5.2: Argyris 14×5, released from its shape under 8600 Pa onto the lower obstacle at −0.1 m",
        {"initial_load": 8600.0, "obstacle_upper_enabled": False},
        0.0,
        0.0,
        "initial_load",
        4.0,
        (10.0, 14.0),
    ),
    "fvs": Scene(
        "fvs",
        "FVS near obstacles: FVS 20×7, obstacles ±0.01 m, base 0.009 sin(2π·35 t) m",
        {"element": 2, "nx": 20, "ny": 7, "obstacle_lower": -0.01, "obstacle_upper": 0.01},
        0.009,
        35.0,
        "amplitude",
        0.25,
        (0.2, 1.0),
    ),
    "tip_stop": Scene(
        "tip_stop",
        "stop under the tip (docs/theory.md §25): Argyris 12×4 (x = 1.0 m on a mesh line), a lower stop over "
        "x ≥ 1.0 m at −0.05 m, the upper obstacle off, base 0.09 sin(2π·10 t) m",
        {"nx": 12, "ny": 4, "obstacle_lower": -0.05, "obstacle_lower_x_min": 1.0, "obstacle_upper_enabled": False},
        0.09,
        10.0,
        "amplitude",
        2.0,
        (2.0, 5.0),
    ),
}


@dataclass
class Series:
    label: str
    t: np.ndarray
    corner: np.ndarray
    energy: np.ndarray
    onsets: np.ndarray  # (n, 2) contact_onsets_lower, contact_onsets_upper (cumulative)
    cpu: float
    params: dict = field(default_factory=dict)


def has_variable(fmu, name):
    with PlateImpactFMU(fmu, initialize=False) as plate:
        return name in plate.vars


def simulate(fmu, scene, params, stop, label, amplitude_factor=1.0, h=H):
    """One run of `scene` with FMU parameters `params` to `stop`, outputs every h; the base is given
    with its first two derivatives at every communication point (exact inside the step)."""
    n = round(stop / h)
    out = np.empty((n, 4))
    amp, w = scene.amplitude * amplitude_factor, 2 * math.pi * scene.frequency
    t0 = time.process_time()
    with PlateImpactFMU(fmu, **params) as plate:
        real = [plate.vars[v].valueReference for v in ("corner_1", "energy")]
        ints = [plate.vars[v].valueReference for v in ("contact_onsets_lower", "contact_onsets_upper")]
        vb = plate.vars["base_displacement"].valueReference
        fmu_ = plate.fmu
        for k in range(n):
            t = k * h
            if amp:
                s, c = math.sin(w * t), math.cos(w * t)
                fmu_.setReal([vb], [amp * s])
                fmu_.setRealInputDerivatives([vb, vb], [1, 2], [amp * w * c, -amp * w * w * s])
            fmu_.doStep(currentCommunicationPoint=t, communicationStepSize=h)
            out[k, :2] = fmu_.getReal(real)
            out[k, 2:] = fmu_.getInteger(ints)
    cpu = time.process_time() - t0
    print(f"  {label}: {stop:g} s simulated, {cpu:.1f} s CPU", flush=True)
    return Series(label, (np.arange(n) + 1) * h, out[:, 0], out[:, 1], out[:, 2:], cpu, params)


# -- the horizon -----------------------------------------------------------------------------


def first_exceedance(t, sep, eps):
    k = int(np.argmax(sep > eps))
    return float(t[k]) if sep[k] > eps else None


def growth(t, sep):
    """t* at every decade above the pair's roundoff floor; the least-squares rate lambda of
    ln(eps) against t*, its R^2, and the local slopes between decades. Clean: at least 4 decades
    and R^2 >= 0.97 (the crossings fall where the oscillating separation peaks, so the local slopes
    scatter even when the envelope grows exponentially)."""
    floor = float(np.max(sep[: max(1, round(0.01 / (t[1] - t[0])))]))  # separation over the first 10 ms
    points = [(first_exceedance(t, sep, e), e) for e in DECADES if e > 10 * floor]
    points = [(ts, e) for ts, e in points if ts is not None]
    if len(points) < 3:
        return dict(floor=floor, points=points, rate=None, r2=None, local=[], clean=False)
    ts, es = np.array([p[0] for p in points]), np.log([p[1] for p in points])
    slope, icept = np.polyfit(ts, es, 1)
    r2 = 1.0 - float(np.sum((es - (slope * ts + icept)) ** 2) / np.sum((es - es.mean()) ** 2))
    local = [float((b - a) / (tb - ta)) if tb > ta else None for a, b, ta, tb in zip(es, es[1:], ts, ts[1:])]
    return dict(
        floor=floor,
        points=[[float(a), float(b)] for a, b in points],
        rate=float(slope),
        r2=r2,
        local=local,
        clean=bool(len(points) >= 4 and r2 >= 0.97),
    )


def horizon(a, b, eps):
    n = min(len(a.t), len(b.t))
    t, sep = a.t[:n], np.abs(a.corner[:n] - b.corner[:n])
    return dict(
        pair=[a.label, b.label],
        stop=float(t[-1]),
        t_star={f"{e:g}": first_exceedance(t, sep, e) for e in eps},
        max_separation=float(sep.max()),
        growth=growth(t, sep),
    )


# -- statistics beyond the horizon -----------------------------------------------------------


def episodes(t, counts, quiet=QUIET):
    """Onset times (the communication steps in which the cumulative counter rose) that come at
    least `quiet` after the previous onset."""
    rose = t[np.flatnonzero(np.diff(counts, prepend=0) > 0)]
    keep = [x for i, x in enumerate(rose) if i == 0 or x - rose[i - 1] >= quiet]
    return np.array(keep)


def statistics(s, window):
    from scipy.signal import welch

    ta, tb = window
    m = (s.t > ta - 1e-12) & (s.t <= tb + 1e-12)
    if not m.any() or s.t[-1] < tb - 1e-9:
        return None
    length = tb - ta
    k0, k1 = np.flatnonzero(m)[[0, -1]]
    stats = {}
    for j, side in enumerate(("lower", "upper")):
        before = s.onsets[k0 - 1, j] if k0 > 0 else 0
        stats[f"onsets_{side}"] = float(s.onsets[k1, j] - before) / length
        ep = episodes(s.t, s.onsets[:, j])
        stats[f"episodes_{side}"] = float(np.count_nonzero((ep > ta) & (ep <= tb))) / length
    stats["energy_mean"] = float(s.energy[m].mean())
    stats["energy_max"] = float(s.energy[m].max())
    stats["energy_start"] = float(s.energy[k0])
    stats["energy_end"] = float(s.energy[k1])
    c = s.corner[m]
    stats["corner_rms"] = float(np.sqrt(np.mean(c * c)))
    fs = 1.0 / (s.t[1] - s.t[0])
    nperseg = 2 ** int(math.log2(len(c) / 4))
    f, p = welch(c - c.mean(), fs=fs, nperseg=nperseg)
    total = float(p.sum())  # the bins are uniform: sums are the integrals over df
    stats["psd_resolution"] = float(f[1] - f[0])
    stats["dominant_frequency"] = float(f[np.argmax(p)])
    stats["spectral_centroid"] = float((f * p).sum() / total)
    stats["band_shares"] = [float(p[(f >= lo) & (f < hi)].sum() / total) for lo, hi in zip(BANDS, BANDS[1:])]
    return stats


STATISTICS = [
    # key, label, unit
    ("onsets_lower", "contact onsets per s, lower obstacle", "1/s"),
    ("onsets_upper", "contact onsets per s, upper obstacle", "1/s"),
    ("episodes_lower", f"impact episodes per s, lower (onsets ≥ {QUIET * 1e3:g} ms apart)", "1/s"),
    ("episodes_upper", f"impact episodes per s, upper (onsets ≥ {QUIET * 1e3:g} ms apart)", "1/s"),
    ("energy_mean", "mean energy", "J"),
    ("energy_max", "max energy", "J"),
    ("corner_rms", "RMS of corner_1", "m"),
    ("dominant_frequency", "dominant frequency of corner_1", "Hz"),
    ("spectral_centroid", "spectral centroid of corner_1", "Hz"),
]


def verdict(ensembles, contraction=0.75):
    """The verdict of one statistic from its values on the ladder's levels (coarse -> fine), each an
    ensemble: the level's run and its roundoff twins. Ensemble means m_k with standard errors; the
    difference of a level's mean from the finest's counts as resolved when it exceeds 3 standard
    errors of that difference."""
    values = [np.array(e, dtype=float) for e in ensembles]
    means = [float(v.mean()) for v in values]
    spreads = [float(v.std(ddof=1)) for v in values]  # one run's scatter about the ensemble mean
    n = [len(v) for v in values]
    finest = means[-1]
    scale = max(abs(finest), 1e-300)
    se = [math.sqrt(spreads[k] ** 2 / n[k] + spreads[-1] ** 2 / n[-1]) for k in range(len(values) - 1)]
    from_finest = [abs(m - finest) for m in means[:-1]]
    diffs = [abs(a - b) for a, b in zip(means, means[1:])]
    row = dict(
        means=means,
        spreads=spreads,
        n=n,
        relative_spread=spreads[0] / scale,  # a single run's statistic scatters this much
        diffs=diffs,
        from_finest=from_finest,
        standard_errors=se,
        relative_from_finest=max(from_finest) / scale if from_finest else None,
        relative_from_finest_each=[d / scale for d in from_finest],
        relative_3se_each=[3 * e / scale for e in se],
    )
    everything = np.concatenate(values)
    if not from_finest:
        row.update(verdict="not measured", within=None)
    elif float(everything.max() - everything.min()) <= 1e-9 * scale:
        row.update(verdict="identical", within=None)
    elif all(d <= 3 * e for d, e in zip(from_finest, se)):
        row.update(verdict="converges within", within=max(3 * e for e in se) / scale)
    elif len(diffs) >= 2 and all(b <= contraction * a for a, b in zip(diffs, diffs[1:])):
        row.update(verdict="converges", within=diffs[-1] / scale)
    else:
        row.update(verdict="does not converge", within=None)
    return row


# -- the study -------------------------------------------------------------------------------


def study_scene(fmu, scene, base_params, args, tolerance_var):
    print(f"{scene.title}", flush=True)
    ladder_name = args.ladder
    first = base_params[ladder_name] if ladder_name in base_params else None
    if first is None:
        raise SystemExit(f"--ladder {ladder_name}: no such knob in the law's parameters {base_params}")
    stop = scene.window[1]
    params = dict(scene.params, **base_params)
    eps = list(EPS) + ([base_params["tolerance"]] if "tolerance" in base_params else [])

    def perturbed(k, delta=ROUNDOFF):
        if scene.perturbed == "amplitude":
            return dict(params), 1.0 + k * delta
        return dict(params, **{scene.perturbed: params[scene.perturbed] * (1.0 + k * delta)}), 1.0

    # the ladder: the knob halved; the finest level only to the horizon, the others with their
    # roundoff twins to the end of the statistics' window
    ladder, ensembles = [], []
    for i in range(args.levels):
        value = first / 2**i
        finest = i == args.levels - 1
        p = dict(params, **{ladder_name: value})
        name = f"{ladder_name} = {value:g}"
        ladder.append(simulate(fmu, scene, p, scene.horizon_stop if finest else stop, name))
        if finest:
            continue
        members = [ladder[-1]]
        for k in range(1, args.twins + 1):
            q, factor = perturbed(k)
            q[ladder_name] = value
            members.append(
                simulate(fmu, scene, q, stop, f"{name}, {scene.perturbed} × (1 + {k}e-14)", amplitude_factor=factor)
            )
        ensembles.append(members)
    base, twins = ladder[0], ensembles[0][1:]
    obstacle = simulate(
        fmu,
        scene,
        dict(params, obstacle_lower=params.get("obstacle_lower", -0.1) * (1 + 1e-15)),
        stop,
        "obstacle_lower × (1 + 1e-15)",
    )
    extra = []
    if "tolerance" in base_params and tolerance_var:
        p = dict(params, tolerance=base_params["tolerance"] * (1 + ROUNDOFF))
        extra.append(simulate(fmu, scene, p, stop, "tolerance × (1 + 1e-14)"))
    repeat = simulate(fmu, scene, dict(params), min(stop, 0.2), "the same run again")
    deterministic = bool(np.array_equal(repeat.corner, base.corner[: len(repeat.corner)]))
    everything = ladder + [m for e in ensembles for m in e[1:]] + [obstacle, repeat] + extra

    roundoff = [horizon(base, twins[0], eps), horizon(base, obstacle, eps)] + [horizon(base, e, eps) for e in extra]
    refinement = [horizon(a, b, eps) for a, b in zip(ladder, ladder[1:])]
    if ladder_name == "tolerance":  # the measure: the pair parts by more than its tolerance
        for r, a, b in zip(refinement, ladder, ladder[1:]):
            n = min(len(a.t), len(b.t))
            sep = np.abs(a.corner[:n] - b.corner[:n])
            r["t_star_at_tolerance"] = first_exceedance(a.t[:n], sep, a.params["tolerance"])
    for r in roundoff + refinement:
        print(f"  t* {r['pair'][1]:>32}: {r['t_star']}  rate {r['growth']['rate']}", flush=True)

    result = dict(
        key=scene.key,
        title=scene.title,
        params={k: v for k, v in params.items()},
        window=list(scene.window),
        horizon_stop=scene.horizon_stop,
        deterministic=deterministic,
        roundoff=roundoff,
        refinement=refinement,
        ladder=dict(knob=ladder_name, values=[first / 2**i for i in range(args.levels)]),
        cpu=sum(s.cpu for s in everything),
    )
    # how t* moves: its shift per halving of the ladder's knob, and what halving the error level
    # buys at the growth rate of the roundoff twins (ln 2 / lambda)
    result["shifts"] = (
        {
            key: [
                b["t_star"][key] - a["t_star"][key] if a["t_star"][key] and b["t_star"][key] else None
                for a, b in zip(refinement, refinement[1:])
            ]
            for key in refinement[0]["t_star"]
        }
        if refinement
        else {}
    )
    rate = roundoff[0]["growth"]["rate"]
    result["gain_per_halving"] = math.log(2) / rate if rate else None
    # the horizon of a second law (twins and one halving of the ladder, to horizon_stop)
    if args.compare_law:
        other = dict(scene.params, **LAWS[args.compare_law], dt=args.dt)
        if "tolerance" in base_params:
            other["tolerance"] = base_params["tolerance"]
        a = simulate(fmu, scene, other, scene.horizon_stop, f"{args.compare_law}, dt = {args.dt:g}")
        if scene.perturbed == "amplitude":
            b = simulate(
                fmu,
                scene,
                other,
                scene.horizon_stop,
                f"{args.compare_law}, amplitude × (1 + 1e-14)",
                amplitude_factor=1 + ROUNDOFF,
            )
        else:
            q = dict(other, **{scene.perturbed: other[scene.perturbed] * (1 + ROUNDOFF)})
            b = simulate(fmu, scene, q, scene.horizon_stop, f"{args.compare_law}, {scene.perturbed} × (1 + 1e-14)")
        c = simulate(
            fmu, scene, dict(other, dt=args.dt / 2), scene.horizon_stop, f"{args.compare_law}, dt = {args.dt / 2:g}"
        )
        result["compare_law"] = dict(law=args.compare_law, roundoff=horizon(a, b, eps), refinement=horizon(a, c, eps))
        result["cpu"] += a.cpu + b.cpu + c.cpu

    # statistics beyond the horizon
    # every ensemble member parted from its level's run by 1e-4 m before the window starts (and the
    # obstacle twin from the run)
    t_twins = [r["t_star"]["0.0001"] for r in roundoff]
    t_twins += [horizon(e[0], m, [1e-4])["t_star"]["0.0001"] for e in ensembles for m in e[1:]]
    result["ensemble_t_star_max"] = max((x for x in t_twins if x is not None), default=None)
    result["window_after_horizon"] = all(x is not None and x <= scene.window[0] for x in t_twins)
    stats = [[statistics(m, scene.window) for m in e] for e in ensembles]
    rows = []
    for key, label, unit in STATISTICS:
        row = verdict([[st[key] for st in level] for level in stats])
        rows.append(dict(row, key=key, label=label, unit=unit))
        print(f"  {label}: {row['verdict']} {row['within']} means {row['means']} spreads {row['spreads']}", flush=True)
    result["statistics"] = rows
    shares = [np.array([st["band_shares"] for st in level]) for level in stats]
    result["band_shares"] = dict(
        bands=list(BANDS),
        means=[[float(x) for x in level.mean(axis=0)] for level in shares],
        spreads=[[float(x) for x in level.std(axis=0, ddof=1)] for level in shares],
        max_from_finest=float(max(np.abs(level.mean(axis=0) - shares[-1].mean(axis=0)).max() for level in shares)),
        max_spread=float(max(level.std(axis=0, ddof=1).max() for level in shares)),
    )
    twin_stats = stats[0]
    result["psd_resolution"] = twin_stats[0]["psd_resolution"]
    result["energy_window"] = [twin_stats[0]["energy_start"], twin_stats[0]["energy_end"]]
    return result


def run_record(repo, wall0, cpu0):
    """How a study ran: wall and CPU seconds since perf_counter() = wall0 and process_time() = cpu0,
    the checkout's commit, the date, the load, the machine."""
    try:
        commit = subprocess.run(
            ["git", "-C", str(repo), "rev-parse", "--short", "HEAD"], capture_output=True, text=True
        ).stdout.strip()
    except OSError:
        commit = "?"
    return dict(
        wall_s=time.perf_counter() - wall0,
        cpu_s=time.process_time() - cpu0,
        commit=commit,
        date=time.strftime("%Y-%m-%d"),
        load=os.getloadavg()[0],
        machine=platform.machine(),
    )


def command(args):
    """The command line of this study's choices (not of where its files are)."""
    line = ["tools/predictability.py"]
    for name in ("time_scheme", "dt", "contact_substeps", "tolerance", "ladder", "levels", "twins", "compare_law"):
        value, default = getattr(args, name), DEFAULTS[name]
        if value != default:
            line.append(f"--{name.replace('_', '-')} {value if value != '' else repr('')}")
    if args.scenes != ",".join(SCENES):
        line.append(f"--scenes {args.scenes}")
    return " ".join(line + (["--quick"] if args.quick else []))


DEFAULTS = dict(
    time_scheme=3,
    dt=1e-5,
    contact_substeps=None,
    tolerance=None,
    ladder="dt",
    levels=4,
    twins=N_TWINS,
    compare_law="conserving",
)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_checkout_arguments(ap)
    ap.add_argument("--out", type=Path, help="the JSON (default <repo>/docs/predictability.json)")
    ap.add_argument("--scenes", default=",".join(SCENES), help=f"comma-separated, of {', '.join(SCENES)}")
    ap.add_argument("--time-scheme", type=int, default=3, help="2 conserving, 3 flow (default; mass = singular_p0)")
    ap.add_argument(
        "--dt", type=float, default=1e-5, help="internal step (s), the ladder's first level for --ladder dt"
    )
    ap.add_argument(
        "--contact-substeps", type=int, help="time_scheme = flow: sub-steps of a contact step (FMU default 16)"
    )
    ap.add_argument("--tolerance", type=float, help="passed as the FMU's `tolerance` (m) when it has that variable")
    ap.add_argument("--ladder", default="dt", help="the knob halved along the refinement ladder: dt or tolerance")
    ap.add_argument("--levels", type=int, default=4, help="ladder levels (default 4: dt, dt/2, dt/4, dt/8)")
    ap.add_argument("--twins", type=int, default=N_TWINS, help="perturbed twins besides the run (default 4)")
    ap.add_argument("--compare-law", default="conserving", help="a second law's horizon (conserving; '' for none)")
    ap.add_argument("--quick", action="store_true", help="short windows, 2 ladder levels, 2 twins (a smoke run)")
    args = ap.parse_args(argv)
    line = command(args)
    fmu = fmu_path(args)
    wall0, cpu0 = time.perf_counter(), time.process_time()
    law = {"mass": 2, "time_scheme": args.time_scheme, "dt": args.dt}
    if args.contact_substeps:
        law["contact_substeps"] = args.contact_substeps
    tolerance_var = has_variable(fmu, "tolerance")
    if args.tolerance is not None:
        if tolerance_var:
            law["tolerance"] = args.tolerance
        else:
            print(f"--tolerance {args.tolerance:g}: this FMU has no variable `tolerance`; not passed", flush=True)
    scenes = [SCENES[k] for k in args.scenes.split(",") if k]
    if args.quick:
        args.levels, args.twins = 2, 2
        scenes = [
            Scene(
                s.key,
                s.title,
                s.params,
                s.amplitude,
                s.frequency,
                s.perturbed,
                s.window[0] / 4,
                (s.window[0] / 4, s.window[0] / 2),
            )
            for s in scenes
        ]
    results = [study_scene(fmu, s, law, args, tolerance_var) for s in scenes]
    data = dict(
        quick=args.quick,
        command=line,
        law=dict(name={2: "conserving", 3: "flow"}.get(args.time_scheme, str(args.time_scheme)), **law),
        tolerance_variable=tolerance_var,
        ladder=args.ladder,
        h=H,
        eps=list(EPS),
        roundoff=ROUNDOFF,
        twins=args.twins,
        quiet=QUIET,
        bands=list(BANDS),
        scenes=results,
        run=run_record(args.repo, wall0, cpu0),
    )
    out = args.out or args.repo / "docs" / "predictability.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(data, indent=1))
    print(
        f"wrote {out} ({data['run']['wall_s']:.0f} s wall, {data['run']['cpu_s']:.0f} s CPU); "
        "render it: python tools/render_docs.py performance.md"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
