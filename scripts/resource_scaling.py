"""The scaling table of docs/performance.md ("Resources"): for meshes of the default scene's
aspect (14:5) from 7 x 3 up to the largest the default budget (memory_limit = 2048 MB) admits,
both elements and each engine, the resource estimate (ResourceEstimate.h) beside what is
measured — peak RSS and initialization time of plate_bench in its own process, time per step
(CPU time; no contact in these short runs) and the floor (one solve with the factor of A) —
and the fitted growth exponents against the dof count.

    .venv/bin/python scripts/resource_scaling.py --bench build/solver/bench/plate_bench [--max-init 120]

Sizes whose estimated initialization exceeds --max-init seconds are not run: their row shows
the estimate only. --json writes the rows, the fits and the comparisons of estimate and measurement
(docs/resource_scaling.json, which tools/render_docs.py renders into docs/performance.md):

    .venv/bin/python scripts/resource_scaling.py --max-init 15 --json docs/resource_scaling.json
    .venv/bin/python tools/render_docs.py performance.md
"""

import argparse
import json
import math
import os
import subprocess
import time

MEMORY_LIMIT_MB = 2048  # the default budget
PREDICTED = ("argyris", 400, 400)  # a mesh the first stage refuses from nx and ny alone
ASPECT = [(7, 3), (14, 5), (28, 10), (56, 20), (84, 30), (112, 40), (168, 60), (224, 80), (280, 100)]


def bench(path, **args):
    cmd = ["nice", "-n", "10", path] + [f"{k}={v}" for k, v in args.items()]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        return None, done.stderr.strip()
    return json.loads(done.stdout.strip().splitlines()[-1]), None


def fit(xs, ys):
    """Least-squares exponent and constant of y = c x^a in log-log."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    a = sum((u - mx) * (v - my) for u, v in zip(lx, ly)) / sum((u - mx) ** 2 for u in lx)
    return a, math.exp(my - a * mx)


def measure(path, element, engine, nx, ny, max_init):
    est, refused = bench(
        path, element=element, nx=nx, ny=ny, engine=engine, estimate_only=1, memory_limit=MEMORY_LIMIT_MB
    )
    if est is None:
        return {"element": element, "engine": engine, "nx": nx, "ny": ny, "refused": refused}
    row = {"element": element, "engine": engine, "nx": nx, "ny": ny, **est}
    if est["est_init_s"] > max_init:
        row["skipped"] = True
        return row
    steps = int(min(5000, max(20, 1.0 / max(est["est_step_s"], 1e-7))))
    run, error = bench(path, element=element, nx=nx, ny=ny, engine=engine, steps=steps, floor_repeats=200)
    if run is None:
        row["error"] = error
        return row
    row.update(run)
    row["rss_mb"] = run["rss_peak_mb"] - run["rss_before_mb"]
    row["ratio"] = run["step_cpu_s"] / run["floor_cpu_s"]
    return row


def table(rows):
    out = [
        "| element | engine | mesh | dofs | nnz(K) | nnz(L) | memory est. MB | peak RSS MB | init est. s | init s "
        "| step s | step/floor |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        mesh = f"{r['nx']} × {r['ny']}"
        if "refused" in r:
            out.append(f"| {r['element']} | {r['engine']} | {mesh} | refused: {r['refused'][:90]}… |")
            continue
        if r.get("skipped") or "init_s" not in r:
            out.append(
                f"| {r['element']} | {r['engine']} | {mesh} | {r['dofs']} | {r['nnz_k']} | {r['nnz_l']} | "
                f"{r['est_peak_mb']:.0f} | (not run) | {r['est_init_s']:.3g} | — | ({r['est_step_s']:.2g} est.) | — |"
            )
            continue
        out.append(
            f"| {r['element']} | {r['engine']} | {mesh} | {r['dofs']} | {r['nnz_k']} | {r['nnz_l']} | "
            f"{r['est_peak_mb']:.0f} | {r['rss_mb']:.0f} | {r['est_init_s']:.3g} | {r['init_s']:.3g} | "
            f"{r['step_cpu_s']:.3g} | {r['ratio']:.2f} |"
        )
    return "\n".join(out)


def fit_rows(rows):
    """Per element, the growth exponents against the dof count (sparse engine, measured sizes with
    n >= 2000) and the dof counts where the fitted init time reaches 10 s and 60 s."""
    out = []
    for element in ("argyris", "fvs"):
        run = [r for r in rows if r["element"] == element and r["engine"] == "sparse" and "init_s" in r]
        run = [r for r in run if r["dofs"] >= 2000]
        if len(run) < 3:
            continue
        n = [r["dofs"] for r in run]
        exponents = {key: fit(n, [r[key] for r in run])[0] for key in ("nnz_l", "rss_mb", "init_s", "step_cpu_s")}
        a, c = fit(n, [r["init_s"] for r in run])
        out.append(
            {
                "element": element,
                "dofs_from": min(n),
                "dofs_to": max(n),
                "exponents": exponents,
                "init_10s_dofs": (10 / c) ** (1 / a),
                "init_60s_dofs": (60 / c) ** (1 / a),
            }
        )
    return out


def fits(rows):
    names = {"nnz_l": "nnz(L)", "rss_mb": "peak RSS", "init_s": "init", "step_cpu_s": "step"}
    return "\n".join(
        f"- {f['element']}, sparse engine, n = {f['dofs_from']}…{f['dofs_to']}: "
        + ", ".join(f"{names[k]} ~ n^{a:.2f}" for k, a in f["exponents"].items())
        + f"; init = 10 s at n ≈ {f['init_10s_dofs']:.0f}, init = 60 s at n ≈ {f['init_60s_dofs']:.0f}"
        for f in fit_rows(rows)
    )


def span(values):
    values = list(values)
    return {"min": min(values), "max": max(values), "count": len(values)} if values else None


def comparisons(rows, memory_above_mb=10.0, init_from_dofs=2000, step_above_dofs=20000):
    """The estimate against the measurement: memory per engine over the sizes above `memory_above_mb`,
    the most the smaller ones are overestimated by, init time (wall) from `init_from_dofs` (the sizes
    the fits use: below them a process's fixed start dominates), step (CPU) above `step_above_dofs`;
    per element, the largest measured mesh that initialized under 10 s and the next one."""
    run = [r for r in rows if "rss_mb" in r]
    under10 = {}
    for element in ("argyris", "fvs"):
        sizes = sorted((r for r in run if r["element"] == element and r["engine"] == "sparse"), key=lambda r: r["dofs"])
        below = [r for r in sizes if r["init_s"] < 10]
        above = [r for r in sizes if r["init_s"] >= 10]
        pick = lambda r: {"mesh": f"{r['nx']} × {r['ny']}", "dofs": r["dofs"], "init_s": r["init_s"]}  # noqa: E731
        under10[element] = {
            "last_below": pick(below[-1]) if below else None,
            "first_above": pick(above[0]) if above else None,
        }
    return {
        "memory_above_mb": memory_above_mb,
        "memory_ratio": {
            engine: span(
                r["est_peak_mb"] / r["rss_mb"] for r in run if r["rss_mb"] > memory_above_mb and r["engine"] == engine
            )
            for engine in sorted({r["engine"] for r in run})
        },
        "small_overestimate_mb": max(
            (r["est_peak_mb"] - r["rss_mb"] for r in run if r["rss_mb"] <= memory_above_mb), default=None
        ),
        "init_from_dofs": init_from_dofs,
        "init_over_estimate": span(r["init_s"] / r["est_init_s"] for r in run if r["dofs"] >= init_from_dofs),
        "step_above_dofs": step_above_dofs,
        "step_over_estimate": span(r["step_cpu_s"] / r["est_step_s"] for r in run if r["dofs"] > step_above_dofs),
        "init_under_10s": under10,
    }


def predicted_refusal(path):
    """The first stage's refusal of a mesh far beyond the budget: its message and the wall time."""
    element, nx, ny = PREDICTED
    t0 = time.perf_counter()
    est, refused = bench(path, element=element, nx=nx, ny=ny, estimate_only=1, memory_limit=MEMORY_LIMIT_MB)
    wall = time.perf_counter() - t0
    needs = refused and next((w for w in refused.split("estimated ")[1:2]), "")
    return {
        "element": element,
        "mesh": f"{nx} × {ny}",
        "refused": est is None,
        "predicted_mb": float(needs.split(" MB")[0]) if needs else None,
        "wall_s": wall,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bench", default="build/solver/bench/plate_bench")
    parser.add_argument("--max-init", type=float, default=120.0)
    parser.add_argument("--json", help="also write the rows as JSON here")
    parser.add_argument(
        "--summarize", help="recompute the fits and comparisons of this JSON's rows (no measurement) and rewrite it"
    )
    args = parser.parse_args()
    if args.summarize:
        with open(args.summarize) as f:
            report = json.load(f)
        report.update(fits=fit_rows(report["rows"]), comparisons=comparisons(report["rows"]))
        with open(args.summarize, "w") as f:
            json.dump(report, f, indent=1)
            f.write("\n")
        print(fits(report["rows"]))
        return
    rows = []
    for element in ("argyris", "fvs"):
        for engine in ("sparse", "modal"):
            for nx, ny in ASPECT:
                row = measure(args.bench, element, engine, nx, ny, args.max_init)
                print(json.dumps(row), flush=True)
                rows.append(row)
                if "refused" in row or "error" in row:
                    break  # the next sizes are larger still
    if args.json:
        for r in rows:
            r["mesh"] = f"{r['nx']} × {r['ny']}"
        report = {
            "command": f"scripts/resource_scaling.py --max-init {args.max_init:g}",
            "max_init_s": args.max_init,
            "memory_limit_mb": MEMORY_LIMIT_MB,
            "rows": rows,
            "fits": fit_rows(rows),
            "comparisons": comparisons(rows),
            "predicted_refusal": predicted_refusal(args.bench),
            "commit": subprocess.run(
                ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True
            ).stdout.strip(),
            "date": time.strftime("%Y-%m-%d"),
            "load_average": os.getloadavg()[0],
            "cores": os.cpu_count(),
        }
        with open(args.json, "w") as f:
            json.dump(report, f, indent=1)
            f.write("\n")
    print(table(rows))
    print()
    print(fits(rows))


if __name__ == "__main__":
    main()
