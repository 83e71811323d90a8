"""What a fine mesh's setup costs through the FMU (issue 70; docs/performance.md, "The condensed plate
on fine meshes"): each plate in its own process instantiated and initialized by fmpy (the package's
driver), its setup's process CPU time and peak RSS (VmHWM, beside the process's before the setup)
against the resource estimate the FMU logs, then a short run of the default drive (0.09 sin(2π·10 t) m,
communication step 1e-4 s) to show it steps, with its CPU per communication step.

    python tools/fine_mesh_setup.py [--fmu build/PlateImpact.fmu] [--json docs/fine_mesh_setup.json]
                                    [--stop 0.005] [--only 56x20] [--summarize]

About five minutes on the 2-core machine (112 × 40 is most of it).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
FLOW = {"time_scheme": "flow", "mass": "singular_p0"}
# (mesh, modes, law, mass): the default mesh and 28 × 10 (the dense condensation, bit for bit as
# before), 56 × 20 on 40, 100 and 250 modes and with the conserving law, 112 × 40 on 100 modes: the
# issue's goals; then the paper's law with the consistent mass on a few modes (Lanczos, Spectrum.cpp).
CASES = [
    ((14, 5), 0, "flow", "singular_p0"),
    ((28, 10), 40, "flow", "singular_p0"),
    ((56, 20), 40, "flow", "singular_p0"),
    ((56, 20), 100, "flow", "singular_p0"),
    ((56, 20), 250, "flow", "singular_p0"),
    ((56, 20), 100, "conserving", "singular_p0"),
    ((112, 40), 100, "flow", "singular_p0"),
    ((56, 20), 60, "newmark", "consistent"),
    ((112, 40), 100, "newmark", "consistent"),
]
FINE_DOFS = 10000
GOALS = {"56x20": {"cpu_s": 3.0, "rss_mb": 300.0}, "112x40": {"cpu_s": 30.0, "rss_mb": 2048.0}}


def vm_hwm_mb():
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024.0
    return float("nan")


def one(fmu, nx, ny, modes, law, mass, stop):
    """In the child process: the setup and the short run of one plate; its row as JSON on stdout."""
    sys.path.insert(0, str(REPO / "python"))
    from plateimpact import PlateImpactFMU
    from plateimpact.scenes import default_base

    params = {"nx": nx, "ny": ny, "modes": modes, "time_scheme": law, "mass": mass}
    log = []
    rss0 = vm_hwm_mb()
    cpu0 = time.process_time()
    plate = PlateImpactFMU(fmu, logger=lambda s, c, m: log.append((s, m)), base0=default_base(0.0)[0], **params)
    setup_cpu = time.process_time() - cpu0
    rss = vm_hwm_mb()
    estimate = next(m for _, m in log if "resource estimate:" in m)
    h, steps = 1e-4, round(stop / 1e-4)
    cpu1 = time.process_time()
    for k in range(steps):
        out = plate.step(h, base=default_base(k * h))
    step_cpu = (time.process_time() - cpu1) / steps
    plate.close()
    return {
        "mesh": f"{nx}x{ny}",
        "modes": modes,
        "law": law,
        "mass": mass,
        "dofs": int(re.search(r"(\d+) free dofs", estimate).group(1)),
        "contact_rows": int(re.search(r"(\d+) contact vertices", estimate).group(1)),
        "setup_cpu_s": setup_cpu,
        "rss_mb": rss,
        "rss_before_mb": rss0,
        "est_init_s": float(re.search(r"initialization ~([\d.e+-]+) s", estimate).group(1)),
        "est_peak_mb": float(re.search(r"memory peak (\d+) MB", estimate).group(1)),
        "warnings": [m for s, m in log if s == 1],
        "steps": steps,
        "step_cpu_ms": 1e3 * step_cpu,
        "corner_1_end": out["corner_1"],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fmu", default=str(REPO / "build" / "PlateImpact.fmu"))
    ap.add_argument("--json", default=str(REPO / "docs" / "fine_mesh_setup.json"))
    ap.add_argument("--stop", type=float, default=0.005, help="the short run after the setup, s")
    ap.add_argument("--only", help="one mesh, e.g. 56x20 (no JSON written)")
    ap.add_argument("--summarize", action="store_true", help="recompute the goals and ratios of --json")
    ap.add_argument("--child", nargs=5, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.summarize:
        out = summarize(json.loads(Path(args.json).read_text()))
        Path(args.json).write_text(json.dumps(out, indent=1) + "\n")
        return 0
    if args.child:
        nx, ny, modes = (int(v) for v in args.child[:3])
        print(json.dumps(one(args.fmu, nx, ny, modes, args.child[3], args.child[4], args.stop)))
        return 0
    rows = []
    for (nx, ny), modes, law, mass in CASES:
        if args.only and args.only != f"{nx}x{ny}":
            continue
        cmd = [sys.executable, __file__, "--fmu", args.fmu, "--stop", str(args.stop), "--child"]
        r = subprocess.run([*cmd, str(nx), str(ny), str(modes), law, mass], capture_output=True, text=True, check=True)
        row = json.loads(r.stdout.strip().splitlines()[-1])
        rows.append(row)
        print(
            f"{row['mesh']:>7} m{modes:<4} {law:10s} {mass:11s} {row['dofs']:6d} dofs {row['contact_rows']:5d} rows: setup "
            f"{row['setup_cpu_s']:7.2f} s CPU (est. {row['est_init_s']:.3g}), {row['rss_mb']:6.0f} MB "
            f"(est. {row['est_peak_mb']:.0f}); {row['steps']} steps {row['step_cpu_ms']:.2f} ms CPU each",
            flush=True,
        )
    if args.only:
        return 0
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True, text=True)
    out = {
        "commit": commit.stdout.strip(),
        "date": time.strftime("%Y-%m-%d"),
        "cores": os.cpu_count(),
        "load_average": os.getloadavg()[0],
        "stop_s": args.stop,
        "rows": rows,
    }
    Path(args.json).write_text(json.dumps(summarize(out), indent=1) + "\n")
    return 0


def summarize(out):
    """Each row's goal and its measured over estimated setup CPU and memory (the setup's own: the peak
    less the process before it, Python and fmpy), and their range over the fine meshes (from
    FINE_DOFS free dofs: the sparse condensation, the estimate's stated accuracy of 1.5×)."""
    for row in out["rows"]:
        row["cpu_over_estimate"] = row["setup_cpu_s"] / row["est_init_s"]
        row["rss_over_estimate"] = (row["rss_mb"] - row["rss_before_mb"]) / row["est_peak_mb"]
        goal = GOALS.get(row["mesh"]) if row["modes"] == 100 and row["law"] == "flow" else None
        if goal:
            row["goal"] = goal
            row["goal_cpu_met"] = row["setup_cpu_s"] <= goal["cpu_s"]
            row["goal_rss_met"] = row["rss_mb"] <= goal["rss_mb"]
    fine = [r for r in out["rows"] if r["dofs"] >= FINE_DOFS]
    out["fine_dofs"] = FINE_DOFS
    for key in ("cpu_over_estimate", "rss_over_estimate"):
        out[key] = {"min": min(r[key] for r in fine), "max": max(r[key] for r in fine)}
    return out


if __name__ == "__main__":
    raise SystemExit(main())
