"""The golden output: the default scene's first 0.1 s at the communication step 1e-4 s
(input derivatives given, as run.sh drives it), every output compared bit for bit with
python_tests/golden/default_scene_0.1s.csv.

The file changes only in a commit that says which physics changed on purpose; regenerate it
with `.venv/bin/python python_tests/test_golden.py --write`. Floats are written with repr(),
which round-trips every double exactly, so equality here is bit identity.
"""

from __future__ import annotations

import csv
import os
import sys
from pathlib import Path

from plateimpact import PlateImpactFMU, default_base

GOLDEN = Path(__file__).resolve().parent / "golden" / "default_scene_0.1s.csv"
STEP, STEPS = 1e-4, 1000  # 0.1 s: the plate hits both obstacles from t = 0.05 s on


def simulate(fmu_path) -> list[dict[str, float]]:
    rows = []
    with PlateImpactFMU(fmu_path) as plate:
        rows.append({"time": 0.0, **plate.outputs()})
        for k in range(STEPS):
            plate.step(STEP, base=default_base(k * STEP))
            rows.append({"time": (k + 1) * STEP, **plate.outputs()})
    return rows


def read_golden() -> list[dict[str, float]]:
    with GOLDEN.open() as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def test_default_scene_matches_golden_output_bit_for_bit(fmu_path):
    golden = read_golden()
    rows = simulate(fmu_path)
    assert len(rows) == len(golden)
    # Every column of the golden file must still be an output (new outputs may be added).
    missing = set(golden[0]) - set(rows[0])
    assert not missing, f"outputs of the golden file no longer exist: {missing}"
    # The plate hits the obstacles inside the window: the file pins impacts, not only free flight.
    assert max(r["contact_vertices"] for r in golden) > 0
    for want, got in zip(golden, rows):
        for name, value in want.items():
            assert got[name] == value, f"{name} at t = {want['time']}: {got[name]!r} != golden {value!r}"


if __name__ == "__main__":
    if "--write" not in sys.argv:
        sys.exit("usage: test_golden.py --write  (regenerates the golden file: say why in the commit)")
    fmu = os.environ.get("PLATEIMPACT_FMU", str(Path(__file__).resolve().parents[1] / "build" / "PlateImpact.fmu"))
    rows = simulate(fmu)
    with GOLDEN.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(list(rows[0]))
        for row in rows:
            writer.writerow([repr(float(v)) for v in row.values()])
    print(f"wrote {GOLDEN} ({len(rows)} rows)")
