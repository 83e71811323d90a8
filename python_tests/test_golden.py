"""The golden output: the default scene's first 0.1 s at the communication step 1e-4 s
(input derivatives given, as run.sh drives it), every output compared bit for bit with
python_tests/golden/default_scene_0.1s.csv — here, and on other CPUs (docs/theory.md §20).

The file carries its own input: the base displacement and its two derivatives set at each
communication point (columns base, base_d1, base_d2), written exactly. The run takes them from
the file, never from a sine computed now: the C library's sin differs by CPU in the last bit, and
so would the run. What is compared is then only what the FMU computes, and the FMU computes
nothing whose last bit depends on the CPU (no libm call where bits matter, no fused multiply-add,
fixed dense blocking).

Other CPUs: python_tests/test_golden_emulated.py runs the same check with a C master (no Python
under emulation) under qemu-x86_64 with `-cpu Nehalem` (SSE4.2, no AVX, no FMA)
and `-cpu Haswell` (AVX2 and FMA) — the one whose choices the host makes by its native run —
over the first 0.06 s (the first impacts of both obstacles:
corner_1 reaches the lower one at 0.0495 s) — the window where a CPU-dependent last bit showed
before (issue 31: FMA and libm choices made the runs differ from t = 1e-4 s and t = 0.0496 s on).

The file changes only in a commit that says which physics changed on purpose; regenerate it with
`.venv/bin/python python_tests/test_golden.py --write`. Floats are written with repr(), which
round-trips every double exactly, so equality here is bit identity.
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import sys
from pathlib import Path

from plateimpact import PlateImpactFMU, default_base

GOLDEN = Path(__file__).resolve().parent / "golden" / "default_scene_0.1s.csv"
STEP, STEPS = 1e-4, 1000  # 0.1 s: the plate hits both obstacles from t = 0.05 s on
INPUTS = ("base", "base_d1", "base_d2")
QEMU_WINDOW = 600  # steps: 0.06 s, past the first impact (0.0495 s)


def simulate(fmu_path, inputs, steps=STEPS) -> list[dict[str, float]]:
    """The outputs at every communication point, driven by `inputs` (one (z, z', z'') per step)."""
    rows = []
    with PlateImpactFMU(fmu_path) as plate:
        rows.append({"time": 0.0, **plate.outputs()})
        for k in range(steps):
            plate.step(STEP, base=inputs[k])
            rows.append({"time": (k + 1) * STEP, **plate.outputs()})
    return rows


def read_golden() -> list[dict[str, float]]:
    with GOLDEN.open() as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def golden_inputs(golden) -> list[tuple[float, float, float]]:
    return [tuple(row[c] for c in INPUTS) for row in golden]


def mismatches(golden, rows) -> list[str]:
    """Where the run differs from the golden file, bit for bit (empty: identical)."""
    found = []
    for want, got in zip(golden, rows):
        for name, value in want.items():
            if name in INPUTS:
                continue
            if got[name] != value:
                found.append(f"{name} at t = {want['time']}: {got[name]!r} != golden {value!r}")
    return found


def test_default_scene_matches_golden_output_bit_for_bit(fmu_path):
    golden = read_golden()
    rows = simulate(fmu_path, golden_inputs(golden))
    assert len(rows) == len(golden)
    # Every column of the golden file must still be an output (new outputs may be added).
    missing = set(golden[0]) - set(rows[0]) - set(INPUTS)
    assert not missing, f"outputs of the golden file no longer exist: {missing}"
    # The plate hits the obstacles inside the window: the file pins impacts, not only free flight.
    assert max(r["contact_vertices"] for r in golden) > 0
    assert not mismatches(golden, rows), mismatches(golden, rows)[:5]


def test_golden_input_is_the_default_scene(fmu_path):
    """The tabulated input is the default scene's base (0.09 sin(2π 10 t) m and its derivatives)
    to the C library's accuracy here (1e-14 of each column's amplitude A, Aω, Aω²): the file pins
    the scene, not some other input."""
    omega = 2 * math.pi * 10.0
    for k, row in enumerate(read_golden()):
        want = default_base(k * STEP)  # the input of the step from communication point k
        for c, w, scale in zip(INPUTS, want, (0.09, 0.09 * omega, 0.09 * omega**2)):
            assert abs(row[c] - w) <= 1e-14 * scale, (c, row["time"], row[c], w)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--write", action="store_true", help="regenerate the golden file (say why in the commit)")
    parser.add_argument("--check", action="store_true", help="compare a run with the file, exit 1 on a difference")
    parser.add_argument("--steps", type=int, default=STEPS)
    parser.add_argument(
        "--fmu",
        default=os.environ.get(
            "PLATEIMPACT_FMU", str(Path(__file__).resolve().parents[1] / "build" / "PlateImpact.fmu")
        ),
    )
    args = parser.parse_args()
    if args.write:
        # The input: the default scene's base at each communication point, computed once here and
        # kept in the file, exactly, from then on.
        inputs = [tuple(default_base(k * STEP)) for k in range(STEPS + 1)]
        rows = simulate(args.fmu, inputs)
        with GOLDEN.open("w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(list(rows[0]) + list(INPUTS))
            for row, given in zip(rows, inputs):
                writer.writerow([repr(float(v)) for v in row.values()] + [repr(float(v)) for v in given])
        print(f"wrote {GOLDEN} ({len(rows)} rows)")
    elif args.check:
        golden = read_golden()[: args.steps + 1]
        rows = simulate(args.fmu, golden_inputs(golden), args.steps)
        found = mismatches(golden, rows)
        if found:
            print("\n".join(found[:10]))
            sys.exit(1)
        print(f"identical over {args.steps} steps")
    else:
        parser.print_usage()
        sys.exit(2)


if __name__ == "__main__":
    main()
