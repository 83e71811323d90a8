"""What a scene needs: the cheapest configuration whose error against the plate stays within an
accuracy over a window (docs/theory.md §26, docs/performance.md "The error against the plate").

    python -m plateimpact.sizing SCENE.json --accuracy 1e-3 --until 0.1 [--fmu PlateImpact.fmu]
        [--scheduler ADDRESS] [--workers N] [--json OUT.json] [--figure OUT.png] [--quick]

The scene (plateimpact.convergence.Scene): the FMU's parameters of the plate and a drive. The runs go
to Dask, a local cluster of one worker per core unless --scheduler names a running one:
  - the reference ladder: Argyris on h, h/2, h/4, each on its complete basis, with the flow law on
    the singular P0 mass at dt = 1e-5 s (exact free flight; its time error far below the mesh's);
  - the candidates: elements, meshes, modes, laws, dt and sub-steps (CANDIDATES).
Then the converged plate by Richardson's extrapolation with the measured order (or the verdict that
it does not converge), each candidate's error against it and CPU per simulated second, the front,
and the cheapest candidate within the accuracy. --quick: a coarse ladder (h = the base mesh's
double) and a handful of candidates, for a check in seconds.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from . import convergence as cv


def base_mesh(parameters):
    """The ladder's coarsest mesh: five cells across the width, about square cells (the default
    plate's 14 x 5)."""
    length = float(parameters.get("length", 1.2))
    width = float(parameters.get("width", 0.4))
    return max(2, round(14 * (length / width) / 3)), 5


def candidates(nx, ny, quick=False):
    """The configurations a user can choose from: the default (the paper's law on the base mesh),
    finer meshes on a few modes, the energy-exact laws, a coarser dt, FVS."""
    flow = {"time_scheme": "flow", "mass": "singular_p0"}
    out = [
        {"nx": nx, "ny": ny},  # the FMU's default: newmark (the paper's law), consistent mass
        dict(flow, nx=nx, ny=ny),
        dict(flow, nx=nx, ny=ny, modes=20),
        {"nx": 2 * nx, "ny": 2 * ny, "modes": 40, "time_scheme": "conserving", "mass": "singular_p0"},
    ]
    if quick:
        return out
    for mx, my in ((3 * nx // 2, 3 * ny // 2 + 1), (2 * nx, 2 * ny)):
        for modes in (20, 40, 100):
            out.append(dict(flow, nx=mx, ny=my, modes=modes))
    out += [
        dict(flow, nx=2 * nx, ny=2 * ny, modes=40, dt=2e-5),
        dict(flow, nx=2 * nx, ny=2 * ny, modes=40, contact_substeps=4),
        {"nx": 2 * nx, "ny": 2 * ny, "modes": 40},  # newmark, consistent mass, reduced
        dict(flow, nx=4 * nx, ny=4 * ny, modes=100),
        dict(flow, element="fvs", nx=round(10 * nx / 7), ny=round(7 * ny / 5), modes=40),
    ]
    return out


def _run(fmu, scene_dict, config, until):
    """One task: the run's points and cost (plain data, for Dask)."""
    from .tasks import local_fmu

    r = cv.run(local_fmu(fmu), cv.Scene.from_dict(scene_dict), config, until)
    return {"config": r.config, "points": r.points, "cpu_per_second": r.cpu_per_second, "setup_s": r.setup_s}


def plan(scene_parameters, quick=False):
    """The runs: (name, config) for the ladder and the candidates."""
    nx, ny = base_mesh(scene_parameters)
    if quick:
        nx, ny = max(2, nx // 2), 3
    rungs = cv.ladder(dict(cv.LADDER_LAW, nx=nx, ny=ny))
    runs = [("h", rungs[0]), ("h/2", rungs[1]), ("h/4", rungs[2])]
    runs += [(cv.label(c), c) for c in candidates(nx, ny, quick)]
    return runs


def analyse(results, until, accuracy, windows=()):
    """The converged plate over each window (Richardson with the order measured over that window),
    each candidate's error against it and cost, the front (over `until`), the choice."""
    by = dict(results)
    h, h2, h4 = (by[n]["points"] for n in ("h", "h/2", "h/4"))
    references, plates = {}, {}
    for w in sorted(set(windows) | {until}):
        n = round(w / cv.SAMPLE)
        plate = cv.converged_plate(h[:n], h2[:n], h4[:n])
        plates[w] = plate.points
        references[f"{w:g}"] = plate.summary()
    rows = []
    for name, r in results:
        if name.startswith("h"):
            continue
        errors = {f"{w:g}": float(np.abs(r["points"][: len(p)] - p).max()) for w, p in plates.items()}
        rows.append(
            {
                "name": name,
                "config": r["config"],
                "error": errors[f"{until:g}"],
                "errors": errors,
                "cpu_per_second": r["cpu_per_second"],
                "setup_s": r["setup_s"],
            }
        )
    reference = dict(references[f"{until:g}"], ladder=[cv.label(by[n]["config"]) for n in ("h", "h/2", "h/4")])
    front = [rows[i]["name"] for i in cv.pareto([(r["cpu_per_second"], r["error"]) for r in rows])]
    within = [r for r in rows if r["error"] + reference["uncertainty"] <= accuracy]
    choice = min(within, key=lambda r: r["cpu_per_second"]) if within else None
    return {
        "plates": plates,
        "until": until,
        "accuracy": accuracy,
        "reference": reference,
        "references": references,
        "candidates": rows,
        "front": front,
        "choice": choice["name"] if choice else None,
        "choice_config": choice["config"] if choice else None,
    }


def figure(report, path, title=""):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    rows = report["candidates"]
    front = set(report["front"])
    for r in rows:
        on = r["name"] in front
        ax.loglog(r["cpu_per_second"], r["error"], "o" if on else "x", color="C0" if on else "0.6")
        if on:
            ax.annotate(
                r["name"], (r["cpu_per_second"], r["error"]), fontsize=6, xytext=(3, 3), textcoords="offset points"
            )
    pts = sorted((r["cpu_per_second"], r["error"]) for r in rows if r["name"] in front)
    ax.loglog([p[0] for p in pts], [p[1] for p in pts], "-", color="C0", lw=0.8)
    ax.axhline(report["accuracy"], color="C3", lw=0.8, ls="--", label=f"accuracy {report['accuracy']:g} m")
    ax.axhline(report["reference"]["uncertainty"], color="0.4", lw=0.8, ls=":", label="reference's uncertainty")
    ax.set_xlabel("CPU per simulated second (s)")
    ax.set_ylabel(f"error against the plate over {report['until']:g} s (m)")
    ax.set_title(title or "error against the plate vs CPU", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def size(fmu, scene: cv.Scene, until, accuracy, client=None, quick=False, progress=True, windows=()):
    """The sizing of a scene: the runs (on `client` when given, else in this process) and their analysis."""
    runs = plan(scene.parameters, quick)
    scene_dict = {
        "parameters": scene.parameters,
        "drive": {"amplitude": scene.amplitude, "frequency": scene.frequency, "load": scene.load},
    }
    calls = [((scene_dict, config, until), {}) for _, config in runs]
    if client is None:
        results = [_run(fmu, *args) for args, _ in calls]
    else:
        from .tasks import on_dask

        data = fmu if not isinstance(fmu, (str, Path)) else Path(fmu).read_bytes()
        results = on_dask(client, _run, data, calls, progress, desc="sizing")
    return analyse([(name, r) for (name, _), r in zip(runs, results)], until, accuracy, windows)


def _names(fmu):
    from .driver import unzipped

    _, md = unzipped(fmu)
    return {v.name for v in md.modelVariables if v.causality == "parameter"}


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m plateimpact.sizing", description=__doc__.split("\n\n")[0])
    ap.add_argument("scene", help="the scene: a JSON file with 'parameters' and 'drive'")
    ap.add_argument("--accuracy", type=float, default=1e-3, help="m, the error against the plate allowed")
    ap.add_argument("--until", type=float, default=0.1, help="s, the window")
    ap.add_argument("--fmu", default=str(Path(__file__).resolve().parents[2] / "build" / "PlateImpact.fmu"))
    ap.add_argument("--scheduler", help="a Dask scheduler's address (default: a local cluster)")
    ap.add_argument("--workers", type=int, default=None, help="local cluster's workers (default: one per core)")
    ap.add_argument("--json", help="write the report here")
    ap.add_argument("--figure", help="draw the front here (PNG)")
    ap.add_argument("--quick", action="store_true", help="a coarse ladder and four candidates (seconds)")
    ap.add_argument("--no-progress", action="store_true")
    args = ap.parse_args(argv)

    def refuse(message):
        print(f"sizing: {message}", file=sys.stderr)
        return 2

    if not (math.isfinite(args.accuracy) and args.accuracy > 0):
        return refuse(f"--accuracy {args.accuracy}: a length > 0 in m (e.g. 1e-3)")
    if not (math.isfinite(args.until) and cv.SAMPLE <= args.until <= 10.0):
        return refuse(f"--until {args.until}: a window in s from {cv.SAMPLE:g} to 10")
    if not Path(args.fmu).is_file():
        return refuse(f"{args.fmu}: no such FMU (bash run.sh builds build/PlateImpact.fmu; or pass --fmu)")
    try:
        scene = cv.Scene.load_file(args.scene, _names(args.fmu))
    except cv.SceneError as e:
        return refuse(str(e))
    from distributed import Client, LocalCluster

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    try:
        report = size(args.fmu, scene, args.until, args.accuracy, client, args.quick, not args.no_progress)
    except Exception as e:  # a refusal of the FMU (bad parameters) reaches here from a worker
        return refuse(f"the scene could not be run: {e}")
    finally:
        client.close()
    ref = report["reference"]
    print(
        f"the converged plate: {ref['verdict']} (ladder {', '.join(ref['ladder'])}; "
        f"uncertainty {ref['uncertainty']:.2g} m)"
    )
    print(f"{'configuration':58s} {'error (m)':>10s} {'CPU/s (s)':>10s} {'setup (s)':>9s}  front")
    front = set(report["front"])
    for r in sorted(report["candidates"], key=lambda r: r["cpu_per_second"]):
        print(
            f"{r['name']:58s} {r['error']:10.3g} {r['cpu_per_second']:10.3g} {r['setup_s']:9.2f}  "
            f"{'*' if r['name'] in front else ''}"
        )
    if report["choice"]:
        print(f"cheapest within {args.accuracy:g} m over {args.until:g} s: {report['choice']}")
        print("  FMU parameters: " + json.dumps(report["choice_config"]))
    else:
        best = min(report["candidates"], key=lambda r: r["error"])
        print(
            f"no configuration tried is within {args.accuracy:g} m over {args.until:g} s (reference uncertainty "
            f"{ref['uncertainty']:.2g} m); the closest: {best['name']} at {best['error']:.3g} m — a larger "
            f"accuracy, a shorter window or a finer mesh on more modes"
        )
    if args.json:
        Path(args.json).write_text(json.dumps({k: v for k, v in report.items() if k != "plates"}, indent=1) + "\n")
    if args.figure:
        figure(report, args.figure, f"{Path(args.scene).name}, {args.until:g} s")
    return 0 if report["choice"] else 1


if __name__ == "__main__":
    sys.exit(main())
