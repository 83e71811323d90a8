"""Accuracy on request (docs/performance.md, "Accuracy on request"): the flow law with a tolerance
(time_scheme = flow, tolerance > 0, docs/theory.md §22) against converged references, its error
estimate against the measured error, its cost against the conserving law's, and the worst
communication step through fmpy — each measured in one run of this script.

    python tools/tolerance_study.py [--repo .] [--quick] [--json docs/tolerance.json]

Scenes (solver/bench/plate_bench, singular_p0 mass, dt = 1e-5 s):
  §5.2     the release from 8600 Pa onto the lower obstacle, corner_1 over 0.3 s; reference: the
           flow law at dt = 6.25e-7 s with 64 sub-steps per contact step, checked against
           dt = 1.25e-6 s (their difference is the reference's own error bound);
  default  the FMU's default scene (0.09 sin(2π·10 t) m), its first impacts: corner_1 over
           0–0.07 s (beyond, the scene is chaotic: docs/performance.md, "Predictability").
Cost: process CPU per internal step, pure stepping, best of three interleaved runs; the front:
error against CPU per simulated second for the conserving law at four dt and the flow law at
three tolerances. The worst communication step of these laws is tools/step_latency.py's (one table
of it, docs/performance.md).
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

DT = 1e-5
SCENES = {
    "§5.2": {"args": ["amplitude=0", "initial_load=8600", "lower_only=1"], "window": 0.3, "stop": 0.3},
    "default": {"args": [], "window": 0.07, "stop": 0.07},
}
FMU_SCENES = {"default": {}, "§5.2": {"initial_load": 8600.0, "obstacle_upper_enabled": False}}
REFERENCE = {"dt": 6.25e-7, "substeps": 64}
CHECK = {"dt": 1.25e-6, "substeps": 64}
TOLERANCES = [1e-4, 1e-5, 1e-6]
CONSERVING_DTS = [1e-5, 5e-6, 2.5e-6, 1.25e-6]
LAW = ["mass=singular_p0"]


def bench(repo: Path, *args: str, series: Path | None = None) -> dict:
    exe = repo / "build" / "solver" / "bench" / "plate_bench"
    extra = [f"series={series}"] if series else []
    out = subprocess.run([str(exe), *args, *extra, "floor_repeats=1"], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def corner(path: Path) -> tuple[np.ndarray, np.ndarray]:
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return np.array([float(r["time"]) for r in rows]), np.array([float(r["corner_1"]) for r in rows])


def run(repo: Path, scene: str, law: list[str], dt: float, tmp: Path, name: str) -> tuple[dict, np.ndarray]:
    s = SCENES[scene]
    series = tmp / f"{name}.csv"
    result = bench(repo, *s["args"], *LAW, *law, f"dt={dt}", f"steps={round(s['stop'] / dt)}", series=series)
    t, c = corner(series)
    return result, c[t <= s["window"] + 1e-12]


def cpu_best(repo: Path, scene: str, laws: dict[str, list[str]], repeats: int) -> dict[str, float]:
    """Process CPU per simulated second, best of `repeats` interleaved runs per law."""
    s = SCENES[scene]
    best = {k: float("inf") for k in laws}
    for _ in range(repeats):
        for key, law in laws.items():
            dt = float(next((a.split("=")[1] for a in law if a.startswith("dt=")), DT))
            r = bench(repo, *s["args"], *LAW, *law, f"dt={dt}", f"steps={round(s['stop'] / dt)}")
            best[key] = min(best[key], r["step_cpu_s"] / dt)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repo", type=Path, default=Path("."))
    parser.add_argument("--quick", action="store_true", help="one scene, two tolerances")
    parser.add_argument("--json", type=Path, default=Path("docs/tolerance.json"))
    args = parser.parse_args()
    repo = args.repo.resolve()
    report: dict = {"dt": DT, "reference": REFERENCE, "scenes": {}}
    tolerances = TOLERANCES[:2] if args.quick else TOLERANCES
    with tempfile.TemporaryDirectory() as tmpdir:
        tmp = Path(tmpdir)
        for scene in ["§5.2"] if args.quick else list(SCENES):
            ref_law = ["scheme=flow", f"substeps={REFERENCE['substeps']}"]
            _, ref = run(repo, scene, ref_law, REFERENCE["dt"], tmp, "ref")
            _, check = run(repo, scene, ["scheme=flow", f"substeps={CHECK['substeps']}"], CHECK["dt"], tmp, "check")
            entry: dict = {"window_s": SCENES[scene]["window"], "reference_spread_m": float(np.abs(ref - check).max())}
            rows = {}
            laws = {"conserving": ["scheme=conserving"], "flow 16": ["scheme=flow", "substeps=16"]}
            laws |= {f"flow tol={t:g}": ["scheme=flow", f"tolerance={t:g}"] for t in tolerances}
            # The contact steps in every row (docs/theory.md §24: the baseline of the row space), and
            # the reduced model, in the same interleaved runs.
            laws |= {
                "flow 16, every row": ["scheme=flow", "substeps=16", "rowspace=0"],
                "flow tol=1e-05, every row": ["scheme=flow", "tolerance=1e-05", "rowspace=0"],
                "conserving m=20": ["scheme=conserving", "modes=20"],
                "flow 16 m=20": ["scheme=flow", "substeps=16", "modes=20"],
            }
            for key, law in laws.items():
                result, c = run(repo, scene, law, DT, tmp, key.replace(" ", "_"))
                rows[key] = {
                    "error_m": float(np.abs(c - ref).max()),
                    "error_estimate_m": result["error_estimate"],
                    "capped_steps": result["capped_steps"],
                    "contact_solves": result["qp_iterations_total"],
                }
            cpu = cpu_best(repo, scene, laws, 1 if args.quick else 3)
            for key in rows:
                rows[key]["cpu_per_sim_s"] = cpu[key]
                rows[key]["cpu_vs_conserving"] = cpu[key] / cpu["conserving"]
            entry["laws"] = rows
            if scene == "§5.2":
                # The conserving law's front: its error and CPU at finer dt.
                front = {}
                for dt in CONSERVING_DTS:
                    _, c = run(repo, scene, ["scheme=conserving"], dt, tmp, f"c{dt:g}")
                    front[f"{dt:g}"] = {"error_m": float(np.abs(c[: len(ref)] - ref[: len(c)]).max())}
                fcpu = cpu_best(repo, scene, {f"{dt:g}": ["scheme=conserving", f"dt={dt}"] for dt in CONSERVING_DTS}, 1)
                for k in front:
                    front[k]["cpu_per_sim_s"] = fcpu[k]
                entry["conserving_front"] = front
                # At each tolerance: the conserving law's error at the same CPU (log-log interpolation).
                xs = np.log([front[k]["cpu_per_sim_s"] for k in front])
                ys = np.log([front[k]["error_m"] for k in front])
                order = np.argsort(xs)
                for key, row in rows.items():
                    if key.startswith("flow tol"):
                        at = float(np.exp(np.interp(np.log(row["cpu_per_sim_s"]), xs[order], ys[order])))
                        row["conserving_error_at_equal_cpu_m"] = at
                        row["error_ratio_at_equal_cpu"] = at / row["error_m"]
            report["scenes"][scene] = entry
            print(json.dumps({scene: entry}, indent=1, ensure_ascii=False), flush=True)
    args.json.write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n")
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
