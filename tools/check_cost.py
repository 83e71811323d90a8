"""What discretization_check costs (docs/performance.md, "The error against the plate"; docs/theory.md
§26): plate_bench with check=0 and check=1 on the same scene, as instructions counted by callgrind
inside CheckedPlate::communicate (the stepping, the companion's included: repeatable on a shared
machine; 5000 or 20000 steps) and as process CPU per step over 0.3 s (the least of three
interleaved runs), with their ratios.

    python tools/check_cost.py [--bench build/solver/bench/plate_bench] [--json docs/check_cost.json]
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
FLOW = ["scheme=flow", "mass=singular_p0"]
S52 = ["amplitude=0", "initial_load=8600", "lower_only=1"]
# (name, plate_bench arguments, steps): the default drive (contact every cycle) and §5.2 (mostly free
# flight), the configurations of the front; a contact-rich small plate; the paper's law.
CASES = [
    ("default drive, argyris 14x5 newmark (the FMU's default)", ["nx=14", "ny=5"], 5000),
    ("default drive, argyris 14x5 conserving", ["nx=14", "ny=5", "scheme=conserving", "mass=singular_p0"], 5000),
    ("default drive, argyris 14x5 flow", ["nx=14", "ny=5", *FLOW], 5000),
    ("default drive, argyris 28x10 m40 flow", ["nx=28", "ny=10", "modes=40", *FLOW], 5000),
    ("default drive, fvs 20x7 m40 flow", ["element=fvs", "nx=20", "ny=7", "modes=40", *FLOW], 5000),
    (
        "obstacles ±0.03 m, 0.02 sin(2π·15 t), argyris 7x5 flow",
        ["nx=7", "ny=5", "gap=0.03", "amplitude=0.02", "frequency=15", *FLOW],
        5000,
    ),
    ("§5.2, argyris 14x5 newmark", ["nx=14", "ny=5", *S52], 20000),
    ("§5.2, argyris 28x10 m20 flow", ["nx=28", "ny=10", "modes=20", *FLOW, *S52], 20000),
    ("§5.2, argyris 28x10 m40 flow", ["nx=28", "ny=10", "modes=40", *FLOW, *S52], 20000),
    ("§5.2, fvs 20x7 m40 flow", ["element=fvs", "nx=20", "ny=7", "modes=40", *FLOW, *S52], 20000),
]
COMMON = ["floor_repeats=20", "comm=5e-4"]
CPU_STEPS = 30000


def instructions(bench, args):
    with tempfile.TemporaryDirectory() as tmp:
        r = subprocess.run(
            [
                "valgrind",
                "--tool=callgrind",
                f"--callgrind-out-file={tmp}/cg",
                "--toggle-collect=plate::CheckedPlate::communicate*",
                bench,
                *args,
            ],
            capture_output=True,
            text=True,
            check=True,
        )
    return int(re.search(r"Collected : (\d+)", r.stderr).group(1))


def cpu_per_step(bench, args):
    r = subprocess.run([bench, *args], capture_output=True, text=True, check=True)
    return json.loads(r.stdout)["step_cpu_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bench", default=str(REPO / "build" / "solver" / "bench" / "plate_bench"))
    ap.add_argument("--json", default=str(REPO / "docs" / "check_cost.json"))
    args = ap.parse_args()
    rows = []
    for name, case, steps in CASES:
        base = [*case, *COMMON, f"steps={steps}"]
        ir = {c: instructions(args.bench, [*base, f"check={c}"]) for c in (0, 1)}
        cpu = {0: [], 1: []}
        timed = [*case, *COMMON, f"steps={CPU_STEPS}"]  # 0.3 s: long enough for the process clock
        for _ in range(3):
            for c in (0, 1):
                cpu[c].append(cpu_per_step(args.bench, [*timed, f"check={c}"]))
        row = {
            "case": name,
            "instructions_off": ir[0],
            "instructions_on": ir[1],
            "instructions_ratio": ir[1] / ir[0],
            "cpu_step_off_us": 1e6 * min(cpu[0]),
            "cpu_step_on_us": 1e6 * min(cpu[1]),
            "cpu_ratio": min(cpu[1]) / min(cpu[0]),
        }
        rows.append(row)
        print(
            f"{name:60s} instructions ×{row['instructions_ratio']:.3f}  CPU {row['cpu_step_off_us']:.2f} → "
            f"{row['cpu_step_on_us']:.2f} µs/step ×{row['cpu_ratio']:.2f}",
            flush=True,
        )
    out = {
        "rows": rows,
        "instructions_ratio_max": max(r["instructions_ratio"] for r in rows),
        "cpu_ratio_max": max(r["cpu_ratio"] for r in rows),
    }
    Path(args.json).write_text(json.dumps(out, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
