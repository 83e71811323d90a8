"""What the speed-against-error report computes (tools/speed_vs_error.py --quick --no-report, the
summary of tools/speed_summary.py in speed_vs_error.json): every error it reports is finite, the
convergence verdicts follow the documented rule from the differences it reports, an error is
reported exactly for the quantities that converge, the Python/SciPy baseline agrees with the
solver before the first impact, and the goal verdicts follow from the numbers beside them. No
timing is asserted, and the page is its template filled from the JSON (python_tests/test_render_docs.py)."""

import json
import math
import os
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import pytest
from speed_study import converges, make_plan

REPO = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("PLATEIMPACT_BUILD_DIR", REPO / "build"))
BENCH = Path(os.environ.get("PLATEIMPACT_BENCH", BUILD / "solver" / "bench" / "plate_bench"))
CONTRACTION = 0.75  # the documented rule, restated independently of the script


def rule(diffs, resolution):
    """At least two differences, each ≤ 0.75 × the previous one (a previous one below its
    resolution counts as the resolution), or within its own resolution."""
    if len(diffs) < 2 or not all(math.isfinite(d) for d in diffs):
        return False
    return all(
        d2 <= max(CONTRACTION * max(d1, r1), r2) for d1, d2, r1, r2 in zip(diffs, diffs[1:], resolution, resolution[1:])
    )


@pytest.mark.parametrize(
    "diffs, resolution, expected",
    [
        ([1.0], [0.0], False),  # one difference shows nothing
        ([1.0, 0.5, 0.25], [0.0] * 3, True),
        ([1.0, 0.75], [0.0] * 2, True),  # exactly the contraction
        ([1.0, 0.76], [0.0] * 2, False),
        ([1.0, 0.5, 0.6], [0.0] * 3, False),  # one step that does not shrink
        ([1e-4, 1e-4, 1e-4], [1e-4] * 3, True),  # within the resolution (an impact time on its output step)
        ([1e-6, 5e-5], [1e-4] * 2, True),  # below its resolution: compared as the resolution
        ([1e-6, 2e-4], [1e-4] * 2, False),
        ([1.0, float("nan")], [0.0] * 2, False),
    ],
)
def test_the_rule(diffs, resolution, expected):
    """speed_study.converges(), the rule the report applies, against the rule as documented."""
    assert rule(diffs, resolution) is expected
    assert converges(diffs, resolution) is expected


@pytest.fixture(scope="module")
def summary(tmp_path_factory, fmu_path):
    if not BENCH.exists():
        pytest.skip(f"plate_bench not built ({BENCH})")
    pytest.importorskip("osqp")
    out = tmp_path_factory.mktemp("perf")
    proc = subprocess.run(
        [
            sys.executable,
            str(REPO / "tools" / "speed_vs_error.py"),
            "--quick",
            "--no-report",
            "--out",
            str(out),
            "--bench",
            str(BENCH),
            "--fmu",
            str(fmu_path),
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    assert sorted(p.name for p in out.iterdir()) == ["speed_vs_error.json"]  # --no-report: the summary only
    return json.loads((out / "speed_vs_error.json").read_text())


def finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def test_every_reported_error_is_finite(summary):
    s = summary
    assert s["quick"] is True
    assert s["errors"], "no sine-scene rows"
    for row in s["errors"]:
        for key in ("wall_per_sim_s", "rtf", "step_over_floor"):
            assert finite(row[key]) and row[key] > 0, row
        for key in ("err_trajectory", "err_impact"):
            assert row[key] is None or (finite(row[key]) and row[key] >= 0), row
    assert s["modes"]
    for m in s["modes"]:
        assert finite(m["rel_err"]) and finite(m["speedup"]) and m["speedup"] > 0, m
    b = s["baseline"]
    assert b is not None and "error" not in b
    for key in ("step_s", "free_phase_step_s", "contact_phase_step_s"):
        assert finite(b[key]) and b[key] > 0
    for engine in ("auto", "sparse"):
        assert finite(b["ratio"][engine]) and b["ratio"][engine] > 0
        # the baseline is the same scheme: before the first impact it agrees to roundoff
        assert b["agree"][engine]["before"] < 1e-8
        assert finite(b["agree"][engine]["after"])
    for row in s["scaling"]:
        for engine in ("auto", "sparse"):
            assert finite(row[engine]["step_over_floor"]) and row[engine]["step_over_floor"] > 0


def test_convergence_verdicts_follow_the_rule(summary):
    q = summary["quantities"]
    for name in ("trajectory", "impact", "energy_lost_0p5s"):
        seqs = q[name]["sequences"]
        assert seqs
        for seq in seqs:
            assert len(seq["diffs"]) == len(seq["labels"]) - 1
            assert seq["converges"] == rule(seq["diffs"], seq["resolution"]), seq["name"]
        assert q[name]["converges"] == all(seq["converges"] for seq in seqs)
    # an error is reported for a quantity exactly when that quantity converges (the reference
    # row itself carries none)
    for key, name in (("err_trajectory", "trajectory"), ("err_impact", "impact")):
        reported = [row[key] is not None for row in summary["errors"]]
        if q[name]["converges"]:
            assert sum(reported) == len(reported) - 1
        else:
            assert not any(reported)
    # the envelope max |corner| is never used as an error
    assert q["envelope_max_corner"]["converges"] is False


def test_goal_verdicts_follow_the_numbers(summary):
    plan = make_plan(True)
    goals = summary["goals"]

    def goal(prefix):
        found = [g for g in goals if g["goal"].startswith(prefix)]
        assert len(found) == 1, (prefix, [g["goal"] for g in goals])
        return found[0]["verdict"]

    def met(verdict):
        return verdict.startswith("**met")

    # the default scene within 2.5 × its horizon: on the FMU's wall clock, else on its CPU time
    fmu, bench = summary["default"]["fmu"], summary["default"]["bench"]
    assert fmu is not None
    limit = 2.5 * plan["default_T"]
    verdict = goal("exact default scene")
    assert (verdict == "**met**") == (fmu["total_s"] <= limit)
    assert met(verdict) == (fmu["total_s"] <= limit or fmu["cpu_s"] <= limit)
    assert met(goal("step/floor ≤ 1.2")) == (bench["step_over_floor"] <= 1.2)
    # modes on the base mesh and Δt: met when one m is both within 1 % and ≥ 10× faster
    base_modes = {replace(plan["free_modes_base"], modes=m).label() for m in plan["free_modes"]}
    ms = [m for m in summary["modes"] if m["config"] in base_modes]
    assert len(ms) == len(base_modes)
    assert met(goal("`modes` ≥ 10× faster than exact")) == any(
        abs(m["rel_err"]) <= 0.01 and m["speedup"] >= 10 for m in ms
    )
    assert met(goal("≥ 50× faster than the Python/SciPy baseline")) == (summary["baseline"]["ratio"]["auto"] >= 50)
