"""How long a communication step may be for the input's own content (issue 71; README, "Simulate it
with fmpy"; fmu/binding/PlateAdvice.h, missAdvice): the README's 10 Hz scene (base 0.09 sin(2π·10 t) m,
obstacles at ±0.1 m, 1 s) through the package's driver, the base passed as values only with each
base_input_mode (hold, linear, quadratic) or with its exact derivatives, at communication steps from
dt to 0.016 s. Per run: the energy at 1 s against the finest run's, the impacts on each obstacle (10
and 10 when right), and whether the FMU warned that the master's values miss its model of the input.

    .venv/bin/python tools/step_misses.py [--fmu build/PlateImpact.fmu] [--json docs/step_misses.json]
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import time
from pathlib import Path

from plateimpact import PlateImpactFMU

AMPLITUDE, FREQUENCY, STOP = 0.09, 10.0, 1.0
WAYS = {
    "quadratic": [1e-3, 2e-3, 4e-3, 5e-3, 8e-3, 0.01, 0.016],
    "linear": [1e-3, 2e-3, 4e-3, 8e-3],
    "hold": [1e-5, 2e-5, 1e-4, 1e-3],
    "derivatives": [1e-4, 1e-3, 2e-3, 4e-3, 0.01],
}
MODES = {"hold": 1, "linear": 2, "quadratic": 3}


def base(t):
    w = 2 * math.pi * FREQUENCY
    return (AMPLITUDE * math.sin(w * t), AMPLITUDE * w * math.cos(w * t), -AMPLITUDE * w * w * math.sin(w * t))


def run(fmu, way, h, stop=STOP):
    """One run of the scene: energy at the end, impacts, the FMU's warning of a miss ('' if none)."""
    parameters = {"base_input_mode": MODES[way]} if way in MODES else {}
    start = time.process_time()
    with PlateImpactFMU(fmu, **parameters) as plate:
        for k in range(round(stop / h)):
            b = base(k * h)
            out = plate.step(h, base=b if way == "derivatives" else b[0], derivatives=way == "derivatives")
        said = [m for s, _, m in plate.log if s == 1 and "model of it" in m]
    return {
        "way": way,
        "h": h,
        "energy_end": float(out["energy"]),
        "impacts": [int(out["impacts_lower"]), int(out["impacts_upper"])],
        "warned": bool(said),
        "warning": said[0] if said else "",
        "cpu_s": time.process_time() - start,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fmu", type=Path, default=Path("build/PlateImpact.fmu"))
    parser.add_argument("--json", type=Path, default=Path("docs/step_misses.json"))
    args = parser.parse_args()
    rows = []
    for way, steps in WAYS.items():
        for h in steps:
            rows.append(run(args.fmu, way, h))
            r = rows[-1]
            print(
                f"{way:11s} h = {h:g} s: energy {r['energy_end']:.4g} J, impacts {r['impacts']}, warned {r['warned']}",
                file=sys.stderr,
                flush=True,
            )
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    report = {"amplitude": AMPLITUDE, "frequency": FREQUENCY, "stop": STOP, "commit": commit, "rows": rows}
    args.json.write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n")
    print(f"wrote {args.json}", file=sys.stderr)


if __name__ == "__main__":
    main()
