"""Speed against error of PlateImpact: wall time per simulated second, real-time factor and
step/floor ratio beside errors against a fine reference, for both elements, several grids,
Δt from 1e-3 down to 1e-6 and several `modes`; plus the same scheme in plain Python/SciPy
(sparse factorization + a general QP solver from PyPI) as the baseline a user might write.

Everything is measured in this run with `plate_bench` (the solver without FMI, one JSON line
per run, the floor = one solve with the sparse factor of A = M + βΔt²K measured in the same
run) and, for the default scene's wall time, with the FMU through fmpy.

    .venv/bin/python tools/speed_vs_error.py            # full: docs/performance.md (~10 min)
    .venv/bin/python tools/speed_vs_error.py --quick --out /tmp/perf   # smoke run, seconds
    .venv/bin/python tools/speed_vs_error.py --quick --no-report --out /tmp/perf   # the suite's run

Errors are used only for quantities shown to converge (successive differences of a refinement
sequence shrinking, rule in `converges()`); a quantity that does not is reported and flagged,
never used as an error. speed_summary computes the summary from the measurements (errors,
verdicts, goals, every table's rows) and writes nothing else. Writes <out>/speed_vs_error.json
(all numbers) and, unless --no-report, renders <out>/performance.md from
docs/templates/performance.md and its figures (tools/render_docs.py).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import render_docs
from checkout import add_checkout_arguments, fmu_path
from speed_study import (
    SINE,
    Bench,
    Cfg,
    first_frequency,
    first_impact,
    fmu_wall,
    make_plan,
    python_baseline,
    study_free,
    study_long,
    study_scaling,
    study_short,
)
from speed_summary import summarize


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="smoke run on tiny grids (seconds)")
    add_checkout_arguments(ap)
    ap.add_argument(
        "--out", help="output directory (speed_vs_error.json, performance.md, figures/; default: <repo>/docs)"
    )
    ap.add_argument(
        "--no-report",
        action="store_true",
        help="measure and summarize only: write speed_vs_error.json, no markdown, no figures",
    )
    ap.add_argument("--bench", help="plate_bench (default: $PLATEIMPACT_BUILD_DIR or <repo>/build, solver/bench/)")
    args = ap.parse_args(argv)
    build = Path(os.environ.get("PLATEIMPACT_BUILD_DIR", args.repo / "build"))
    args.bench = args.bench or str(build / "solver" / "bench" / "plate_bench")
    args.fmu = fmu_path(args)

    out = Path(args.out) if args.out else args.repo / "docs"
    out.mkdir(parents=True, exist_ok=True)
    plan = make_plan(args.quick)
    started = time.perf_counter()
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory(prefix="speed_vs_error_") as tmp:
        bench = Bench(args.bench, tmp)
        print("== first natural frequencies (mesh accuracy), from the exported M, K")
        freqs = {}
        for element, nx, ny in plan["freq_grids"]:
            f, n = first_frequency(bench, Cfg(element, nx, ny), tmp)
            freqs[(element, nx, ny)] = dict(f1=f, dofs=n)
            print(f"  {element} {nx}x{ny}: {n} dofs, f1 = {f:.6f} Hz")
        f_ref_key = max(freqs, key=lambda k: (k[0] == "argyris", freqs[k]["dofs"]))
        for k, v in freqs.items():
            v["rel_err"] = abs(v["f1"] - freqs[f_ref_key]["f1"]) / freqs[f_ref_key]["f1"]

        print("== scaling: per-step time and floor against dofs")
        scaling = study_scaling(bench, plan)
        ms_cfg = plan["modes_setup"]
        ms_run = bench.run(ms_cfg, SINE, 100 * ms_cfg.dt)
        ms_exact = next(
            (r["auto"] for r in scaling if (r["element"], r["nx"], r["ny"]) == (ms_cfg.element, ms_cfg.nx, ms_cfg.ny)),
            None,
        )
        modes_setup = dict(cfg=ms_cfg, run=ms_run, exact_setup_s=ms_exact["setup_s"] if ms_exact else float("nan"))
        print("== sine scene, short horizon (trajectory before the first impact, impact time)")
        short = study_short(bench, plan)
        print("== §5.2 free vibration (energy lost by 0.5 s)")
        free = study_free(bench, plan)
        free["plan_seqs"] = plan["free_seqs"]
        print("== sine scene, long horizon (envelope)")
        long = study_long(bench, plan)

        print("== default scene: plate_bench and the FMU")
        dflt = bench.run(plan["default"], SINE, plan["default_T"], repeats=plan["default_repeats"])
        fmu = None
        if Path(args.fmu).exists():
            tries = []
            for _ in range(plan["default_repeats"]):
                tries.append(
                    fmu_wall(
                        args.fmu, plan["default_T"], dt=plan["default"].dt, nx=plan["default"].nx, ny=plan["default"].ny
                    )
                )
            fmu = min(tries, key=lambda t: t["total_s"])
            print(f"  FMU: {fmu['total_s']:.2f} s wall for {plan['default_T']} s (init {fmu['init_s']:.2f} s)")

        print("== Python/SciPy baseline")
        bl = plan["baseline"]
        exp_dir = Path(tmp) / "baseline_export"
        bench.export(bl["cfg"], exp_dir)
        try:
            py = min(
                (
                    python_baseline(exp_dir, bl["cfg"].dt, bl["steps"], bl["comm"], bl["split"])
                    for _ in range(plan["baseline_tries"])
                ),
                key=lambda r: r["step_s"],
            )
        except ImportError as e:
            py = dict(error=str(e))
        cpp = {}
        items = [
            (replace(bl["cfg"], engine=e), SINE, n * bl["cfg"].dt, bl["comm"])
            for e in ("auto", "sparse")
            for n in (bl["steps"], bl["split"])
        ]
        timed = bench.run_group(items, rounds=plan["baseline_rounds"])
        for k, engine in enumerate(("auto", "sparse")):
            whole, free_part = timed[2 * k], timed[2 * k + 1]
            c = replace(bl["cfg"], engine=engine)
            ser = bench.run(c, SINE, bl["steps"] * c.dt, comm=bl["comm"], series=True)
            contact_s = max(
                (whole["step_s"] * bl["steps"] - free_part["step_s"] * bl["split"]) / (bl["steps"] - bl["split"]), 0.0
            )
            cpp[engine] = dict(run=whole, free_step_s=free_part["step_s"], contact_step_s=contact_s, series=ser)
        if "error" not in py:
            ser = cpp["auto"]["series"]["series"]
            t_imp = first_impact(cpp["auto"]["series"])
            agree = {}
            for engine in ("auto", "sparse"):
                s = cpp[engine]["series"]["series"]
                diff = np.abs(py["corner_1"] - s["corner_1"][: len(py["corner_1"])])
                before = py["time"] < t_imp - 1e-12
                agree[engine] = dict(
                    before=float(diff[before].max()),
                    after=float(diff[~before].max()) if (~before).any() else float("nan"),
                )
            py["agree"] = agree
            py["t_impact"] = t_imp
            py["ratio"] = {e: py["step_s"] / cpp[e]["run"]["step_s"] for e in cpp}
            py["ratio_free"] = {e: py["free_phase_step_s"] / cpp[e]["free_step_s"] for e in cpp}
            py["ratio_contact"] = {
                e: py["contact_phase_step_s"] / cpp[e]["contact_step_s"]
                if cpp[e]["contact_step_s"] > 0
                else float("nan")
                for e in cpp
            }
            print(
                f"  Python {1e6 * py['step_s']:.0f} us/step ({py['qp_steps']} QP steps), "
                f"ratio to C++ auto {py['ratio']['auto']:.0f}x, agreement before impact "
                f"{agree['auto']['before']:.1e} m, after {agree['auto']['after']:.1e} m"
            )
    elapsed = time.perf_counter() - started
    load_after = os.getloadavg()

    ctx = dict(
        plan=plan,
        freqs=freqs,
        modes_setup=modes_setup,
        f_ref_key=f_ref_key,
        scaling=scaling,
        short=short,
        free=free,
        long=long,
        dflt=dflt,
        fmu=fmu,
        py=py,
        cpp=cpp,
        elapsed=elapsed,
        load=(load_before, load_after),
        runs=bench.count,
        args=args,
    )
    summary = summarize(ctx)
    summary["runs"] = bench.log  # every plate_bench run: wall and CPU step times, floors, engine
    (out / "speed_vs_error.json").write_text(json.dumps(summary, indent=1, default=float))
    print(f"== wrote {out / 'speed_vs_error.json'} in {elapsed:.0f} s ({bench.count} plate_bench runs)")
    if not args.no_report:  # the page and its figures, from the JSON just written
        render_docs.main(["--data", str(out), "--out", str(out), "--figures", "performance.md"])
    for line in summary["headline_lines"]:
        print("  " + line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
