"""The clamp's stress under a static pressure (docs/theory.md §23) under mesh refinement, both
elements: plate_bench static_stress=P on 7×3, 14×5, 28×10, 56×20 (h_x halves each time; from 14×5
on h_y too). Writes docs/stress_convergence.json: per element and mesh σ_xx at mid-edge and at the
corner, the root moment ∫ D w_xx dy against the exact clamp moment P W L²/2, the FMU's root_stress;
the observed orders of the moment's error (14×5 → 56×20 is a uniform refinement) and of the FVS
mid-edge stress against the finest Argyris one, and how far the Argyris mid-edge stress still moves.

    .venv/bin/python tools/stress_convergence.py --bench build/solver/bench/plate_bench
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
from pathlib import Path

MESHES = [(7, 3), (14, 5), (28, 10), (56, 20)]
PRESSURE = 1000.0  # Pa: linear, so any value gives the same ratios


def run(bench, element, nx, ny):
    out = subprocess.run(
        [bench, f"element={element}", f"nx={nx}", f"ny={ny}", f"static_stress={PRESSURE}"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return json.loads(out)


def study(bench):
    result = {"pressure": PRESSURE, "meshes": MESHES, "elements": {}}
    for element in ("argyris", "fvs"):
        rows = [run(bench, element, nx, ny) for nx, ny in MESHES]
        for r in rows:
            r["moment_error"] = abs(r["root_moment"] - r["clamp_moment"]) / r["clamp_moment"]
            r["mid_over_strip"] = r["sigma_xx_mid"] / r["sigma_strip"]
            # At the clamp σ_yy = ν σ_xx and τ = 0: von Mises = σ_xx √(1 − ν + ν²).
            nu = r["poisson_ratio"]
            r["root_sigma_xx"] = r["root_stress"] / math.sqrt(1 - nu + nu * nu)
        e = [r["moment_error"] for r in rows]
        s = [r["sigma_xx_mid"] for r in rows]
        result["elements"][element] = {
            "rows": rows,
            # uniform refinement from 14×5 on: h halves
            "moment_order": math.log2(e[2] / e[3]),
            # how much the mid-edge stress still moves from 14×5 to 56×20, relative
            "mid_spread": (max(s[1:]) - min(s[1:])) / s[3],
        }
    # The mid-edge stress against the finest Argyris value (the reference: it moves by 3e-4 from
    # 14×5 on); the FVS error's order from it.
    reference = result["elements"]["argyris"]["rows"][-1]["sigma_xx_mid"]
    result["mid_reference"] = reference
    for data in result["elements"].values():
        for r in data["rows"]:
            r["mid_error"] = abs(r["sigma_xx_mid"] - reference) / reference
    fvs = [r["mid_error"] for r in result["elements"]["fvs"]["rows"]]
    result["elements"]["fvs"]["mid_order"] = math.log2(fvs[2] / fvs[3])
    return result


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default="build/solver/bench/plate_bench")
    ap.add_argument("--out", default="docs/stress_convergence.json")
    # (the docs quote these numbers in theory.md §23)
    args = ap.parse_args(argv)
    result = study(args.bench)
    Path(args.out).write_text(json.dumps(result, indent=1) + "\n")
    for element, data in result["elements"].items():
        order = f", mid-edge order {data['mid_order']:.2f}" if "mid_order" in data else ""
        print(element, f"moment order {data['moment_order']:.2f}, mid-edge spread {data['mid_spread']:.1e}{order}")
        for r in data["rows"]:
            print(
                f"  {r['nx']:>2}x{r['ny']:<2} sigma_xx mid {r['sigma_xx_mid'] / 1e6:.4f} MPa "
                f"({r['mid_over_strip']:.4f} x strip), corner {r['sigma_xx_corner'] / 1e6:.3f} MPa, "
                f"root moment error {r['moment_error']:.2e}"
            )


if __name__ == "__main__":
    main()
