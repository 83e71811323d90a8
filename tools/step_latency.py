"""The worst case a real-time user budgets against: the wall time of one communication step of
1e-4 s through fmpy (PlateImpactFMU.step: set the inputs, fmi2DoStep, read the outputs), per law,
on the default (driven) scene and §5.2's release — median, p99 and maximum over 1 s, measured
in one run. The flow scheme's contact steps take `contact_substeps` midpoint sub-steps: its p99
and maximum show what they cost where they happen. Each step is timed twice: the wall clock (what
a real-time master sees, raised on a busy machine by the time the process waited for a core) and
the thread's CPU clock (the step's own work: what a real-time core budgets). The README's
real-time row quotes the CPU maximum of its recipe from this file.

    python tools/step_latency.py [--fmu build/PlateImpact.fmu] [--stop 1] [--json docs/step_latency.json]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import time
from pathlib import Path

import numpy as np

from plateimpact import PlateImpactFMU, default_base

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
    for scene, scene_values in SCENES.items():
        for law, values in LAWS.items():
            t, cpu = step_times(args.fmu, values, scene_values, args.stop)
            row = {
                "scene": scene,
                "law": law,
                "median_us": float(np.median(t)),
                "p99_us": float(np.percentile(t, 99)),
                "max_us": float(t.max()),
                "cpu_median_us": float(np.median(cpu)),
                "cpu_p99_us": float(np.percentile(cpu, 99)),
                "cpu_max_us": float(cpu.max()),
                "steps": int(t.size),
            }
            rows.append(row)
            print(
                f"{scene:8s} {law:20s} wall median {row['median_us']:8.1f} µs  p99 {row['p99_us']:8.1f}  "
                f"max {row['max_us']:8.1f}; CPU median {row['cpu_median_us']:8.1f}  p99 {row['cpu_p99_us']:8.1f}  "
                f"max {row['cpu_max_us']:8.1f}",
                flush=True,
            )
    load = os.getloadavg()
    report = {"communication_step": H, "stop": args.stop, "rows": rows, "commit": commit(), "load_average": load[0]}
    args.json.write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n")
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
