"""The speed-against-error report (tools/speed_vs_error.py) in its --quick form: it writes the
markdown table and the figures, every error it reports is finite, and the convergence verdicts
it prints follow its own rule from the differences it prints. No timing is asserted."""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

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


@pytest.fixture(scope="module")
def report(tmp_path_factory, fmu_path):
    if not BENCH.exists():
        pytest.skip(f"plate_bench not built ({BENCH})")
    pytest.importorskip("osqp")
    out = tmp_path_factory.mktemp("perf")
    proc = subprocess.run(
        [
            sys.executable,
            str(REPO / "tools" / "speed_vs_error.py"),
            "--quick",
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
    return out, proc.stdout, json.loads((out / "speed_vs_error.json").read_text())


def test_writes_table_and_figures(report):
    out, stdout, _ = report
    md = (out / "performance.md").read_text()
    for heading in (
        "## Headline numbers and goals",
        "## Which quantities converge",
        "## Per-step time and floor against the number of dofs",
        "## Plain Python/SciPy baseline",
    ):
        assert heading in md
    assert "tools/speed_vs_error.py --quick" in md  # the regenerate command
    assert "| goal | measured | verdict |" in md
    assert "figures/speed_vs_error.png" in md and "figures/scaling.png" in md
    for png in ("speed_vs_error.png", "scaling.png"):
        data = (out / "figures" / png).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20_000
    assert "wrote" in stdout


def finite(x):
    return isinstance(x, (int, float)) and math.isfinite(x)


def test_every_reported_error_is_finite(report):
    _, _, s = report
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


def test_convergence_verdicts_follow_the_rule(report):
    out, _, s = report
    q = s["quantities"]
    n_yes = n_no = 0
    for name in ("trajectory", "impact", "energy_lost_0p5s"):
        seqs = q[name]["sequences"]
        assert seqs
        for seq in seqs:
            assert len(seq["diffs"]) == len(seq["labels"]) - 1
            assert seq["converges"] == rule(seq["diffs"], seq["resolution"]), seq["name"]
            n_yes += seq["converges"]
            n_no += not seq["converges"]
        assert q[name]["converges"] == all(seq["converges"] for seq in seqs)
    # an error is reported for a quantity exactly when that quantity converges (the reference
    # row itself carries none)
    for key, name in (("err_trajectory", "trajectory"), ("err_impact", "impact")):
        reported = [row[key] is not None for row in s["errors"]]
        if q[name]["converges"]:
            assert sum(reported) == len(reported) - 1
        else:
            assert not any(reported)
    # the envelope max |corner| is never used as an error
    assert q["envelope_max_corner"]["converges"] is False
    # the markdown's convergence table prints the same verdicts
    md = (out / "performance.md").read_text()
    section = md.split("## Which quantities converge")[1].split("\n## ")[0]
    rows = [
        line
        for line in section.splitlines()
        if line.startswith("| ") and "sequence" not in line and "envelope" not in line and not line.startswith("|---")
    ]
    assert sum(line.rstrip().endswith("| yes |") for line in rows) == n_yes
    assert sum(line.rstrip().endswith("| **no** |") for line in rows) == n_no
