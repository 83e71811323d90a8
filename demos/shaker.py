"""The two-way system model: a sine sweep drives a shaker's armature that carries PlateImpact's
clamp, run three ways and measured against each other (issue 27; docs/system-model.md):

- monolithic: PlateImpact.fmu alone with the armature inside (base_drive = force): the exact
  coupling through impacts, the reference;
- tlm: Shaker.fmu <-> PlateImpact.fmu through a transmission line (base_drive = tlm, coupling = 2):
  each side sends its mean outgoing wave, the line's energy is booked;
- force: Shaker.fmu <-> PlateImpact.fmu, armature velocity in, clamp force out, held values (the
  motion-in / force-out port), with libcosim's fixed step and with ECCO.

    bash run.sh                                        # builds build/PlateImpact.fmu (and its FMI 3.0 twin)
    bash scripts/setup.sh SineSweepFmu ShakerFmu       # builds build/SineSweep.fmu and build/Shaker.fmu
    .venv/bin/python demos/shaker.py --quick        # the suite's version: 1 s, 20 kg, impacts (~15 s)
    .venv/bin/python demos/shaker.py --mass 20 --duration 20 --step 1e-3 --coupling tlm --out out/run
    .venv/bin/python demos/shaker.py --master fmpy-ssp --mass 20 100 --step 1e-4 1e-3 --duration 20 \\
        --coupling tlm --out out/shaker_fmpy_ssp      # the line in fmpy's SSP master
    .venv/bin/python demos/shaker.py --goals --out docs/figures   # the issue's goals, one run, then:
    .venv/bin/python tools/render_docs.py system-model.md            # docs/system-model.md from shaker.json

The sweep's signal (SineSweep.fmu's output base_displacement, unit m) is connected as the drive
force (N): its `amplitude` is set in newtons; libcosim does not compare units.

--out DIR (default out/) gets shaker.json and shaker.png (the envelopes). The JSON has, per run: the coupling error (the energy the coupling created: drive work -
stored - losses, a line's energy in transit counting as stored and its loss as a loss), the drive
work, the largest clamp force, the impact count, and the deviations from the monolithic reference
(largest clamp force ratio, base acceleration envelope before the first impact, impact count);
the goals as measured; the constants of the set-up the page quotes.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from cosim import run_system, run_system_fmpy_ssp, system_energy

from plateimpact.fmufile import output_dir, require_fmu

# The plate: the default 14x5 Argyris plate (37.3 kg, first mode 5.95 Hz) with 2 % Rayleigh
# (mass-proportional) damping at its first mode, internal step dt = 1e-4 s.
F1 = 5.9459  # Hz, first mode of the default plate (docs/impact-laws.md)
PLATE_MASS = 37.3  # kg
PLATE = {"dt": 1e-4, "damping_mass": 2 * 0.02 * 2 * np.pi * F1}
# The sweep of the issue: 4 -> 8 Hz over 20 s, 500 N, 0.5 s ramp-in; obstacles at +-0.1 m.
SWEEP = {"amplitude": 500.0, "start_frequency": 4.0, "end_frequency": 8.0, "duration": 20.0, "ramp_time": 0.5}
GAP = 0.1
# --quick: the first second of the sweep with obstacles at +-0.025 m (impacts from 0.3 s on with a
# 20 kg armature; at +-0.02 m the armature's swing itself reaches the obstacles).
QUICK = {"mass": 20.0, "duration": 1.0, "gap": 0.025}
# The armature: a 2 Hz suspension with 10 % damping for any mass.
SUSPENSION_HZ, SUSPENSION_ZETA = 2.0, 0.1
# The line's impedance: Z = (M + m_p) 2 pi f1, the impedance of the moving mass (armature and plate)
# at the plate's first mode, where the coupling matters; the line then adds an inertia Z h and a
# compliance h / Z (docs/system-model.md: the choice, measured).
# ECCO (force coupling): the step may grow again after an impact (max_change_rate > 1) and the
# tolerances are on the scale of the bond's energy per step (500 N x 0.1 m/s x 1e-4 s = 5e-3 J):
# libcosimpy's defaults (max_change_rate 0.2) only let it shrink.
ECCO = {
    "safety_factor": 0.8,
    "step_size": 1e-4,
    "min_step_size": 1e-5,
    "max_step_size": 1e-3,
    "min_change_rate": 0.2,
    "max_change_rate": 1.5,
    "abs_tolerance": 1e-4,
    "rel_tolerance": 1e-2,
    "p_gain": 0.2,
    "i_gain": 0.15,
}
WINDOW = 0.25  # s, the envelope's window
# Where the envelope's windows start and how long they are: after the sweep's ramp-in, 0.25 s. A
# --quick run (1 s, first impact near 0.3 s) has no window before its first impact with those, so
# it takes windows of 0.05 s from 0.1 s on (the envelope's deviation then has four windows).
ENVELOPE = {"start": SWEEP["ramp_time"], "window": WINDOW}
QUICK_ENVELOPE = {"start": 0.1, "window": 0.05}
# Contact onsets within 10 ms of each other are one impact (the plate's first period is 170 ms;
# one impact chatters over a few ms).
EPISODE_SEPARATION = 0.01


def fmus(plate_fmu):
    """The three FMUs: PlateImpact.fmu at `plate_fmu`, SineSweep.fmu and Shaker.fmu beside it."""
    build = Path(plate_fmu).parent
    return {"sweep": build / "SineSweep.fmu", "shaker": build / "Shaker.fmu", "plate": Path(plate_fmu)}


def shaker_values(mass):
    k = mass * (2 * np.pi * SUSPENSION_HZ) ** 2
    return {"mass": mass, "stiffness": k, "damping": 2 * SUSPENSION_ZETA * np.sqrt(k * mass), "dt": 1e-5}


def impedance(mass, h):
    return (mass + PLATE_MASS) * 2 * np.pi * F1


def values(mass, h, gap, duration, z=None, dt=None):
    sweep = dict(SWEEP)
    plate = dict(PLATE, obstacle_lower=-gap, obstacle_upper=gap)
    if dt is not None:
        plate["dt"] = dt
    shaker = shaker_values(mass)
    shaker["tlm_impedance"] = plate["tlm_impedance"] = z if z is not None else impedance(mass, h)
    return {"sweep": sweep, "shaker": shaker, "plate": plate}


def frequency(t):
    f0, f1, d = SWEEP["start_frequency"], SWEEP["end_frequency"], SWEEP["duration"]
    return f0 + (f1 - f0) * np.minimum(t, d) / d


def envelope(t, a, end=None):
    """Amplitude of the base acceleration per window (sqrt(2) x RMS) from ENVELOPE's start (the
    ramp-in's end), up to `end`: window centres (s) and amplitudes."""
    end = t[-1] if end is None else min(end, t[-1])
    edges = np.arange(ENVELOPE["start"], end + 1e-12, ENVELOPE["window"])
    mid, amp = [], []
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = (t >= lo) & (t < hi)
        if sel.sum() < 2:
            continue
        mid.append(0.5 * (lo + hi))
        amp.append(np.sqrt(2 * np.mean(a[sel] ** 2)))
    return np.array(mid), np.array(amp)


def acceleration(run, position):
    """Times and the base acceleration from the second difference of `position` at the
    communication points (any spacing; ECCO's steps vary). With h = dt it is the scheme's own
    acceleration (clamp_acceleration); at larger h it averages over the step, where a point sample
    of the acceleration would pick up the step's jumps of a held wave (§19) at a fixed phase."""
    t, z = run["time"], run[position]
    h = np.diff(t)
    a = 2 * (np.diff(z[1:]) / h[1:] - np.diff(z[:-1]) / h[:-1]) / (h[1:] + h[:-1])
    return t[1:-1], a


def first_impact(run):
    onsets = run["plate.contact_onsets_lower"] + run["plate.contact_onsets_upper"]
    hit = np.nonzero(onsets > 0)[0]
    return run["time"][hit[0]] if len(hit) else np.inf


def impact_episodes(run, separation=EPISODE_SEPARATION):
    """Impacts as episodes: contact onsets (steps whose contact force starts from zero, the
    counters contact_onsets_*) closer than `separation` to the previous one belong to its episode. The
    onsets themselves are not a converged count: a vertex that chatters on the obstacle makes
    more of them at a smaller dt (docs/system-model.md)."""
    onsets = run["plate.contact_onsets_lower"] + run["plate.contact_onsets_upper"]
    onsets = run["time"][np.diff(np.concatenate([[0.0], onsets])) > 0]
    return int(len(onsets) and 1 + np.count_nonzero(np.diff(onsets) > separation))


def simulate(paths, coupling, mass, h, duration, gap, ecco=False, z=None, dt=None, master="libcosim"):
    """One run; a dict of its numbers (and the arrays under "run" when it finished). `dt`: the
    plate's internal step (default PLATE's)."""
    v = values(mass, h, gap, duration, z, dt)
    row = {
        "coupling": coupling + (" (ECCO)" if ecco else "" if master == "libcosim" else f" ({master})"),
        "master": "libcosim" if ecco else master,
        "mass": mass,
        "step": None if ecco else h,
        "dt": v["plate"]["dt"],
        "duration": duration,
        "gap": gap,
        "impedance": v["plate"]["tlm_impedance"] if coupling == "tlm" else None,
    }
    start = time.perf_counter()
    try:
        if master == "fmpy-ssp" and not ecco:  # the same system as an SSP file, fmpy's fixed-step master
            run = run_system_fmpy_ssp(paths, v, duration, coupling, h)
        else:
            run = run_system(paths, v, duration, coupling, h=None if ecco else h, ecco=ECCO if ecco else None)
    except RuntimeError as e:
        row.update(finished=False, failure=str(e), wall=time.perf_counter() - start)
        return row
    row["wall"] = time.perf_counter() - start
    e = system_energy(run, coupling)
    drive = float(e["drive_work"][-1])
    steps = np.diff(np.concatenate([[0.0], run["time"]]))
    row.update(
        finished=True,
        steps=len(steps),
        h_min=float(steps.min()),
        h_max=float(steps.max()),
        drive_work=drive,
        coupling_error=float(e["coupling_error"][-1]),
        max_coupling_error=float(np.abs(e["coupling_error"]).max()),
        relative_coupling_error=float(np.abs(e["coupling_error"]).max() / abs(drive)),
        line_energy=float(e["line"][-1]),
        line_loss=float(e["line_loss"][-1]),
        ledgers=float(e["ledgers"]),
        clamp_force_max=float(np.abs(run["plate.clamp_force"]).max()),
        impacts=impact_episodes(run),
        contact_onsets=int(run["plate.contact_onsets_lower"][-1] + run["plate.contact_onsets_upper"][-1]),
        first_impact=float(first_impact(run)),
        run=run,
    )
    t, a = envelope(*acceleration(run, "plate.clamp_displacement"))
    band = (frequency(t) > 5.0) & (frequency(t) < 7.0) & (t < row["first_impact"])
    if band.any():  # the force drop-out at the plate's first resonance
        i = np.argmin(np.where(band, a, np.inf))
        row["drop_frequency"], row["drop_amplitude"] = float(frequency(t[i])), float(a[i])
        for f in (5, 7):
            row[f"envelope_at_{f}hz"] = float(a[np.argmin(np.abs(frequency(t) - f))])
    return row


def compare(row, reference):
    """The deviations of a finished run from the monolithic reference (same mass)."""
    if not row.get("finished") or not reference.get("finished"):
        return
    run, ref = row["run"], reference["run"]
    end = min(row["first_impact"], reference["first_impact"])
    tc, ac = envelope(*acceleration(run, "plate.clamp_displacement"), end)
    tm, am = envelope(*acceleration(ref, "plate.clamp_displacement"), end)
    n = min(len(ac), len(am))
    if n:
        row["envelope_deviation"] = float(np.max(np.abs(ac[:n] - am[:n]) / am[:n]))
        row["envelope_deviation_of_peak"] = float(np.max(np.abs(ac[:n] - am[:n])) / am[:n].max())
        row["envelope_until"] = float(end)
    if "shaker.armature_displacement" in run:  # the shaker's table, beyond the line (§19)
        ts, as_ = envelope(*acceleration(run, "shaker.armature_displacement"), end)
        n = min(len(as_), len(am))
        if n:
            row["armature_envelope_deviation"] = float(np.max(np.abs(as_[:n] - am[:n]) / am[:n]))
    row["clamp_force_ratio"] = row["clamp_force_max"] / reference["clamp_force_max"]
    row["impact_count_deviation"] = (row["impacts"] - reference["impacts"]) / max(reference["impacts"], 1)


# The plate's dt ladder of --goals: how far the reference's impact count moves with its own dt,
# and the line at h = 1e-4 s on each (the master's step fixed, the plate's internal step refined).
LADDER = (5e-5, 2.5e-5, 1.25e-5)


def run_refinement(paths, mass, dts, duration, gap, log=print):
    """Per plate dt of `dts`: the monolithic reference and the line at h = 1e-4 s on that dt,
    compared with each other (rows tagged "ladder")."""
    rows = []
    for dt in dts:
        reference = simulate(paths, "monolithic", mass, dt, duration, gap, dt=dt)
        log(summary(reference))
        line = simulate(paths, "tlm", mass, 1e-4, duration, gap, dt=dt)
        compare(line, reference)
        log(summary(line))
        rows += [dict(reference, ladder=True), dict(line, ladder=True)]
    return rows


def run_ssp_runs(paths, masses, steps, duration, gap, rows, log=print):
    """The line through fmpy's SSP master, compared with the libcosim matrix's references."""
    out = []
    for mass in masses:
        reference = next(r for r in rows if r["coupling"] == "monolithic" and r["mass"] == mass)
        for h in steps:
            row = simulate(paths, "tlm", mass, h, duration, gap, master="fmpy-ssp")
            compare(row, reference)
            log(summary(row))
            out.append(row)
    return out


def run_matrix(paths, masses, steps, couplings, duration, gap, ecco, z=None, log=print, master="libcosim"):
    """Every run of the matrix; the monolithic reference per mass at the plate's own step (its
    result does not depend on the master's step beyond the force's reconstruction)."""
    rows = []
    for mass in masses:
        reference = simulate(paths, "monolithic", mass, PLATE["dt"], duration, gap, master=master)
        rows.append(reference)
        log(summary(reference))
        runs = [(c, h, False) for c in couplings if c != "monolithic" for h in steps]
        if ecco:
            runs.append(("force", None, True))
        for coupling, h, use_ecco in runs:
            row = simulate(paths, coupling, mass, h or PLATE["dt"], duration, gap, use_ecco, z, master=master)
            compare(row, reference)
            rows.append(row)
            log(summary(row))
    return rows


def summary(r):
    head = f"{r['coupling']:>13} M = {r['mass']:g} kg h = {r['step'] or 'ECCO'}: "
    if not r["finished"]:
        return head + f"FAILED ({r['failure'][:90]}) after {r['wall']:.0f} s"
    text = (
        f"drive {r['drive_work']:.4g} J, coupling error {r['max_coupling_error']:.2e} J "
        f"({r['relative_coupling_error']:.1e}), clamp force max {r['clamp_force_max']:.4g} N, "
        f"{r['impacts']} impacts ({r['contact_onsets']} onsets), line {r['line_energy']:.2e} J stored {r['line_loss']:.2e} J lost, {r['wall']:.0f} s"
    )
    if "clamp_force_ratio" in r:
        text += (
            f"; vs monolithic: force x{r['clamp_force_ratio']:.2f}, impacts {r['impact_count_deviation']:+.1%}, "
            + (
                f"envelope {r['envelope_deviation']:.1%}"
                if "envelope_deviation" in r
                else f"envelope n/a (no {ENVELOPE['window']:g} s window from {ENVELOPE['start']:g} s before the first impact)"
            )
        )
    return head + text


def figure(rows, path):
    """The envelopes per mass into `path`; returns [(label, number of points)] of the curves drawn."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    masses = sorted({r["mass"] for r in rows})
    fig, axes = plt.subplots(len(masses), 1, figsize=(8.5, 3.6 * len(masses)), squeeze=False)
    drawn = []
    for ax, mass in zip(axes[:, 0], masses):
        for r in (r for r in rows if r["mass"] == mass and r.get("finished")):
            run = r["run"]
            t, a = envelope(*acceleration(run, "plate.clamp_displacement"))
            label = r["coupling"] + ("" if r["step"] is None else f" h = {r['step']:g} s")
            style = {"lw": 2.5, "color": "k"} if r["coupling"] == "monolithic" else {"lw": 1}
            (line,) = ax.semilogy(frequency(t), a, label=label + " (clamp)", marker=".", ms=3, **style)
            drawn.append((label + " (clamp)", len(t)))
            if "shaker.armature_displacement" in run:  # the shaker's table, beyond the line
                t, a = envelope(*acceleration(run, "shaker.armature_displacement"))
                ax.semilogy(frequency(t), a, ls="--", lw=1, color=line.get_color(), label=label + " (armature)")
                drawn.append((label + " (armature)", len(t)))
        for r in (r for r in rows if r["mass"] == mass and not r.get("finished")):
            ax.plot([], [], " ", label=f"{r['coupling']} h = {r['step'] or 'ECCO'}: failed")
        ax.axvline(F1, color="gray", ls=":")
        ax.set_title(
            f"armature {mass:g} kg: base acceleration envelope, 500 N sweep, obstacles ±{rows[0]['gap']:g} m",
            fontsize=10,
        )
        ax.set_xlabel("sweep frequency [Hz]")
        ax.set_ylabel(f"√2·RMS over {ENVELOPE['window']:g} s [m/s²]")
        ax.set_ylim(0.5, 1e5)
        ax.legend(fontsize=6, ncol=2, loc="upper left")
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return drawn


def public(row):
    return {k: v for k, v in row.items() if k != "run"}


def goals(rows):
    """The issue's goals, each as (goal, measured, met) from the matrix's rows."""
    out = []
    coupled = [r for r in rows if r["coupling"] == "tlm"]
    refs = {r["mass"]: r for r in rows if r["coupling"] == "monolithic"}
    done = all(r["finished"] for r in coupled)
    out.append(
        (
            "every run of the line coupling finishes (20 and 100 kg, h = 1e-4 and 1e-3 s)",
            f"{sum(r['finished'] for r in coupled)} of {len(coupled)}",
            done,
        )
    )
    ratios = [r.get("clamp_force_ratio", np.inf) for r in coupled]
    out.append(
        (
            "largest clamp force within 2x the monolithic run's",
            ", ".join(f"x{x:.2f}" for x in ratios),
            all(x <= 2.0 for x in ratios),
        )
    )
    errors = [r.get("relative_coupling_error", np.inf) for r in coupled]
    out.append(
        (
            "|coupling error| <= 1e-3 of the drive work (line's transit stored, its loss a loss)",
            "max " + format(max(errors), ".1e"),
            max(errors) <= 1e-3,
        )
    )
    ledgers = [r["relative_coupling_error"] for r in refs.values() if r["finished"]]
    out.append(
        (
            "the monolithic ledger closes to roundoff through impacts",
            "max " + format(max(ledgers), ".1e") + " of the drive work",
            max(ledgers) <= 1e-9,
        )
    )
    fine = [r for r in coupled if r["step"] == 1e-4 and r["finished"]]
    env = [r.get("envelope_deviation", np.inf) for r in fine]
    out.append(
        (
            "base acceleration envelope within 5 % of the monolithic before the first impact at h = 1e-4 s",
            ", ".join(f"{x:.1%}" for x in env),
            all(x <= 0.05 for x in env),
        )
    )
    counts = [(r["impacts"], refs[r["mass"]]["impacts"]) for r in fine]
    dev = [abs(a - b) / max(b, 1) for a, b in counts]
    out.append(
        (
            "impact count over the sweep within 5 % (h = 1e-4 s)",
            ", ".join(f"{a} vs {b}" for a, b in counts),
            all(d <= 0.05 for d in dev),
        )
    )
    ssp = [r for r in rows if r.get("master") == "fmpy-ssp"]
    if ssp:
        worst = max(r.get("relative_coupling_error", np.inf) for r in ssp)
        out.append(
            (
                "the line in fmpy's SSP master: every run finishes, |coupling error| <= 1e-3 of the drive work",
                f"{sum(r['finished'] for r in ssp)} of {len(ssp)}, max {worst:.1e}",
                all(r["finished"] for r in ssp) and worst <= 1e-3,
            )
        )
    return out


def document(rows, refinement, command):
    """What docs/system-model.md's two-way section is filled from: the runs, the goals and the set-up."""
    return dict(
        command=command,
        setup=dict(
            sweep=SWEEP,
            suspension_hz=SUSPENSION_HZ,
            suspension_zeta=SUSPENSION_ZETA,
            plate_dt=PLATE["dt"],
            f1=F1,
            plate_mass=PLATE_MASS,
            gap=rows[0]["gap"],
            ecco=ECCO,
            episode_separation=EPISODE_SEPARATION,
            impedances=[[m, impedance(m, 1e-4)] for m in sorted({r["mass"] for r in rows})],
        ),
        rows=[public(r) for r in rows],
        refinement=[public(r) for r in refinement],
        goals=[dict(goal=g, measured=m, met=bool(ok)) for g, m, ok in goals(rows)],
    )


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="build/PlateImpact.fmu", help="SineSweep.fmu and Shaker.fmu beside it")
    ap.add_argument(
        "--quick",
        action="store_true",
        help="1 s, 20 kg, obstacles +-0.025 m, h = 1e-4 s and ECCO, envelope windows of 0.05 s from 0.1 s (the suite)",
    )
    ap.add_argument("--goals", action="store_true", help="the issue's matrix: 20 and 100 kg x h = 1e-4, 1e-3 s")
    ap.add_argument("--mass", type=float, nargs="+", default=[20.0], help="armature mass(es), kg")
    ap.add_argument("--duration", type=float, default=SWEEP["duration"], help="simulated time, s")
    ap.add_argument("--step", type=float, nargs="+", default=[1e-4], help="communication step(s) h, s")
    ap.add_argument("--gap", type=float, default=GAP, help="obstacles at +-gap, m")
    ap.add_argument(
        "--coupling", nargs="+", default=["tlm", "force"], choices=["tlm", "force"], help="besides the monolithic"
    )
    ap.add_argument("--impedance", type=float, help="the line's Z, N s/m (default (M + m_p) 2 pi f1)")
    ap.add_argument("--ecco", action="store_true", help="also the force coupling under ECCO")
    ap.add_argument(
        "--master",
        default="libcosim",
        choices=["libcosim", "fmpy-ssp"],
        help="libcosim's fixed step, or the system as an SSP file run by fmpy's SSP master (not ECCO)",
    )
    ap.add_argument("--out", default="out", help="shaker.json and shaker.png go here (docs: docs/figures)")
    args = ap.parse_args(argv)
    masses, steps, duration, gap, ecco = args.mass, args.step, args.duration, args.gap, args.ecco
    if args.quick:
        masses, steps, duration, gap, ecco = [QUICK["mass"]], [1e-4], QUICK["duration"], QUICK["gap"], True
        ENVELOPE.update(QUICK_ENVELOPE)
    if args.goals:
        masses, steps, ecco = [20.0, 100.0], [1e-4, 1e-3], True
    for name, x in (("--mass", min(masses)), ("--step", min(steps)), ("--duration", duration), ("--gap", gap)):
        if not x > 0:
            ap.error(f"{name} must be > 0")
    if args.impedance is not None and not args.impedance > 0:
        ap.error("--impedance must be > 0")
    paths = {k: require_fmu(v, "shaker") for k, v in fmus(args.fmu).items()}
    rows = run_matrix(
        paths,
        masses,
        steps,
        args.coupling,
        duration,
        gap,
        ecco,
        args.impedance,
        log=lambda s: print(s, file=sys.stderr),
        master=args.master,
    )
    refinement = []
    if args.goals:  # the line in fmpy's SSP master; the reference's own dt dependence, 20 kg
        rows += run_ssp_runs(paths, masses, steps, duration, gap, rows, log=lambda s: print(s, file=sys.stderr))
        refinement = run_refinement(paths, 20.0, LADDER, duration, gap, log=lambda s: print(s, file=sys.stderr))
    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never a full run's files
    command = "demos/shaker.py " + " ".join(argv if argv is not None else sys.argv[1:])
    (out / "shaker.json").write_text(json.dumps(document(rows, refinement, command), indent=1, default=float))
    figure([r for r in rows if r.get("master") != "fmpy-ssp"], out / "shaker.png")  # libcosim's curves
    print(f"wrote {out / 'shaker.json'} and {out / 'shaker.png'}", file=sys.stderr)
    return rows + refinement


if __name__ == "__main__":
    main()
