"""The error against the plate (docs/performance.md "The error against the plate", docs/theory.md
§26): for each scene the converged plate from a mesh ladder (Richardson with the measured order, and
the verdict whether it converges), every candidate configuration's error against it and CPU per
simulated second (the front), and what discretization_check says against that error.

    python tools/plate_front.py [--fmu build/PlateImpact.fmu] [--json docs/plate_front.json]
                                [--figures docs/figures] [--scenes default,s52,fvs,...] [--workers 2]

Scenes (the FMU's parameters and a drive, dt = 1e-5 s for the ladder):
  default   the FMU's default scene: 0.09 sin(2π·10 t) m, obstacles ±0.1 m; windows 0.05 and 0.1 s
  s52       the paper's §5.2: released from 8600 Pa onto the lower obstacle; windows 0.1 and 0.3 s
  fvs       contact-rich: obstacles ±0.01 m, 0.008 sin(2π·25 t) m, Rayleigh a = 2 1/s, b = 1e-5 s, with
            FVS candidates; windows 0.05 and 0.1 s
  and scenes the check was not tuned on (fixed before it was measured):
  wide      a 0.8 × 0.5 m plate 6 mm thick, obstacles -0.03/+0.05 m, 0.02 sin(2π·15 t) m; 0.1 s
  pressed   the default plate under a load of -3000 Pa and 0.03 sin(2π·8 t) m, obstacles ±0.06 m; 0.2 s
  free      the default drive with both obstacles off (no impact: the linear plate); 0.1 and 0.2 s
  thick     a 20 mm plate between obstacles ±5 mm, 0.004 sin(2π·40 t) m (parts early); 0.05 and 0.1 s
The check: discretization_check on six configurations per scene (the default, the flow law on the
base mesh, the doubled mesh on 40 modes, FVS on 40 modes, the paper's law on 2 modes and the flow law
on 3), its discretization_error against the
error measured against the converged plate at each window: the promise (theory §26) is that it never
under-states, i.e. at least the error less the plate's own uncertainty; and its CPU against the same
run without it (the least of three interleaved runs each).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "python"))

from plateimpact import convergence as cv  # noqa: E402
from plateimpact import sizing  # noqa: E402

SCENES = {
    "default": ({"parameters": {}, "drive": {"amplitude": 0.09, "frequency": 10}}, (0.05, 0.1)),
    "s52": (
        {"parameters": {"initial_load": 8600, "obstacle_upper_enabled": False}, "drive": {"amplitude": 0}},
        (0.1, 0.3),
    ),
    "fvs": (
        {
            "parameters": {
                "obstacle_lower": -0.01,
                "obstacle_upper": 0.01,
                "damping_mass": 2,
                "damping_stiffness": 1e-5,
            },
            "drive": {"amplitude": 0.008, "frequency": 25},
        },
        (0.05, 0.1),
    ),
    "wide": (
        {
            "parameters": {
                "length": 0.8,
                "width": 0.5,
                "thickness": 0.006,
                "obstacle_lower": -0.03,
                "obstacle_upper": 0.05,
            },
            "drive": {"amplitude": 0.02, "frequency": 15},
        },
        (0.1,),
    ),
    "pressed": (
        {
            "parameters": {"obstacle_lower": -0.06, "obstacle_upper": 0.06},
            "drive": {"amplitude": 0.03, "frequency": 8, "load": -3000},
        },
        (0.2,),
    ),
    "free": (
        {
            "parameters": {"obstacle_lower_enabled": False, "obstacle_upper_enabled": False},
            "drive": {"amplitude": 0.09, "frequency": 10},
        },
        (0.1, 0.2),
    ),
    "thick": (
        {
            "parameters": {"thickness": 0.02, "obstacle_lower": -0.005, "obstacle_upper": 0.005},
            "drive": {"amplitude": 0.004, "frequency": 40},
        },
        (0.05, 0.1),
    ),
}
TUNED = ("default", "s52", "fvs")  # the scenes the parting threshold was read from; the others were not
MEASURABLE = 0.5  # the reference's uncertainty against the error, at most, for the promise to be measured
ACCURACY = 1e-3  # m: the README's accurate configuration is the cheapest within it (§5.2 over 0.1 s)


def checked_configs(nx, ny):
    flow = {"time_scheme": "flow", "mass": "singular_p0"}
    return [
        {"nx": nx, "ny": ny},
        dict(flow, nx=nx, ny=ny),
        dict(flow, nx=2 * nx, ny=2 * ny, modes=40),
        dict(flow, element="fvs", nx=round(10 * nx / 7), ny=round(7 * ny / 5), modes=40),
        # a few modes, where the truncation is most of the error (theory §26, "A truncated modal basis")
        {"nx": nx, "ny": ny, "modes": 2},
        dict(flow, nx=nx, ny=ny, modes=3),
    ]


def _checked(fmu, scene_dict, config, until, repeats=3):
    """One check task: the run with the check on and the same run without it, interleaved
    `repeats` times; the CPU of each is its least (the one least disturbed by other work)."""
    from plateimpact.tasks import local_fmu

    scene = cv.Scene.from_dict(scene_dict)
    on, off = [], []
    for _ in range(repeats):
        on.append(cv.run(local_fmu(fmu), scene, config, until, check=True))
        off.append(cv.run(local_fmu(fmu), scene, config, until))
    return {
        "points": on[0].points,
        "same_bits": all(np.array_equal(a.points, b.points) for a in on for b in off),
        "estimate": on[0].estimate,
        "warned_at": on[0].warned_at,
        "cpu_on": min(r.cpu_per_second for r in on),
        "cpu_off": min(r.cpu_per_second for r in off),
    }


def summary(scenes):
    """The check over every scene and window: the promise kept or not; the range of estimate/error
    where the error is measurable, apart where it is Richardson's estimate and where the bound (past
    the horizon, theory §26); the CPU ratio's range."""
    windows = [(k, c, w, v) for k, s in scenes.items() for c in s["checks"] for w, v in c["windows"].items()]
    estimated = [v["ratio"] for *_, v in windows if v["measurable"] and not v["bound"]]
    bounded = [v["ratio"] for *_, v in windows if v["measurable"] and v["bound"]]
    ratios = [c["cpu_ratio"] for s in scenes.values() for c in s["checks"]]
    return {
        "windows": len(windows),
        "measurable": len(estimated) + len(bounded),
        "kept": sum(v["kept"] for *_, v in windows),
        "broken": [f"{k} {c['name']} {w} s" for k, c, w, v in windows if not v["kept"]],
        "ratio_min": min(estimated, default=None),
        "ratio_max": max(estimated, default=None),
        "estimated": len(estimated),
        "bound_ratio_min": min(bounded, default=None),
        "bound_ratio_max": max(bounded, default=None),
        "bounded": len(bounded),
        "cpu_ratio_min": min(ratios, default=None),
        "cpu_ratio_max": max(ratios, default=None),
        "same_bits": all(c["same_bits"] for s in scenes.values() for c in s["checks"]),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fmu", default=str(REPO / "build" / "PlateImpact.fmu"))
    ap.add_argument("--json", default=str(REPO / "docs" / "plate_front.json"))
    ap.add_argument("--figures", default=str(REPO / "docs" / "figures"))
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--no-check", action="store_true", help="the front only")
    args = ap.parse_args()
    from distributed import Client, LocalCluster

    from plateimpact.tasks import on_dask

    client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None))
    fmu_bytes = Path(args.fmu).read_bytes()
    out = {"sample_s": cv.SAMPLE, "scenes": {}}
    try:
        for key in args.scenes.split(","):
            scene_dict, windows = SCENES[key]
            until = max(windows)
            scene = cv.Scene.from_dict(scene_dict)
            print(f"== {key}: the ladder and the candidates over {until:g} s", flush=True)
            report = sizing.size(fmu_bytes, scene, until, ACCURACY, client, windows=windows)
            plates = report.pop("plates")
            sizing.figure(report, Path(args.figures) / f"plate_front_{key}.png", f"{key}, {until:g} s")
            checks = []
            nx, ny = sizing.base_mesh(scene.parameters)
            if not args.no_check:
                configs = checked_configs(nx, ny)
                results = on_dask(
                    client, _checked, fmu_bytes, [((scene_dict, c, until), {}) for c in configs], desc=f"{key} check"
                )
                for c, r in zip(configs, results):
                    row = {
                        "name": cv.label(c),
                        "same_bits": r["same_bits"],
                        "cpu_ratio": r["cpu_on"] / r["cpu_off"],
                        "windows": {},
                    }
                    for w in windows:
                        curve = cv.error_curve(r["points"], plates[w])
                        err, est = float(curve[-1]), float(r["estimate"][len(curve) - 1])
                        ref = report["references"][f"{w:g}"]
                        # The promise is measured where the converged plate is known to better than half
                        # the error; elsewhere the error itself is unknown (MEASURABLE).
                        measurable = ref["converges"] and ref["uncertainty"] <= MEASURABLE * err
                        # Never under-states: at least the error, which is known to ± the plate's uncertainty.
                        kept = est >= err - ref["uncertainty"]
                        row["windows"][f"{w:g}"] = {
                            "error": err,
                            "estimate": est,
                            "ratio": est / err,
                            "measurable": measurable,
                            "kept": kept,
                            "bound": r["warned_at"] is not None and r["warned_at"] <= w,
                        }
                    row["warned_at"] = r["warned_at"]
                    checks.append(row)
            # The cheapest configuration within ACCURACY of the plate over each window (error plus the
            # plate's own uncertainty): the README's recommendation reads §5.2's over 0.1 s.
            report["choices"] = {}
            for w in windows:
                unc = report["references"][f"{w:g}"]["uncertainty"]
                within = [r for r in report["candidates"] if r["errors"][f"{w:g}"] + unc <= ACCURACY]
                best = min(within, key=lambda r: r["cpu_per_second"]) if within else None
                default = next(r for r in report["candidates"] if r["config"] == {"nx": nx, "ny": ny})
                report["choices"][f"{w:g}"] = {
                    "name": best["name"] if best else None,
                    "config": best["config"] if best else None,
                    "error": best["errors"][f"{w:g}"] if best else None,
                    "cpu_per_second": best["cpu_per_second"] if best else None,
                    "default_error": default["errors"][f"{w:g}"],
                    "default_cpu_per_second": default["cpu_per_second"],
                }
            report["checks"] = checks
            report["tuned"] = key in TUNED
            report["windows"] = list(windows)
            out["scenes"][key] = report
            for w, ref in report["references"].items():
                print(
                    f"   plate over {w} s: {ref['verdict']}; d1 {ref['d1']:.3g} d2 {ref['d2']:.3g} m, uncertainty "
                    f"{ref['uncertainty']:.3g} m"
                )
            for r in sorted(report["candidates"], key=lambda r: r["cpu_per_second"]):
                errs = " ".join(f"{r['errors'][f'{w:g}']:.3g}" for w in windows)
                print(
                    f"   {r['name']:55s} {errs:>20s} m  {r['cpu_per_second']:.3g} s/s"
                    f"{'  front' if r['name'] in report['front'] else ''}"
                )
            for c in checks:
                ws = " ".join(
                    f"{w}: est {v['estimate']:.3g} / err {v['error']:.3g} = {v['ratio']:.2f}"
                    f"{'' if v['measurable'] else ' (not measurable)'}{'' if v['kept'] else ' BROKEN'}"
                    for w, v in c["windows"].items()
                )
                print(
                    f"   check {c['name']:45s} {ws}; warned at {c['warned_at']}; CPU ×{c['cpu_ratio']:.2f}; "
                    f"same bits {c['same_bits']}"
                )
            out["summary"] = summary(out["scenes"])
            Path(args.json).write_text(json.dumps(out, indent=1) + "\n")
    finally:
        client.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
