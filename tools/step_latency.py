"""The worst case a real-time user budgets against: the wall time of one communication step of
1e-4 s through fmpy (PlateImpactFMU.step: set the inputs, fmi2DoStep, read the outputs), per law,
on the default (driven) scene and §5.2's release — median, p99 and maximum over 0.5 s, measured
in one run. The flow scheme's contact steps take `contact_substeps` midpoint sub-steps: its p99
and maximum show what they cost where they happen.

    python tools/step_latency.py [--fmu build/PlateImpact.fmu] [--stop 0.5] [--json docs/step_latency.json]
"""

from __future__ import annotations

import argparse
import json
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
}
SCENES = {"default": {}, "§5.2": {"initial_load": 8600.0, "obstacle_upper_enabled": False}}


def latencies(fmu: Path, law: dict, scene: dict, stop: float) -> np.ndarray:
    driven = "initial_load" not in scene
    out = []
    with PlateImpactFMU(fmu, **law, **scene) as plate:
        for k in range(round(stop / H)):
            base = default_base(k * H) if driven else None
            start = time.perf_counter_ns()
            plate.step(H, base=base)
            out.append(time.perf_counter_ns() - start)
    return np.array(out) * 1e-3  # µs


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fmu", type=Path, default=Path("build/PlateImpact.fmu"))
    parser.add_argument("--stop", type=float, default=0.5)
    parser.add_argument("--json", type=Path, default=Path("docs/step_latency.json"))
    args = parser.parse_args()
    rows = []
    for scene, scene_values in SCENES.items():
        for law, values in LAWS.items():
            t = latencies(args.fmu, values, scene_values, args.stop)
            row = {
                "scene": scene,
                "law": law,
                "median_us": float(np.median(t)),
                "p99_us": float(np.percentile(t, 99)),
                "max_us": float(t.max()),
                "steps": int(t.size),
            }
            rows.append(row)
            print(
                f"{scene:8s} {law:16s} median {row['median_us']:8.1f} µs  p99 {row['p99_us']:8.1f}  "
                f"max {row['max_us']:8.1f}"
            )
    args.json.write_text(json.dumps({"communication_step": H, "stop": args.stop, "rows": rows}, indent=1))
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
