"""The worst case a real-time user budgets against: the wall time of one communication step of
1e-4 s through fmpy (PlateImpactFMU.step: set the inputs, fmi2DoStep, read the outputs), per law,
on the default (driven) scene and §5.2's release — median, p99 and maximum over 1 s, measured
in one run. The flow scheme's contact steps take `contact_substeps` midpoint sub-steps: its p99
and maximum show what they cost where they happen. Each step is timed twice: the wall clock (what
a real-time master sees, raised on a busy machine by the time the process waited for a core) and
the thread's CPU clock (the step's own work: what a real-time core budgets). The README's
real-time row quotes the CPU maximum of its recipe from this file. The same steps are timed again
through a plain C master (python_tests/fmu_driver.c --latency: fmi2DoStep alone, no interpreter),
and each law's p99 and maximum are given as ratios to the conserving law's on the same scene and master.

    python tools/step_latency.py [--fmu build/PlateImpact.fmu] [--stop 1] [--json docs/step_latency.json]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import tempfile
import time
import zipfile
from pathlib import Path

import numpy as np
from fmpy import read_model_description

from plateimpact import PlateImpactFMU, default_base
from plateimpact.driver import switch_items

REPO = Path(__file__).resolve().parents[1]
DRIVER = REPO / "python_tests" / "fmu_driver.c"

H = 1e-4
LAWS = {
    "paper": {},
    "conserving": {"mass": "singular_p0", "time_scheme": "conserving"},
    "flow": {"mass": "singular_p0", "time_scheme": "flow"},
    "conserving m=20": {"mass": "singular_p0", "time_scheme": "conserving", "modes": 20},
    "flow m=20": {"mass": "singular_p0", "time_scheme": "flow", "modes": 20},
    "flow tol=1e-05": {"mass": "singular_p0", "time_scheme": "flow", "tolerance": 1e-5},
    # the real-time recipes: a contact step in 4 sub-steps, or a tolerance whose sub-steps are capped at 4
    "flow 4 sub-steps": {"mass": "singular_p0", "time_scheme": "flow", "contact_substeps": 4},
    "flow tol=1e-05 cap 4": {
        "mass": "singular_p0",
        "time_scheme": "flow",
        "tolerance": 1e-5,
        "max_contact_substeps": 4,
    },
}
SCENES = {"default": {}, "§5.2": {"initial_load": 8600.0, "obstacle_upper_enabled": False}}


def step_times(fmu: Path, law: dict, scene: dict, stop: float) -> tuple[np.ndarray, np.ndarray]:
    """Wall and thread-CPU time of each communication step (µs)."""
    driven = "initial_load" not in scene
    wall, cpu = [], []
    with PlateImpactFMU(fmu, **law, **scene) as plate:
        for k in range(round(stop / H)):
            base = default_base(k * H) if driven else None
            start, start_cpu = time.perf_counter_ns(), time.thread_time_ns()
            plate.step(H, base=base)
            cpu.append(time.thread_time_ns() - start_cpu)
            wall.append(time.perf_counter_ns() - start)
    return np.array(wall) * 1e-3, np.array(cpu) * 1e-3


def latencies(fmu: Path, law: dict, scene: dict, stop: float) -> np.ndarray:
    """Wall time of each communication step (µs)."""
    return step_times(fmu, law, scene, stop)[0]


def c_master(folder: Path) -> Path:
    """fmu_driver.c built at -O2 into `folder`."""
    compiler = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    exe = folder / "fmu_driver"
    headers = REPO / "fmu" / "headers" / "fmi2"
    command = [compiler, "-std=c99", "-D_DEFAULT_SOURCE", "-O2", f"-I{headers}", str(DRIVER), "-o", str(exe)]
    subprocess.run(command + ["-ldl", "-lm"], check=True)
    return exe


def c_arguments(fmu: Path, values: dict) -> list[str]:
    """The driver's i:VR=VALUE / b:VR=VALUE / r:VR=VALUE arguments for these parameters."""
    variables = {v.name: v for v in read_model_description(str(fmu)).modelVariables}
    out = []
    for name, value in values.items():
        v = variables[name]
        if isinstance(value, str):
            value = switch_items(v)[value]
        kind = {"Integer": "i", "Boolean": "b", "Real": "r"}[v.type]
        out.append(f"{kind}:{v.valueReference}={float(value)!r}")
    return out


def c_step_times(driver: Path, unzipped: Path, fmu: Path, law: dict, scene: dict, stop: float) -> np.ndarray:
    """Thread-CPU time of each fmi2DoStep through the C master (µs)."""
    driven = "initial_load" not in scene
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "steps.csv"
        steps = str(round(stop / H))
        command = [str(driver), "--latency", str(out), str(unzipped), steps, str(int(driven))]
        subprocess.run(command + c_arguments(fmu, {**law, **scene}), check=True, capture_output=True)
        return np.loadtxt(out, delimiter=",", skiprows=1)[:, 1]


def ratios(rows: list[dict]) -> list[dict]:
    """Each law's p99 and maximum over the conserving law's (same scene, same master, CPU clock)."""
    out = []
    for row in rows:
        base = next(r for r in rows if r["scene"] == row["scene"] and r["law"] == "conserving")
        entry = {"scene": row["scene"], "law": row["law"]}
        for master, prefix in (("fmpy", "cpu_"), ("c", "c_cpu_")):
            for stat in ("p99", "max"):
                entry[f"{master}_{stat}_ratio"] = row[f"{prefix}{stat}_us"] / base[f"{prefix}{stat}_us"]
        out.append(entry)
    return out


def commit() -> str:
    out = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    return out.stdout.strip() or "unknown"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fmu", type=Path, default=Path("build/PlateImpact.fmu"))
    parser.add_argument("--stop", type=float, default=1.0)
    parser.add_argument("--json", type=Path, default=Path("docs/step_latency.json"))
    args = parser.parse_args()
    rows = []
    folder = Path(tempfile.mkdtemp(prefix="step_latency_"))
    driver = c_master(folder)
    unzipped = folder / "fmu"
    with zipfile.ZipFile(args.fmu) as z:
        z.extractall(unzipped)
    for scene, scene_values in SCENES.items():
        for law, values in LAWS.items():
            t, cpu = step_times(args.fmu, values, scene_values, args.stop)
            c_cpu = c_step_times(driver, unzipped, args.fmu, values, scene_values, args.stop)
            row = {
                "scene": scene,
                "law": law,
                "median_us": float(np.median(t)),
                "p99_us": float(np.percentile(t, 99)),
                "max_us": float(t.max()),
                "cpu_median_us": float(np.median(cpu)),
                "cpu_p99_us": float(np.percentile(cpu, 99)),
                "cpu_max_us": float(cpu.max()),
                "c_cpu_median_us": float(np.median(c_cpu)),
                "c_cpu_p99_us": float(np.percentile(c_cpu, 99)),
                "c_cpu_max_us": float(c_cpu.max()),
                "steps": int(t.size),
            }
            rows.append(row)
            print(
                f"{scene:8s} {law:20s} wall median {row['median_us']:8.1f} µs  p99 {row['p99_us']:8.1f}  "
                f"max {row['max_us']:8.1f}; CPU median {row['cpu_median_us']:8.1f}  p99 {row['cpu_p99_us']:8.1f}  "
                f"max {row['cpu_max_us']:8.1f}; C master CPU median {row['c_cpu_median_us']:8.1f}  "
                f"p99 {row['c_cpu_p99_us']:8.1f}  max {row['c_cpu_max_us']:8.1f}",
                flush=True,
            )
    shutil.rmtree(folder)
    for r in ratios(rows):
        print(
            f"{r['scene']:8s} {r['law']:20s} × conserving: fmpy p99 {r['fmpy_p99_ratio']:5.2f} max {r['fmpy_max_ratio']:5.2f}; "
            f"C p99 {r['c_p99_ratio']:5.2f} max {r['c_max_ratio']:5.2f}"
        )
    load = os.getloadavg()
    report = {
        "communication_step": H,
        "stop": args.stop,
        "rows": rows,
        "ratios": ratios(rows),
        "commit": commit(),
        "load_average": load[0],
    }
    args.json.write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n")
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
