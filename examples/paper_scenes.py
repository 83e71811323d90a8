"""Reproduce the numerical experiments of Pozzolini, Renard & Salaün (2013), §5, with both elements.

Scenes (the paper's figure numbers):
  5–7    forced oscillation, base 0.09 sin(2π·10 t), obstacles ±0.1 m, Δt = 1e-3, 1e-4, 1e-5
  8      obstacles ±0.01 m at Δt = 1e-6 (base amplitude 0.009 m, see below), short horizon
  9–11   forced oscillation at 10, 15, 20, 25, 30, 35 Hz, Δt = 1e-3
  12–16  free vibration: released at rest from the static shape under 8600 Pa, lower obstacle
         only (−0.1 m); corners and free-edge midpoint, Δt = 1e-5, zoom at Δt = 5e-6
  17–18  energy of the free vibration for several Δt
  (extra) energy lost in impacts against Δt, forced and free, down to Δt = 2.5e-6

Meshes: 140 Argyris triangles = 14×5 cells (figures 5–11; 160 = 16×5 for 13, 16, 18, as the
captions say) and 140 FVS quadrilaterals = 20×7 cells.

The FMU keeps the clamped edge between the obstacles (the clamp is a mesh vertex line, the
obstacles are flat and fixed): with ±0.01 m obstacles the paper's amplitude 0.09 m is not
admissible, so figure 8 uses 0.009 m, the paper's ratio amplitude/gap = 0.9. The model is
linear and the obstacles are homogeneous, so that scene is the ±0.1 m scene scaled by 1/10.

Writes the PNGs and two CSVs to --out (default out/; the docs page's: --out docs/figures):
  paper_scenes.csv           one row per simulation: scene, element, mesh, Δt, wall time and
                             the numbers docs/paper-scenes.md quotes
  paper_scenes_elements.csv  Argyris against FVS for the same scene and Δt

    python examples/paper_scenes.py --out docs/figures   # full run, a few minutes
    python tools/render_docs.py paper-scenes.md   # docs/paper-scenes.md's tables from the CSVs
    python examples/paper_scenes.py --quick --out /tmp/ps   # smoke test, short horizons
"""

from __future__ import annotations

import argparse
import csv
import math
import time

import numpy as np

from plateimpact import PlateImpactFMU, sine
from plateimpact.fmufile import output_dir, require_fmu
from plateimpact.scenes import AMPLITUDE

MESHES = {"argyris": (14, 5), "fvs": (20, 7)}
MESHES_FREE = {"argyris": (16, 5), "fvs": (20, 7)}  # figs 13, 16, 18: "160 Argyris triangles"
LABEL = {"argyris": "Argyris", "fvs": "FVS"}


def elements(el, nx, ny):
    """Element count of an nx x ny mesh: two Argyris triangles or one FVS quadrilateral per cell."""
    return nx * ny * (2 if el == "argyris" else 1)


def mesh_text(meshes):
    """The meshes as a title says them: "Argyris 140 (14×5), FVS 140 (20×7) elements"."""
    return ", ".join(f"{LABEL[el]} {elements(el, nx, ny)} ({nx}×{ny})" for el, (nx, ny) in meshes.items()) + " elements"


SERIES = (
    "time",
    "base",
    "corner_1",
    "corner_2",
    "free_edge_mid",
    "energy",
    "energy_dissipated",
    "energy_input",
    "contact_vertices",
)
RUN_COLUMNS = (
    "scene",
    "element",
    "nx",
    "ny",
    "dt",
    "comm_step",
    "stop_time",
    "wall_s",
    "max_abs_corner",
    "max_abs_c1_minus_c2",
    "c1_c2_split_time",
    "max_abs_c1_minus_mid",
    "first_contact_time",
    "contact_episodes",
    "energy_initial",
    "energy_final",
    "energy_dissipated",
    "energy_input",
    "ledger_residual",
    "energy_drift_without_contact",
    "rms_corner",
    "first_peak",
    "last_peak",
    "peak_count",
    "peak_rises",
)
PAIR_COLUMNS = (
    "scene",
    "dt",
    "first_contact_time",
    "max_abs_diff_precontact",
    "horizon_short",
    "max_abs_diff_short",
    "max_abs_diff_all",
    "rms_corner_argyris",
    "rms_corner_fvs",
    "energy_dissipated_argyris",
    "energy_dissipated_fvs",
    "contact_episodes_argyris",
    "contact_episodes_fvs",
    "max_abs_corner_argyris",
    "max_abs_corner_fvs",
)


def simulate(
    fmu,
    element,
    dt,
    stop,
    comm,
    amplitude=0.0,
    frequency=10.0,
    lower=-0.1,
    upper=0.1,
    initial_load=0.0,
    mesh=(14, 5),
):
    """One run; returns (dict of numpy arrays over the communication points, wall seconds)."""
    nx, ny = mesh
    params = dict(element=element, nx=nx, ny=ny, dt=dt, initial_load=initial_load)
    for side, g in (("lower", lower), ("upper", upper)):
        if g is None:
            params[f"obstacle_{side}_enabled"] = False
        else:
            params[f"obstacle_{side}"] = g
    n = round(stop / comm)
    rows = np.empty((n + 1, len(SERIES)))
    t0 = time.perf_counter()
    with PlateImpactFMU(fmu, **params) as plate:
        for k in range(n + 1):
            if k:
                plate.step(comm, base=sine(amplitude, frequency, (k - 1) * comm) if amplitude else None)
            o = plate.outputs()
            t = k * comm
            rows[k] = (t, sine(amplitude, frequency, t)[0], *(o[s] for s in SERIES[2:]))
    wall = time.perf_counter() - t0
    return {s: rows[:, i] for i, s in enumerate(SERIES)} | {"nx": nx, "ny": ny}, wall


def contact_episodes(r):
    """Impacts counted as runs of communication steps in which energy was dissipated."""
    active = np.diff(r["energy_dissipated"]) > 1e-12 * max(1.0, r["energy_dissipated"][-1])
    return int(np.count_nonzero(active[1:] & ~active[:-1]) + (1 if active[:1].any() else 0))


def upward_peaks(t, x, threshold, separation=0.08):
    """Values of the upward peaks of x above threshold, at least `separation` s apart."""
    from scipy.signal import find_peaks

    step = t[1] - t[0] if len(t) > 1 else 1.0
    i, _ = find_peaks(x, height=threshold, distance=max(1, int(separation / step)))
    return [float(x[j]) for j in i]


def metrics(scene, element, dt, comm, stop, r, wall):
    c1, c2, mid = r["corner_1"], r["corner_2"], r["free_edge_mid"]
    split = np.abs(c1 - c2) > 1e-3
    contact = r["contact_vertices"] > 0
    e, ed, ei = r["energy"], r["energy_dissipated"], r["energy_input"]
    no_work = (np.diff(ed) == 0) & (np.diff(ei) == 0)
    peaks = upward_peaks(r["time"], c1, 0.3 * np.max(np.abs(c1))) if np.any(c1) else []
    return {
        "scene": scene,
        "element": element,
        "nx": r["nx"],
        "ny": r["ny"],
        "dt": dt,
        "comm_step": comm,
        "stop_time": stop,
        "wall_s": round(wall, 3),
        "max_abs_corner": float(np.max(np.abs(np.r_[c1, c2]))),
        "max_abs_c1_minus_c2": float(np.max(np.abs(c1 - c2))),
        # first time the two corners are 1 mm apart (NaN: never)
        "c1_c2_split_time": float(r["time"][np.argmax(split)]) if split.any() else math.nan,
        "max_abs_c1_minus_mid": float(np.max(np.abs(c1 - mid))),
        "first_contact_time": float(r["time"][np.argmax(contact)]) if contact.any() else math.nan,
        "contact_episodes": contact_episodes(r),
        "energy_initial": float(e[0]),
        "energy_final": float(e[-1]),
        "energy_dissipated": float(ed[-1]),
        "energy_input": float(ei[-1]),
        "ledger_residual": float(np.max(np.abs(e - (e[0] + ei - ed)))),
        "energy_drift_without_contact": float(np.max(np.abs(np.diff(e)[no_work]), initial=0.0)),
        "rms_corner": float(np.sqrt(np.mean(c1**2))),
        "first_peak": peaks[0] if peaks else math.nan,
        "last_peak": peaks[-1] if peaks else math.nan,
        "peak_count": len(peaks),
        "peak_rises": int(np.count_nonzero(np.diff(peaks) > 0)),
    }


def compare(scene, dt, ra, rf, ma, mf):
    """Argyris against FVS: corner_1 before the first contact (linear regime), to 10 ms after
    it (before impacts make the trajectories diverge) and over the whole run."""
    t = ra["time"]
    firsts = [x for x in (ma["first_contact_time"], mf["first_contact_time"]) if x == x]
    first = min(firsts) if firsts else float(t[-1])
    short = float(min(t[-1], first + 0.01))
    d = np.abs(ra["corner_1"] - rf["corner_1"])
    return {
        "scene": scene,
        "dt": dt,
        "first_contact_time": first,
        "max_abs_diff_precontact": float(d[t < first - 1e-12].max(initial=0.0)),
        "horizon_short": short,
        "max_abs_diff_short": float(d[t <= short + 1e-12].max()),
        "max_abs_diff_all": float(d.max()),
        "rms_corner_argyris": ma["rms_corner"],
        "rms_corner_fvs": mf["rms_corner"],
        "energy_dissipated_argyris": ma["energy_dissipated"],
        "energy_dissipated_fvs": mf["energy_dissipated"],
        "contact_episodes_argyris": ma["contact_episodes"],
        "contact_episodes_fvs": mf["contact_episodes"],
        "max_abs_corner_argyris": ma["max_abs_corner"],
        "max_abs_corner_fvs": mf["max_abs_corner"],
    }


# -- plots -------------------------------------------------------------------------------------
def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # thousands of impact wiggles per curve: unsmoothed lines keep the PNGs small (< 150 KB)
    matplotlib.rcParams["lines.antialiased"] = False
    return plt


def _obstacles(ax, gaps):
    for g in gaps:
        ax.axhline(g, color="k", lw=0.8)


def plot_corners_grid(path, runs, rows_keys, title_fn, gaps, suptitle, base=True, mid=False, window=None):
    """Rows: the keys (e.g. Δt); columns: FVS, Argyris; corner_1, corner_2 (and midpoint)."""
    plt = _plt()
    fig, axes = plt.subplots(
        len(rows_keys), 2, figsize=(11, 2.6 * len(rows_keys) + 0.6), sharex=True, sharey=True, squeeze=False
    )
    for i, key in enumerate(rows_keys):
        for j, el in enumerate(("fvs", "argyris")):
            ax = axes[i, j]
            r = runs[(key, el)]
            t = r["time"]
            k = np.ones_like(t, bool) if window is None else (t >= window[0]) & (t <= window[1])
            if base:
                ax.plot(t[k], r["base"][k], color="0.65", lw=0.7, label="base")
            ax.plot(t[k], r["corner_1"][k], color="C0", lw=1.8, label="corner_1 (L, 0)")
            ax.plot(t[k], r["corner_2"][k], color="C3", lw=0.8, ls="--", label="corner_2 (L, W)")
            if mid:
                ax.plot(t[k], r["free_edge_mid"][k], color="C2", lw=0.8, ls=":", label="free_edge_mid (L, W/2)")
            _obstacles(ax, gaps)
            ax.set_title(title_fn(key, el, r), fontsize=9)
            if j == 0:
                ax.set_ylabel("w [m]")
        axes[0, 0].legend(loc="best", fontsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    fig.suptitle(suptitle, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_frequencies(path, runs, freqs, gap):
    plt = _plt()
    nrow = math.ceil(len(freqs) / 2)
    fig, axes = plt.subplots(nrow, 2, figsize=(11, 2.4 * nrow + 0.6), sharey=True, squeeze=False)
    for ax, f in zip(axes.flat, freqs):
        for el, c, ls in (("fvs", "C1", "-"), ("argyris", "C0", "--")):
            r = runs[(f, el)]
            ax.plot(r["time"], r["corner_1"], color=c, ls=ls, lw=0.7, label=f"{LABEL[el]} {r['nx']}×{r['ny']} corner_1")
        ax.plot(r["time"], r["base"], color="0.65", lw=0.6, label="base")
        _obstacles(ax, (-gap, gap))
        ax.set_title(f"{f:g} Hz", fontsize=9)
        ax.set_ylabel("w [m]")
    for ax in axes[-1]:
        ax.set_xlabel("time [s]")
    axes[0, 0].legend(loc="lower right", fontsize=7)
    fig.suptitle(f"Figs 9–11: base {AMPLITUDE:g} sin(2πf t), obstacles ±0.1 m, Δt = 1e-3 s", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_convergence(path, forced, free, forced_dts, free_dts):
    """The converging quantity: energy lost in impacts over the whole run, against Δt."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8))
    for ax, runs, dts, title in (
        (axes[0], forced, forced_dts, "forced, 10 Hz, ±0.1 m"),
        (axes[1], free, free_dts, "free vibration, 8600 Pa release"),
    ):
        for el, marker, color in (("fvs", "s", "C1"), ("argyris", "o", "C0")):
            r0 = runs[(dts[0], el)]
            y = [runs[(dt, el)]["energy_dissipated"][-1] for dt in dts]
            ax.semilogx(dts, y, marker=marker, color=color, label=f"{LABEL[el]} {r0['nx']}×{r0['ny']}")
        T = runs[(dts[0], "fvs")]["time"][-1]
        ax.set_title(f"{title}: energy dissipated over {T:g} s", fontsize=9)
        ax.set_xlabel("Δt [s]")
        ax.set_ylabel("J")
        ax.grid(True, which="major", color="0.85")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_energy(path, runs, dts):
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, el in zip(axes, ("fvs", "argyris")):
        for i, dt in enumerate(dts):
            r = runs[(dt, el)]
            ax.plot(r["time"], r["energy"], lw=1.0, color=f"C{i}", label=f"Δt = {dt:g} s")
        nx, ny = r["nx"], r["ny"]
        n_el = elements(el, nx, ny)
        ax.set_title(f"{LABEL[el]}, {n_el} elements ({nx}×{ny})", fontsize=9)
        ax.set_xlabel("time [s]")
        ax.legend(fontsize=8)
    axes[0].set_ylabel("energy [J]")
    fig.suptitle("Figs 17–18: total energy in free vibration (8600 Pa release, lower obstacle at −0.1 m)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


# -- the experiments ---------------------------------------------------------------------------
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fmu", default="build/PlateImpact.fmu")
    ap.add_argument("--out", default="out", help="PNGs and CSVs go here (docs/paper-scenes.md: --out docs/figures)")
    ap.add_argument(
        "--quick", action="store_true", help="short horizons, just past the first impacts, coarse meshes (smoke test)"
    )
    args = ap.parse_args(argv)
    args.fmu = str(require_fmu(args.fmu, "paper_scenes"))
    out = output_dir(args.out, args.quick)  # --quick: <out>/quick/, never a full run's files
    q = args.quick
    meshes, meshes_free = MESHES, MESHES_FREE
    if q:  # coarse meshes: the Argyris 14x5 setup alone takes about a second
        meshes = meshes_free = {"argyris": (7, 2), "fvs": (10, 3)}
    results, pairs = [], []
    wall0 = time.perf_counter()
    _experiments(args, out, q, meshes, meshes_free, results, pairs)  # the FMU extracted once for all runs
    with (out / "paper_scenes.csv").open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=RUN_COLUMNS)
        w.writeheader()
        w.writerows(results)
    with (out / "paper_scenes_elements.csv").open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=PAIR_COLUMNS)
        w.writeheader()
        w.writerows(pairs)
    print(
        f"{len(results)} runs in {time.perf_counter() - wall0:.0f} s; wrote PNGs, "
        f"paper_scenes.csv and paper_scenes_elements.csv to {out}"
    )


def _experiments(args, out, q, meshes, meshes_free, results, pairs):
    # --quick: just past the first impacts (forced near 0.05 s, the free vibration near 0.068 s on the
    # coarse meshes), so that its rows count contacts
    T_forced, T_gap, T_freq, T_free = (0.06, 0.005, 0.03, 0.08) if q else (1.0, 0.3, 1.0, 2.0)
    free_dts = (1e-3, 1e-4, 1e-5, 5e-6, 2.5e-6)
    freqs = (10, 15, 20, 25, 30, 35)

    def run(scene, key, el, dt, stop, comm, store, free=False, **kw):
        r, wall = simulate(args.fmu, el, dt, stop, comm, mesh=(meshes_free if free else meshes)[el], **kw)
        m = metrics(scene, el, dt, comm, stop, r, wall)
        results.append(m)
        store[(key, el)] = r
        print(
            f"  {scene:<8} {el:<8} {m['nx']}x{m['ny']} dt={dt:<7g} {stop:g} s in {wall:6.2f} s"
            f"  max|c1-c2|={m['max_abs_c1_minus_c2']:.2e}  dissipated {m['energy_dissipated']:.4g} J"
            f"  contacts {m['contact_episodes']}",
            flush=True,
        )
        return m

    def run_pair(scene, key, dt, stop, comm, store, **kw):
        ma = run(scene, key, "argyris", dt, stop, comm, store, **kw)
        mf = run(scene, key, "fvs", dt, stop, comm, store, **kw)
        pairs.append(compare(scene, dt, store[(key, "argyris")], store[(key, "fvs")], ma, mf))

    print("Figs 5-7: forced oscillation, obstacles ±0.1 m (and 5e-6, 2.5e-6 for convergence)")
    forced = {}
    forced_dts = (1e-3, 1e-4, 1e-5, 5e-6, 2.5e-6)
    for dt in forced_dts:
        run_pair("forced", dt, dt, T_forced, max(dt, 1e-4), forced, amplitude=AMPLITUDE)
    plot_corners_grid(
        out / "paper_fig05-07_forced.png",
        forced,
        (1e-3, 1e-4, 1e-5),
        lambda dt, el, r: (
            f"{LABEL[el]} {r['nx']}×{r['ny']}, Δt = {dt:g} s: "
            f"max|c1−c2| = {np.max(np.abs(r['corner_1'] - r['corner_2'])):.1e} m"
        ),
        (-0.1, 0.1),
        f"Figs 5–7: base {AMPLITUDE:g} sin(2π·10 t), obstacles ±0.1 m, {mesh_text(meshes)}",
    )

    print("Fig 8: obstacles ±0.01 m, base amplitude 0.009 m")
    gap = {}
    for dt in (1e-5, 1e-6):
        run_pair("gap", dt, dt, T_gap, 1e-5, gap, amplitude=0.009, lower=-0.01, upper=0.01)
    plot_corners_grid(
        out / "paper_fig08_gap.png",
        gap,
        (1e-6,),
        lambda dt, el, r: (
            f"{LABEL[el]} {r['nx']}×{r['ny']}, Δt = {dt:g} s: "
            f"max|c1−c2| = {np.max(np.abs(r['corner_1'] - r['corner_2'])):.1e} m"
        ),
        (-0.01, 0.01),
        "Fig 8: base 0.009 sin(2π·10 t), obstacles ±0.01 m, Δt = 1e-6 s",
    )

    print("Figs 9-11: 10 to 35 Hz, Δt = 1e-3")
    freq = {}
    for f in freqs:
        run_pair(f"freq{f}", f, 1e-3, T_freq, 1e-3, freq, amplitude=AMPLITUDE, frequency=f)
    plot_frequencies(out / "paper_fig09-11_frequencies.png", freq, freqs, 0.1)

    print("Figs 12-18: free vibration from the 8600 Pa static shape, lower obstacle only")
    free = {}
    for dt in free_dts:
        run_pair(
            "free",
            dt,
            dt,
            T_free,
            max(dt, 1e-4) if dt >= 1e-4 else 5e-5,
            free,
            lower=-0.1,
            upper=None,
            initial_load=8600.0,
            free=True,
        )
    plot_corners_grid(
        out / "paper_fig12-13_free.png",
        free,
        (1e-5,),
        lambda dt, el, r: (
            f"{LABEL[el]} {r['nx']}×{r['ny']}, Δt = {dt:g} s: max|c1−mid| = "
            f"{np.max(np.abs(r['corner_1'] - r['free_edge_mid'])):.1e} m"
        ),
        (-0.1,),
        "Figs 12–13: free vibration, corners and free-edge midpoint",
        base=False,
        mid=True,
    )
    zoom = (0.305, 0.325) if not q else (0.0, T_free)
    plot_corners_grid(
        out / "paper_fig14-16_free_zoom.png",
        free,
        (1e-5, 5e-6),
        lambda dt, el, r: f"{LABEL[el]} {r['nx']}×{r['ny']}, Δt = {dt:g} s (zoom)",
        (),
        f"Figs 14–16: zoom on t ∈ [{zoom[0]:g}, {zoom[1]:g}] s",
        base=False,
        mid=True,
        window=zoom,
    )
    plot_energy(out / "paper_fig17-18_energy.png", free, free_dts)
    plot_convergence(out / "paper_dt_convergence.png", forced, free, forced_dts, free_dts)


if __name__ == "__main__":
    main()
