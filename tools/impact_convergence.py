"""Convergence after impact, per impact law: the §5.2 scene through the FMU under time-step and
mesh refinement (tools/impact_study.py), into docs/impact_convergence.json, from which
tools/render_docs.py fills the measured part of docs/impact-laws.md.

    python tools/impact_convergence.py            # ~5 min on 2 cores; then render_docs.py impact-laws.md
    python tools/impact_convergence.py --quick --out /tmp/ic.json   # 3 time steps, 2 laws

Measures, per law: the energy lost by 0.5 s, the first three impact times and corner_1 over the
first 0.3 s under dt = 4e-5 ... 2.5e-6 s (14 x 5 cells), their successive differences and
ratios, the verdict converges / does not; the same quantities on 28 x 10 cells; the reduced
model (modes) against the singular-mass scheme; and the cost per internal step of each law.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import impact_study as study
from checkout import add_checkout_arguments, fmu_path

from plateimpact.driver import PlateImpactFMU

# The laws whose cost per step is measured (FMU parameters beyond the scene).
COST_LAWS = {
    "paper (consistent, e = 0)": {},
    "consistent, e = 0.5": {"restitution": 0.5},
    "consistent, damping a = 5 1/s, b = 1e-5 s": {"damping_mass": 5.0, "damping_stiffness": 1e-5},
    "singular_p0": {"mass": 2},
    "singular_p0, e = 0.5, damping": {"mass": 2, "restitution": 0.5, "damping_mass": 5.0, "damping_stiffness": 1e-5},
}


def step_cost(fmu, params, steps=20_000, h=1e-3):
    """CPU seconds per internal step of the §5.2 scene over `steps` steps (contact included),
    communication step h (the FMU's own cost: one doStep per h)."""
    with PlateImpactFMU(fmu, **dict(study.SCENE, **params)) as plate:
        per = round(h / params.get("dt", 1e-5))
        t0 = time.process_time()
        for k in range(steps // per):
            plate.fmu.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
        return (time.process_time() - t0) / (steps // per * per)


def nan_none(xs):
    return [None if isinstance(x, float) and math.isnan(x) else x for x in xs]


def run_row(r):
    return dict(dt=r.dt, nx=r.nx, ny=r.ny, e0=r.e0, lost=r.lost, ledger=r.ledger, impacts=r.impacts, wall=r.wall)


def refinement(fmu, law, dts):
    """One law under dt refinement: the runs, the successive differences and verdicts."""
    runs = [study.run(fmu, law, dt) for dt in dts]
    quantities = [("energy lost", "", *study.successive([r.lost for r in runs]))]
    for j in range(3):
        times = [r.impacts[j] if len(r.impacts) > j else math.nan for r in runs]
        quantities.append((f"impact {j + 1} time", " s", *study.successive(times)))
    quantities.append(("corner_1 over the first 0.3 s", " m", *study.corner_differences(runs)))
    rows = [
        dict(name=name, unit=unit, diffs=nan_none(d), ratios=nan_none(q), verdict=study.verdict(q))
        for name, unit, d, q in quantities
    ]
    energy_ratios = quantities[0][3]
    rows[0]["order"] = study.observed_order(energy_ratios[-1]) if energy_ratios else None
    return dict(law=law, runs=[run_row(r) for r in runs], quantities=rows)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_checkout_arguments(ap)
    ap.add_argument("--out", type=Path, help="the JSON (default <repo>/docs/impact_convergence.json)")
    ap.add_argument("--quick", action="store_true", help="3 time steps, 2 laws, no mesh or modes rows")
    args = ap.parse_args(argv)
    fmu = fmu_path(args)
    laws, dts = (list(study.LAWS)[:2], study.DTS[1:4]) if args.quick else (list(study.LAWS), study.DTS)
    wall0 = time.perf_counter()
    data = dict(laws=[], mesh=[], modes=[], costs=[])
    for law in laws:
        data["laws"].append(refinement(fmu, law, dts))
        print(f"{law}: {', '.join(q['verdict'] for q in data['laws'][-1]['quantities'])}", flush=True)
    if not args.quick:
        for law in laws[:2]:
            for nx, ny in ((14, 5), (28, 10)):
                data["mesh"] += [dict(run_row(study.run(fmu, law, dt, nx=nx, ny=ny)), law=law) for dt in (1e-5, 5e-6)]
        data["modes_reference"] = data["laws"][1]["runs"][-1]
        for m in (10, 40, 160):
            data["modes"].append(dict(run_row(study.run(fmu, f"modes = {m}", 1e-5, extra={"modes": m})), modes=m))
    for nx, ny in ((14, 5),) if args.quick else ((14, 5), (28, 10)):
        base_cost = None
        for name, params in COST_LAWS.items():
            singular = params.get("mass", 1) != 1
            steps = 20_000 if nx == 14 else 5_000
            cost = step_cost(fmu, dict(params, dt=1e-5, nx=nx, ny=ny, obstacle_lower=-0.02), steps=steps)
            base_cost = base_cost or cost
            engine = "sparse" if singular or nx * ny > 100 else "modal-complete"
            data["costs"].append(dict(nx=nx, ny=ny, law=name, engine=engine, step_s=cost, ratio=cost / base_cost))
    data["wall"] = time.perf_counter() - wall0
    out = args.out or args.repo / "docs" / "impact_convergence.json"
    out.write_text(json.dumps(data, indent=1))
    print(f"wrote {out}; render it: python tools/render_docs.py impact-laws.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
