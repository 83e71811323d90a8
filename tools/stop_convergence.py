"""Convergence before the horizon (issue 52, item 2): the stop under the tip under time-step and
mesh refinement, corner_1 against the finest run of each ladder. Writes docs/stop_convergence.json,
which tools/render_docs.py renders into docs/performance.md ("Stops: convergence before the
horizon"); the scene's predictability horizon is its row of docs/predictability.json
(tools/predictability.py, scene `tip_stop`), computed there as for the other scenes.

    .venv/bin/python tools/stop_convergence.py               # about 2.5 min CPU of one core, most in 48×16
    .venv/bin/python tools/render_docs.py performance.md
    .venv/bin/python tools/stop_convergence.py --quick --out /tmp/sc.json   # a smoke run

The scene is predictability.SCENES["tip_stop"] (Argyris 12×4, a lower stop over x ≥ 1.0 m at
−0.05 m, the upper obstacle off, base 0.09 sin(2π·10 t) m), run by predictability.simulate (fmpy,
the base and its derivatives set at every communication point, corner_1 read every
predictability.H) with the law of the predictability study (flow: mass = singular_p0,
time_scheme = flow). Two ladders and a control:

  - dt: the scene's mesh at dt = 2e-5 … 6.25e-7 s (halved each time); the reference is the finest.
  - mesh: 6×2, 12×4, 24×8, 48×16 cells (h halves; x = 1.0 m is a mesh line of each, so the stop's
    rectangle has its edge on the mesh) at dt = MESH_DT; the reference is the finest. The finest
    mesh is run again at MESH_DT/2: the time error of the mesh reference, to set beside the mesh
    differences.
  - free flight, the control: the same meshes and dt with no obstacle at all, to FREE_STOP — what
    the law's mesh convergence is before any contact, so that what the stop adds shows.

Per window [0, T] (T in WINDOWS, up to the ladder's stop): the error of each level, max |corner_1 −
reference| over the outputs t ≤ T; the successive differences d_k = max |corner_1(k) −
corner_1(k+1)|, their ratios and observed orders −log2(d_{k+1}/d_k) (dt and h halve); the verdict
of impact_study.verdict on the ratios (converges when the last two are ≤ 0.6, i.e. an order ≥ 0.74;
does not converge when the last is ≥ 0.9; unclear otherwise). A ladder converges up to the last
window that converges before the first that does not. The t* (predictability.horizon) of each
pair of neighbouring levels: when two levels part by 1e-4, 1e-5, 1e-6 m.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import impact_study as study
import numpy as np
import predictability as pr
from checkout import add_checkout_arguments, fmu_path
from impact_convergence import nan_none

SCENE = pr.SCENES["tip_stop"]
LAW = pr.LAWS["flow"]
DTS = (2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6, 6.25e-7)  # s, on the scene's mesh
MESHES = ((6, 2), (12, 4), (24, 8), (48, 16))  # cells: h = 0.2, 0.1, 0.05, 0.025 m
MESH_DT = 2.5e-6  # s, the mesh ladder's step
WINDOWS = (0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.7, 1.0)  # s; the first landings: 0.015-0.017 s
DT_STOP, MESH_STOP, FREE_STOP = 1.0, 0.5, 0.1  # s, how long each ladder runs


def run(fmu, params, stop, label):
    return pr.simulate(fmu, SCENE, dict(SCENE.params, **LAW, **params), stop, label)


def ladder(series, stop, windows):
    """The errors against the finest level, the successive differences, ratios, orders and
    verdicts of each window [0, T] with T <= stop; and the t* of neighbouring levels."""
    reference = series[-1]
    rows = []
    for window in (w for w in windows if w <= stop + 1e-12):
        m = reference.t <= window + 1e-12
        errors = [float(np.max(np.abs(s.corner[m] - reference.corner[m]))) for s in series[:-1]]
        diffs = [float(np.max(np.abs(a.corner[m] - b.corner[m]))) for a, b in zip(series, series[1:])]
        ratios = [b / a if a > 0 else float("nan") for a, b in zip(diffs, diffs[1:])]
        rows.append(
            dict(
                window=window,
                errors=errors,
                diffs=diffs,
                ratios=nan_none(ratios),
                orders=nan_none([study.observed_order(r) for r in ratios]),
                verdict=study.verdict(ratios),
            )
        )
    up_to = None
    for r in rows:
        if r["verdict"] == "does not converge":
            break
        if r["verdict"] == "converges":
            up_to = r["window"]
    pairs = [pr.horizon(a, b, pr.EPS) for a, b in zip(series, series[1:])]
    levels = [
        dict(
            label=s.label,
            cpu=s.cpu,
            onsets_lower=float(s.onsets[-1, 0]),
            first_onset=float(s.t[np.argmax(s.onsets[:, 0] > 0)]) if s.onsets[-1, 0] > 0 else None,
        )
        for s in series
    ]
    return dict(
        stop=stop,
        levels=levels,
        windows=rows,
        converges_up_to=up_to,
        pairs=[{k: v for k, v in p.items() if k != "growth"} for p in pairs],
    )


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_checkout_arguments(ap)
    ap.add_argument("--out", type=Path, help="the JSON (default <repo>/docs/stop_convergence.json)")
    ap.add_argument("--quick", action="store_true", help="3 time steps, 3 meshes, 0.2 s (a smoke run)")
    args = ap.parse_args(argv)
    fmu = fmu_path(args)
    dts, meshes, dt_stop, mesh_stop, free_stop = (
        (DTS[1:4], MESHES[:3], 0.2, 0.2, 0.05) if args.quick else (DTS, MESHES, DT_STOP, MESH_STOP, FREE_STOP)
    )
    wall0, cpu0 = time.perf_counter(), time.process_time()
    print(SCENE.title, flush=True)
    by_dt = [run(fmu, dict(dt=dt), dt_stop, f"dt = {dt:g}") for dt in dts]
    by_mesh = [run(fmu, dict(dt=MESH_DT, nx=nx, ny=ny), mesh_stop, f"{nx}×{ny}") for nx, ny in meshes]
    nx, ny = meshes[-1]
    free = [
        run(fmu, dict(dt=MESH_DT, nx=nx, ny=ny, obstacle_lower_enabled=False), free_stop, f"{nx}×{ny}, no obstacle")
        for nx, ny in meshes
    ]
    half = run(fmu, dict(dt=MESH_DT / 2, nx=nx, ny=ny), mesh_stop, f"{nx}×{ny}, dt = {MESH_DT / 2:g}")
    dt_ladder = dict(ladder(by_dt, dt_stop, WINDOWS), values=list(dts), mesh=[SCENE.params["nx"], SCENE.params["ny"]])
    mesh_ladder = dict(ladder(by_mesh, mesh_stop, WINDOWS), values=[list(m) for m in meshes], dt=MESH_DT)
    mesh_ladder["reference_time_error"] = [
        float(np.max(np.abs(by_mesh[-1].corner[m] - half.corner[m])))
        for m in (by_mesh[-1].t <= r["window"] + 1e-12 for r in mesh_ladder["windows"])
    ]
    free_ladder = dict(ladder(free, free_stop, WINDOWS), values=[list(m) for m in meshes], dt=MESH_DT)
    for name, lad in (("dt", dt_ladder), ("mesh", mesh_ladder), ("free flight", free_ladder)):
        for r in lad["windows"]:
            orders = ", ".join("—" if o is None else f"{o:.2f}" for o in r["orders"])
            print(f"{name} to {r['window']:g} s: errors {r['errors']}, orders {orders}: {r['verdict']}", flush=True)
        print(f"{name}: converges up to {lad['converges_up_to']} s", flush=True)
    data = dict(
        quick=args.quick,
        command="tools/stop_convergence.py" + (" --quick" if args.quick else ""),
        scene=dict(key=SCENE.key, title=SCENE.title, params=SCENE.params),
        law=dict(name="flow", **LAW),
        h=pr.H,
        eps=list(pr.EPS),
        dt=dt_ladder,
        mesh=mesh_ladder,
        free=free_ladder,
        run=pr.run_record(args.repo, wall0, cpu0),
    )
    out = args.out or args.repo / "docs" / "stop_convergence.json"
    out.write_text(json.dumps(data, indent=1) + "\n")
    print(f"wrote {out}; render it: python tools/render_docs.py performance.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
