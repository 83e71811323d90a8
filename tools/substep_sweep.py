"""What the flow law's sub-steps buy (docs/theory.md §24): corner_1's largest error against a converged
reference for contact_substeps m = 2, 4, 8, 16 and for the conserving law, on tools/tolerance_study.py's
four scenes (the same references: the flow law at dt = 6.25e-7 s, 64 sub-steps). The midpoint sub-steps
are second order in Δt/m: halving m multiplies the error by about 4, which is why m = 16 is the default
and why fewer sub-steps cannot buy the flow law's cost down at today's accuracy.

    python tools/substep_sweep.py [--repo .]       # ~2.5 min wall (after bash run.sh)
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import tolerance_study as ts  # noqa: E402  (the scenes, the references and plate_bench's runner)

SUBSTEPS = [2, 4, 8, 16]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repo", type=Path, default=Path("."))
    repo = parser.parse_args().repo.resolve()
    print("| scene | " + " | ".join(f"m = {m}" for m in SUBSTEPS) + " | conserving |")
    print("|---" * (len(SUBSTEPS) + 2) + "|")
    with tempfile.TemporaryDirectory() as tmpdir:
        tmp = Path(tmpdir)
        for scene in ts.SCENES:
            window = ts.SCENES[scene]["window"]
            ref_law = ["scheme=flow", f"substeps={ts.REFERENCE['substeps']}"]
            _, _, ref, _ = ts.run(repo, scene, ref_law, ts.REFERENCE["dt"], window, tmp, "ref")
            errors = []
            for law in [["scheme=flow", f"substeps={m}"] for m in SUBSTEPS] + [["scheme=conserving"]]:
                _, _, corner, _ = ts.run(repo, scene, law, ts.DT, window, tmp, "run")
                n = min(len(corner), len(ref))
                errors.append(float(np.abs(corner[:n] - ref[:n]).max()))
            print(f"| {scene} ({window:g} s) | " + " | ".join(f"{e:.2e} m" for e in errors) + " |", flush=True)


if __name__ == "__main__":
    main()
