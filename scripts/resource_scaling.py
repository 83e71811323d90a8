"""The scaling table of docs/performance.md ("Resources"): for meshes of the default scene's
aspect (14:5) from 7 x 3 up to the largest the default budget (memory_limit = 2048 MB) admits,
both elements and each engine, the resource estimate (ResourceEstimate.h) beside what is
measured — peak RSS and initialization time of plate_bench in its own process, time per step
(CPU time; no contact in these short runs) and the floor (one solve with the factor of A) —
and the fitted growth exponents against the dof count.

    .venv/bin/python scripts/resource_scaling.py --bench build/solver/bench/plate_bench [--max-init 120]

Sizes whose estimated initialization exceeds --max-init seconds are not run: their row shows
the estimate only, and the init time is extrapolated with the fit (marked so).
"""

import argparse
import json
import math
import subprocess

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
    est, refused = bench(path, element=element, nx=nx, ny=ny, engine=engine, estimate_only=1, memory_limit=2048)
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


def fits(rows):
    out = []
    for element in ("argyris", "fvs"):
        run = [r for r in rows if r["element"] == element and r["engine"] == "sparse" and "init_s" in r]
        run = [r for r in run if r["dofs"] >= 2000]
        if len(run) < 3:
            continue
        n = [r["dofs"] for r in run]
        parts = []
        for key, name in (("nnz_l", "nnz(L)"), ("rss_mb", "peak RSS"), ("init_s", "init"), ("step_cpu_s", "step")):
            a, _ = fit(n, [r[key] for r in run])
            parts.append(f"{name} ~ n^{a:.2f}")
        a, c = fit(n, [r["init_s"] for r in run])
        limits = ", ".join(f"init = {t} s at n ≈ {(t / c) ** (1 / a):.0f}" for t in (10, 60))
        out.append(f"- {element}, sparse engine, n = {min(n)}…{max(n)}: " + ", ".join(parts) + f"; {limits}")
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bench", default="build/solver/bench/plate_bench")
    parser.add_argument("--max-init", type=float, default=120.0)
    parser.add_argument("--json", help="also write the rows as JSON here")
    args = parser.parse_args()
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
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    print(table(rows))
    print()
    print(fits(rows))


if __name__ == "__main__":
    main()
