"""What the flow law's sub-steps buy (docs/theory.md §24): corner_1's largest error against a converged
reference for contact_substeps m = 2, 4, 8, 16 and for the conserving law, on tools/tolerance_study.py's
four scenes (the same references: the flow law at dt = 6.25e-7 s, 64 sub-steps). The midpoint sub-steps
are second order in Δt/m: halving m multiplies the error by about 4, which is why m = 16 is the default
and why fewer sub-steps cannot buy the flow law's cost down at today's accuracy. Then what each
sub-step costs: the stepping CPU of §5.2 and the default scene over 0.3 s for m = 1, 2, 4, 8, 16 and
the conserving law (plate_bench, best of 3 interleaved runs), as ratios to the conserving law — the
floor of docs/theory.md §24 (m = 1: the free steps and a contact step's fixed work; each further
sub-step adds the same).

    python tools/substep_sweep.py [--repo .] [--cost-only]   # ~3 min wall (after bash run.sh)
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
COST_SUBSTEPS = [1, 2, 4, 8, 16]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repo", type=Path, default=Path("."))
    parser.add_argument("--cost-only", action="store_true", help="the CPU table only")
    args = parser.parse_args()
    repo = args.repo.resolve()
    if not args.cost_only:
        errors_table(repo)
    cost_table(repo)


def cost_table(repo: Path) -> None:
    laws = {"conserving": ["scheme=conserving"]} | {f"m = {m}": ["scheme=flow", f"substeps={m}"] for m in COST_SUBSTEPS}
    print()
    print("| scene (0.3 s) | " + " | ".join(laws) + " | each sub-step adds |")
    print("|---" * (len(laws) + 2) + "|")
    for scene in ["§5.2", "default"]:
        cpu = ts.cpu_best(repo, scene, laws, 3)
        ratio = {k: v / cpu["conserving"] for k, v in cpu.items()}
        per = (ratio["m = 16"] - ratio["m = 1"]) / 15
        cells = [f"{cpu['conserving']:.3f} s/s"] + [f"{ratio[k]:.2f}×" for k in laws if k != "conserving"]
        print(f"| {scene} | " + " | ".join(cells) + f" | {per:.3f}× |", flush=True)


def errors_table(repo: Path) -> None:
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
