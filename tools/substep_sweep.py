"""What the flow law's sub-steps buy (docs/theory.md §24): the reported points' largest error (corner_1,
corner_2, free_edge_mid: tolerance_study's measure) against a converged
reference for contact_substeps m = 2, 4, 8, 16 and for the conserving law, on tools/tolerance_study.py's
four scenes (the same references: the flow law at dt = 6.25e-7 s, 64 sub-steps). The midpoint sub-steps
are second order in Δt/m: halving m multiplies the error by about 4, which is why m = 16 is the default
and why fewer sub-steps cannot buy the flow law's cost down at today's accuracy. Then what each
sub-step costs: the stepping CPU of §5.2 and the default scene over 0.3 s for m = 1, 2, 4, 8, 16 and
the conserving law (plate_bench, best of 3 interleaved runs), as ratios to the conserving law — the
floor of docs/theory.md §24 (m = 1: the free steps and a contact step's fixed work; each further
sub-step adds the same).

    python tools/substep_sweep.py [--repo .] [--cost-only]   # ~3 min wall (after bash run.sh)
    python tools/substep_sweep.py --floor [--tolerance 1e-5]  # ~6 min wall

--floor: what a tolerance costs at the least, whatever estimate chooses the sub-steps (issue 51's goal
of 2x the conserving law, docs/theory.md §22): on §5.2 and the default scene, full and modes = 20, the
error of m = 8, 16, 32 fixed sub-steps against the reference of the same model over the scene's window
and their stepping CPU over 0.3 s; the least m whose error is within the tolerance (second order in
1/m from the nearest measured m above it: m* = m·√(error/tolerance)) and what m* sub-steps cost (linear
in m between the measured counts): the kept runs alone, with an estimate that costs nothing and is
exact. An estimate that never under-states runs each contact step at least once more (the pair's coarse
run, half the sub-steps): the floor with it adds half of m*'s sub-steps.
"""

from __future__ import annotations

import argparse
import math
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
    parser.add_argument("--floor", action="store_true", help="the least cost of a tolerance (see above)")
    parser.add_argument("--tolerance", type=float, default=1e-5)
    args = parser.parse_args()
    repo = args.repo.resolve()
    if args.floor:
        floor_table(repo, args.tolerance)
        return
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


FLOOR_SUBSTEPS = [8, 16, 32]


def floor_table(repo: Path, tolerance: float) -> None:
    print(
        f"| scene | error m = {' / '.join(map(str, FLOOR_SUBSTEPS))} | CPU × conserving m = 1 / "
        + " / ".join(map(str, FLOOR_SUBSTEPS))
        + f" | m* for {tolerance:g} m | kept runs alone at m* | with a half-count pair |"
    )
    print("|---" * 6 + "|")
    with tempfile.TemporaryDirectory() as tmpdir:
        tmp = Path(tmpdir)
        for scene in ["§5.2", "default"]:
            for modes in ([], ["modes=20"]):
                window = ts.SCENES[scene]["window"]
                ref_law = ["scheme=flow", f"substeps={ts.REFERENCE['substeps']}", *modes]
                _, _, ref, _ = ts.run(repo, scene, ref_law, ts.REFERENCE["dt"], window, tmp, "ref")
                errors = []
                for m in FLOOR_SUBSTEPS:
                    _, _, corner, _ = ts.run(
                        repo, scene, ["scheme=flow", f"substeps={m}", *modes], ts.DT, window, tmp, "run"
                    )
                    errors.append(float(ts.deviation(corner, ref).max()))
                counts = [1, *FLOOR_SUBSTEPS]
                laws = {"conserving": ["scheme=conserving", *modes]} | {
                    m: ["scheme=flow", f"substeps={m}", *modes] for m in counts
                }
                cpu = ts.cpu_best(repo, scene, laws, 3)
                ratio = [cpu[m] / cpu["conserving"] for m in counts]
                # The least m within the tolerance: from the largest measured m still outside it (or the
                # smallest measured, when all are inside), second order in 1/m.
                outside = [(m, e) for m, e in zip(FLOOR_SUBSTEPS, errors) if e > tolerance]
                m0, e0 = outside[-1] if outside else (FLOOR_SUBSTEPS[0], errors[0])
                need = max(1.0, m0 * math.sqrt(e0 / tolerance))
                kept = float(np.interp(need, counts, ratio, right=None))
                if need > counts[-1]:  # beyond the measured counts: the last slope
                    kept = ratio[-1] + (need - counts[-1]) * (ratio[-1] - ratio[-2]) / (counts[-1] - counts[-2])
                per = (kept - ratio[0]) / max(need - 1.0, 1.0)  # what one sub-step adds
                paired = kept + 0.5 * need * per
                label = f"{scene}{' modes = 20' if modes else ''} ({window:g} s)"
                print(
                    f"| {label} | "
                    + " / ".join(f"{e:.1e}" for e in errors)
                    + " | "
                    + " / ".join(f"{r:.2f}" for r in ratio)
                    + f" | {need:.0f} | {kept:.2f}× | {paired:.2f}× |",
                    flush=True,
                )


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
                errors.append(float(ts.deviation(corner, ref).max()))
            print(f"| {scene} ({window:g} s) | " + " | ".join(f"{e:.2e} m" for e in errors) + " |", flush=True)


if __name__ == "__main__":
    main()
