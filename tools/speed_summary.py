"""The summary of the speed-against-error study (tools/speed_vs_error.py), computed from what
speed_study measured (the run's `ctx`): `summarize(ctx)` returns one dict of data, written to
speed_vs_error.json — every table of docs/performance.md as rows of numbers (the sine-scene errors
against the fine reference, only for quantities shown to converge; the §5.2 runs; the envelope;
the scaling; the Python/SciPy baseline), the convergence verdicts by the rule of
`speed_study.converges()`, the goals with their verdicts, and `notes(summary)`: what the page's
prose quotes (slopes, trends, the element pairs), derived from the same dict. Nothing here writes
the page: tools/render_docs.py fills docs/templates/performance.md from the JSON.
python_tests/test_speed_report.py checks this dict."""

from __future__ import annotations

import datetime
import math
import os
import platform
import subprocess

import numpy as np
from speed_study import CONTRACTION, fmt_dt


def mesh(element, nx, ny):
    return f"{'Argyris' if element == 'argyris' else 'FVS'} {nx}×{ny}"


def run_cells(run):
    return {k: run[k] for k in ("dofs", "engine", "wall_per_sim_s", "rtf", "step_over_floor")}


def summarize(ctx):
    """The dict written to speed_vs_error.json (every key but `runs`, which the command line adds)."""
    plan, short, free, long, py, dflt, fmu = (ctx[k] for k in ("plan", "short", "free", "long", "py", "dflt", "fmu"))
    goals, lines = goal_verdicts(ctx)
    sq = short["quantities"]
    order = lambda c: (c.element, c.nx, c.modes, c.engine, -c.dt)  # noqa: E731
    summary = dict(
        headline_lines=lines,
        goals=goals,
        quantities={
            "trajectory": {k: sq["trajectory"][k] for k in ("converges", "sequences", "ref", "ref_uncertainty")},
            "impact": {k: sq["impact"][k] for k in ("converges", "sequences", "ref_uncertainty", "ref_value")},
            "energy_lost_0p5s": dict(converges=free["converges"], sequences=free["sequences"]),
            "envelope_max_corner": dict(
                converges=False,
                degenerate=long["pinned"],
                roundoff_rel=long["roundoff_rel"],
                dt_half_rel=long["dt_half_rel"],
            ),
        },
        errors=[
            dict(
                config=r["cfg"].label(),
                **run_cells(r["run"]),
                t1=r["t1"],
                reference=r["cfg"] == plan["short_ref"],
                err_trajectory=r["err_trajectory"],
                err_impact=r["err_impact"],
            )
            for r in sorted(short["rows"], key=lambda r: order(r["cfg"]))
        ],
        free=[
            dict(config=c.label(), **run_cells(run), energy_dissipated=run["energy_dissipated"])
            for c, run in sorted(free["runs"].items(), key=lambda kv: order(kv[0]))
        ],
        free_roundoff=dict(value=free["roundoff"], config=free["base"].label()),
        modes=[
            dict(
                config=m["cfg"].label(),
                rel_err=m["rel_err"],
                speedup=m["speedup"],
                energy_dissipated=m["run"]["energy_dissipated"],
            )
            for m in free["modes"]
        ],
        envelope=[
            dict(
                config=r["cfg"].label(),
                **run_cells(r["run"]),
                max_corner=r["max_corner_any"],
                period_envelope=r["period_envelope"],
                energy_dissipated=r["energy_dissipated"],
            )
            for r in long["rows"]
        ],
        freqs=[dict(mesh=mesh(*k), **v) for k, v in ctx["freqs"].items()],
        scaling=[scaling_row(r, ctx["freqs"]) for r in ctx["scaling"]],
        baseline=({k: v for k, v in py.items() if k not in ("time", "corner_1")} if py else None),
        default=dict(
            fmu=fmu,
            bench={k: dflt[k] for k in ("setup_s", "wall_s", "step_s", "floor_solve_s", "step_over_floor", "engine")},
        ),
        modes_setup=modes_setup(ctx["modes_setup"]),
        plan=plan_summary(plan, ctx["f_ref_key"]),
        run=run_summary(ctx),
        elapsed_s=ctx["elapsed"],
        quick=plan["quick"],
    )
    if summary["baseline"] and "error" not in py:
        summary["baseline"]["cpp"] = {
            e: dict(
                engine=c["run"]["engine"],
                step_s=c["run"]["step_s"],
                free_step_s=c["free_step_s"],
                contact_step_s=c["contact_step_s"],
            )
            for e, c in ctx["cpp"].items()
        }
    summary["notes"] = notes(summary)
    return summary


def scaling_row(r, freqs):
    keys = ("engine", "step_s", "floor_solve_s", "step_over_floor")
    f = freqs.get((r["element"], r["nx"], r["ny"]), {})
    return dict(
        mesh=mesh(r["element"], r["nx"], r["ny"]),
        **{k: r[k] for k in ("element", "nx", "ny", "dofs", "steps", "rounds")},
        f1=f.get("f1"),
        f1_rel_err=f.get("rel_err"),
        auto=dict({k: r["auto"][k] for k in keys}, setup_s=r["auto"]["setup_s"]),
        sparse={k: r["sparse"][k] for k in keys},
        modal_step_s=r["modal"]["step_s"] if r.get("modal") else None,
    )


def modes_setup(ms):
    c = ms["cfg"]
    return dict(
        mesh=mesh(c.element, c.nx, c.ny),
        command=f"plate_bench element={c.element} nx={c.nx} ny={c.ny} modes={c.modes} steps=100",
        modes=c.modes,
        dofs=ms["run"]["dofs"],
        setup_s=ms["run"]["setup_s"],
        exact_setup_s=ms["exact_setup_s"],
    )


def plan_summary(plan, f_ref_key):
    bl = plan["baseline"]
    return dict(
        **{k: plan[k] for k in ("short_T", "long_T", "free_T", "pre_impact")},
        contraction=CONTRACTION,
        free_base=plan["free_modes_base"].label(),
        baseline=dict(config=bl["cfg"].label(), steps=bl["steps"], split=bl["split"], comm=bl["comm"], dt=bl["cfg"].dt),
        pairs=[[mesh(*a), mesh(*f)] for a, f in plan["pairs"]],
        f_ref=mesh(*f_ref_key),
    )


def run_summary(ctx):
    try:
        import osqp

        osqp_version = osqp.__version__
    except ImportError:
        osqp_version = None
    git = lambda *a: subprocess.run(["git", "-C", str(ctx["args"].repo), *a], capture_output=True, text=True).stdout  # noqa: E731
    dirty = git("status", "--porcelain", "--untracked-files=no", "solver", "fmu").strip()
    return dict(
        minutes=ctx["elapsed"] / 60,
        bench_runs=ctx["runs"],
        commit=git("rev-parse", "--short", "HEAD").strip() + (" (solver/fmu with uncommitted edits)" if dirty else ""),
        date=datetime.date.today().isoformat(),
        cores=os.cpu_count(),
        load=[ctx["load"][0][0], ctx["load"][1][0]],
        machine=platform.processor() or platform.machine(),
        python=platform.python_version(),
        osqp=osqp_version,
    )


# ------------------------------------------------------------------------------------------
# What the page's prose quotes, derived from the summary's own data (so that a saved JSON gives it
# again): the modes' energies on the base mesh, the observed orders, the §5.2 trends under h, the
# element pairs, the scaling slopes and the engine findings.
# ------------------------------------------------------------------------------------------
def notes(s):
    by = {r["config"]: r for r in s["errors"]}
    freqs = {f["mesh"]: f for f in s["freqs"]}
    pairs = []
    for a, f in s["plan"]["pairs"]:
        for dt in (1e-6, 1e-5):
            ra, rf = by.get(f"{a}, Δt={fmt_dt(dt)}"), by.get(f"{f}, Δt={fmt_dt(dt)}")
            if ra and rf and a in freqs and f in freqs:
                if ra["err_trajectory"] is not None and rf["err_trajectory"] is not None:
                    pairs.append(dict(a=ra, f=rf, mesh_a=a, mesh_f=f, f1_a=freqs[a], f1_f=freqs[f], dt=fmt_dt(dt)))
                break
    seqs = s["quantities"]["trajectory"]["sequences"]
    orders = [dict(name=q["name"], order=q["orders"][-1]) for q in seqs if q["orders"]]
    return dict(
        modes=modes_notes(s),
        orders=orders,
        orders_below_second=any(o["order"] < 1.5 for o in orders if o["name"].startswith("Δt")),
        free_first=s["quantities"]["energy_lost_0p5s"]["sequences"][0],
        free_h=[
            dict(
                mesh=q["name"].split(", ")[1],
                at=q["name"].split(", ")[-1],
                values=q["values"],
                trend=trend(q["values"]),
            )
            for q in s["quantities"]["energy_lost_0p5s"]["sequences"]
            if q["name"].startswith("h") and len(q["values"]) >= 2
        ],
        pairs=pairs,
        scaling=scaling_notes(s["scaling"]),
    )


def trend(v):
    if all(b > a for a, b in zip(v, v[1:])):
        return "rise"
    return "fall" if all(b < a for a, b in zip(v, v[1:])) else "go up and down"


def modes_notes(s):
    base = s["plan"]["free_base"]
    mesh_of = base.split(", ")[0]
    on_base = sorted((m for m in s["modes"] if m["config"].startswith(base + ", m=")), key=modes_of)
    finer = sorted(
        (m for m in s["modes"] if m["config"].startswith(mesh_of + ", ") and not m["config"].startswith(base)),
        key=modes_of,
    )
    es = [m["energy_dissipated"] for m in on_base]
    exact = next(r for r in s["free"] if r["config"] == base)
    return dict(
        on_base=on_base,
        finer=finer,
        falling=all(b <= a for a, b in zip(es, es[1:])),
        dofs=exact["dofs"],
        exact=exact["energy_dissipated"],
    )


def modes_of(m):
    return int(m["config"].split("m=")[1].split(",")[0])


def scaling_notes(rows):
    out = dict(per_element=[], sparse_range=None, auto_sparse_over=[], modal_faster=[], sparse_faster=[])
    for element in ("argyris", "fvs"):
        sparse = sorted(
            (r for r in rows if r["element"] == element and r["sparse"]["engine"] == "sparse"), key=lambda r: r["dofs"]
        )
        if len(sparse) >= 2:
            big = [r for r in sparse if r["dofs"] >= 1000] or sparse
            dofs = [r["dofs"] for r in big]
            out["per_element"].append(
                dict(
                    element="Argyris" if element == "argyris" else "FVS",
                    dofs_from=big[0]["dofs"],
                    dofs_to=big[-1]["dofs"],
                    floor_slope=loglog_slope(dofs, [r["sparse"]["floor_solve_s"] for r in big]),
                    step_slope=loglog_slope(dofs, [r["sparse"]["step_s"] for r in big]),
                    ratios=[[r["dofs"], r["sparse"]["step_over_floor"]] for r in sparse],
                )
            )
    ratios = [r["sparse"]["step_over_floor"] for r in rows if r["sparse"]["engine"] == "sparse"]
    if ratios:
        out["sparse_range"] = [min(ratios), max(ratios)]
    for r in rows:
        auto, modal = r["auto"], r.get("modal_step_s")
        if auto["engine"] == "sparse" and auto["step_over_floor"] > 1.2:
            out["auto_sparse_over"].append(r)
        if modal and auto["engine"] == "sparse" and modal < 0.8 * auto["step_s"]:
            out["modal_faster"].append(r)
        if modal and auto["engine"] != "sparse" and r["sparse"]["step_s"] < 0.8 * auto["step_s"]:
            out["sparse_faster"].append(r)
    return out


def loglog_slope(xs, ys):
    """The slope of log ys against log xs (least squares), nan below two points."""
    xs, ys = np.log(np.asarray(xs, float)), np.log(np.asarray(ys, float))
    return float(np.polyfit(xs, ys, 1)[0]) if len(xs) >= 2 else float("nan")


def goal_verdicts(ctx):
    """The goals: each its title, verdict and the numbers the page's "measured" cell quotes
    (docs/templates/performance.md writes the cell); and the headline lines printed at the end."""
    goals = [g for goal in (goal_default, goal_modes, goal_envelope, goal_baseline) for g in goal(ctx)]
    return goals, [g["line"] for g in goals if g.get("line")]


def goal_default(ctx):
    """The exact default scene's wall time, and its step/floor."""
    plan, d, fmu = ctx["plan"], ctx["dflt"], ctx["fmu"]
    bench = d["setup_s"] + d["wall_s"]
    limit = 2.5 * plan["default_T"]
    wall = fmu["total_s"] if fmu else bench
    cpu = fmu["cpu_s"] if fmu else d["setup_s"] + d["step_s"] * d["steps"]
    verdict = (
        "**met**" if wall <= limit else "**met on CPU time**, not on the wall clock" if cpu <= limit else "**not met**"
    )
    line = f"default scene: FMU {wall:.2f} s wall, plate_bench {bench:.2f} s, step/floor {d['step_over_floor']:.2f}"
    return [
        dict(
            key="default",
            goal=f"exact default scene ({plan['default'].label()}, {plan['default_T']:g} s) ≤ 2.5 s wall",
            verdict=verdict,
            repeats=plan["default_repeats"],
            bench_s=bench,
            line=line,
        ),
        dict(
            key="step_floor",
            goal="step/floor ≤ 1.2 (same scene)",
            verdict="**met**" if d["step_over_floor"] <= 1.2 else "**not met**",
            rtf=d["rtf"],
        ),
    ]


def goal_modes(ctx):
    """`modes` against the exact scheme on the §5.2 energy lost, on the base mesh and Δt."""
    free, base = ctx["free"], ctx["free"]["base"]
    ms = sorted(
        (m for m in free["modes"] if (m["cfg"].dt, m["cfg"].element, m["cfg"].nx) == (base.dt, base.element, base.nx)),
        key=lambda m: m["cfg"].modes,
    )
    if not ms:
        return []
    rows = [
        dict(m=m["cfg"].modes, energy=m["run"]["energy_dissipated"], rel_err=m["rel_err"], speedup=m["speedup"])
        for m in ms
    ]
    within = [r for r in rows if abs(r["rel_err"]) <= 0.01]
    fast = [r for r in rows if r["speedup"] >= 10]
    both = [r for r in within if r["speedup"] >= 10]
    return [
        dict(
            key="modes",
            goal=f"`modes` ≥ 10× faster than exact with ≤ 1 % error on the energy lost by 0.5 s (§5.2), {base.label()}",
            verdict=f"**met** at m = {both[0]['m']}" if both else "**not met**",
            exact=free["runs"][base]["energy_dissipated"],
            modes=rows,
            first_within=within[0] if within else None,
            best_fast=fast[-1] if fast else None,
            line=f"modes (§5.2 energy lost): first within 1 % at m = {within[0]['m']}"
            if within
            else "modes: never within 1 %",
        )
    ]


def goal_envelope(ctx):
    """`modes` against the exact scheme on the sine scene's envelope."""
    long = ctx["long"]
    lrows, lbase = {r["cfg"]: r for r in long["rows"]}, long["base"]
    lm = sorted(
        (r for c, r in lrows.items() if c.modes and c.nx == lbase.nx and c.dt == lbase.dt), key=lambda r: r["cfg"].modes
    )
    if not lm or lbase not in lrows:
        return []
    ex = lrows[lbase]
    rows = [
        dict(
            m=r["cfg"].modes,
            envelope=r["period_envelope"],
            rel=r["period_envelope"] / ex["period_envelope"] - 1,
            speedup=ex["run"]["step_s"] / r["run"]["step_s"],
        )
        for r in lm
    ]
    noise, dth = long["roundoff_rel"], long["dt_half_rel"]
    spread = max((x for x in (noise, dth) if math.isfinite(x)), default=float("nan"))
    verdict = [
        "max |corner|: **vacuous** (0 % error for every m: the corner is a mesh vertex held at the obstacle)"
    ] * long["pinned"]
    if math.isfinite(spread) and spread > 0.01:
        verdict.append(
            f"per-period envelope: **not met / cannot be claimed** (not reproducible to 1 %: {100 * spread:.1f} % from roundoff or Δt/2 alone)"
        )
    else:
        ok = [r for r in rows if r["speedup"] >= 10 and abs(r["rel"]) <= 0.01]
        verdict.append("per-period envelope: " + (f"**met** at m = {ok[0]['m']}" if ok else "**not met**"))
    return [
        dict(
            key="envelope",
            goal="`modes` ≥ 10× faster with ≤ 1 % error on the sine-scene envelope (max |corner|)",
            verdict="; ".join(verdict),
            pinned=long["pinned"],
            exact=ex["period_envelope"],
            modes=rows,
            roundoff=noise,
            dt_half=dth,
        )
    ]


def goal_baseline(ctx):
    """The C++ step against the Python/SciPy baseline's."""
    py = ctx["py"]
    if "error" in py:
        return []
    r = py["ratio"]["auto"]
    return [
        dict(
            key="baseline",
            goal="≥ 50× faster than the Python/SciPy baseline per step",
            verdict="**met**" if r >= 50 else "**not met**",
            line=f"Python/SciPy baseline: {1e6 * py['step_s']:.0f} us/step, {r:.0f}x slower than C++ auto",
        )
    ]
