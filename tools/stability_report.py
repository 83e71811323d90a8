"""Run the stability stress matrix into docs/stability.json, from which tools/render_docs.py fills
docs/templates/stability.md into docs/stability.md.

    python tools/stability_report.py            # the test's short horizons (~30 s)
    python tools/stability_report.py --full     # longer horizons (~1.5 min); docs/stability.md is this

The cases, the runner and the checks are those of tools/stability.py (the same table
python_tests/test_stability.py runs), so the report and the test cannot drift apart. The FMU is
--fmu, or $PLATEIMPACT_FMU, or <--repo>/build/PlateImpact.fmu; the JSON goes to
<--repo>/docs/stability.json unless --out says otherwise, the page beside it.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time
from pathlib import Path

import render_docs
import stability as sc
from checkout import add_checkout_arguments, fmu_path

FIELDS = (
    "dt bound steps horizon wall e0 energy_max ledger_error ledger_error_abs ledger_error_final energy_input "
    "energy_dissipated dissipation_drop penetration penetration_time midedge_overshoot contact_start "
    "contact_max comm_with_contact kkt_max qp_iterations_total qp_iterations_max qp_iterations_mean"
).split()


def finite(x):
    return x if not isinstance(x, float) or math.isfinite(x) else None


def row(r):
    """One case's numbers (None for what a case has not: -inf overshoot, nan times)."""
    c = r.case
    out = dict(name=c.name, varied=c.varied, refused=c.refused, gap=-c.obstacles[0], failures=sc.failures(r))
    out.update(restitution=c.restitution, net_dissipation=c.net_dissipation, penetration_limit=c.penetration_limit)
    out.update({k: finite(getattr(r, k)) for k in FIELDS})
    out["refusal"] = next((m for m in r.refused_log if "kappa_h" in m), None)
    return out


def summary(rows):
    """What the page's findings quote: the worst case of each check (the paper's law apart from
    the laws that allow what it does not), the gap copies."""
    run = [r for r in rows if not r["refused"]]
    held = [r for r in run if r["restitution"] == 0]  # the position held on the obstacle exactly
    paper = [r for r in run if not r["net_dissipation"]]  # energy_dissipated a loss, not a net amount
    worst = lambda rs, key: max(rs, key=lambda r: r[key] if r[key] is not None else -math.inf)  # noqa: E731
    by_ledger = sorted(run, key=lambda r: -r["ledger_error"])
    gaps = [r for r in rows if r["name"] in ("base", "gap_0.01", "gap_0.001", "gap_1e-4")]
    scaled = [r["energy_dissipated"] / r["gap"] ** 2 for r in gaps]
    return dict(
        runs=len(run),
        steps=sum(r["steps"] for r in run),
        failed=[r for r in rows if r["failures"]],
        worst_penetration=worst(held, "penetration"),
        penetration_during_steps=max(max(r["penetration"], 0.0) for r in held if (r["penetration_time"] or 0) > 0),
        restitution=[r for r in run if r["restitution"] > 0],
        net_dissipation=[r["name"] for r in run if r["net_dissipation"]],
        kkt_max=max(r["kkt_max"] for r in run),
        worst_midedge=worst(held, "midedge_overshoot")
        if any(r["midedge_overshoot"] is not None for r in held)
        else None,
        ledger_worst=by_ledger[:2],
        ledger_median=sorted(r["ledger_error"] for r in run)[len(run) // 2],
        ledger_final_max=max(r["ledger_error_final"] for r in run),
        dissipation_drop_min=min(r["dissipation_drop"] for r in paper),
        qp_mean_worst=worst(run, "qp_iterations_mean"),
        qp_max_worst=worst(run, "qp_iterations_max"),
        gaps=gaps,
        gap_energy_over_gap2=scaled,
        gap_spread=(max(scaled) - min(scaled)) / max(scaled) if scaled else None,
        gap_same_counts=len({(r["contact_max"], r["comm_with_contact"], r["qp_iterations_total"]) for r in gaps}) == 1,
        wall=sum(r["wall"] for r in rows),
    )


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--full", action="store_true", help="longer horizons (the cases' full_steps)")
    add_checkout_arguments(ap)
    ap.add_argument("--out", help="the JSON (default: <repo>/docs/stability.json)")
    ap.add_argument("--cases", nargs="*", help="only these cases (default: all)")
    args = ap.parse_args(argv)
    assert (sc.PENETRATION_LIMIT, sc.LEDGER_LIMIT, sc.KKT_LIMIT) == (1e-12, 1e-9, 1e-10), "update the template"
    results = []
    t0 = time.perf_counter()
    for c in (c for c in sc.CASES if not args.cases or c.name in args.cases):
        r = sc.run_case(c, fmu_path(args), full=args.full)
        results.append(r)
        problems = sc.failures(r)
        print(
            f"{c.name:24s} {r.steps:>9d} steps {r.wall:7.1f} s  "
            + ("pass" if not problems else "FAIL: " + "; ".join(problems))
        )
    print(f"total {time.perf_counter() - t0:.0f} s")
    rows = [row(r) for r in results]
    data = dict(
        full=args.full,
        machine=platform.machine(),
        cores=os.cpu_count(),
        base=dict(name=sc.CASES[0].name, base=sc.CASES[0].base.describe()),
        penetration_speed=sc.PENETRATION_SPEED,
        cases=rows,
        summary=summary(rows),
    )
    out = Path(args.out) if args.out else args.repo / "docs" / "stability.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(data, indent=1))
    print(f"wrote {out}")
    render_docs.main(["--data", str(out.parent), "--out", str(out.parent), "stability.md"])
    return 1 if any(r["failures"] for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
