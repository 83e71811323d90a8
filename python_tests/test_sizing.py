"""python -m plateimpact.sizing (docs/theory.md §26): on a tiny scene (the quick ladder 7x3, 14x6,
28x12 and four candidates on a Dask cluster of one worker, seconds) the report's converged plate is
Richardson's extrapolation with the measured order, its choice is the cheapest candidate within the
accuracy (and none cheaper is), the front is the set no candidate beats in both error and CPU; bad
scenes and arguments are refused with what is allowed."""

import json
import math

import numpy as np
import pytest

from plateimpact import convergence as cv
from plateimpact import sizing


def test_richardson_recovers_a_known_order_and_limit():
    """u_h = u* + C h^p on a ladder h, h/2, h/4: the measured order is p and the plate is u*."""
    t = np.linspace(0, 1, 50)[:, None] * np.ones((1, 3))
    exact, c, p = np.sin(7 * t), np.cos(3 * t) + 2, 1.7
    rungs = [exact + c * h**p for h in (0.2, 0.1, 0.05)]
    plate = cv.converged_plate(*rungs)
    assert plate.converges and math.isclose(plate.order, p, rel_tol=1e-12)
    assert np.abs(plate.points - exact).max() < 1e-12
    # differences that do not shrink: no order, the verdict says so
    flat = cv.converged_plate(exact, exact + 0.01, exact)
    assert not flat.converges and "does not converge" in flat.verdict


def test_the_front_is_what_nothing_beats():
    points = [(1, 5), (2, 3), (3, 4), (4, 1), (0.5, 9)]
    assert sorted(cv.pareto(points)) == [0, 1, 3, 4]


def test_sizing_a_tiny_scene(fmu_path, tmp_path):
    scene = tmp_path / "release.json"
    scene.write_text(json.dumps({"parameters": {"initial_load": 8600, "obstacle_upper_enabled": False}}))
    out = tmp_path / "report.json"
    code = sizing.main(
        [
            str(scene),
            "--quick",
            "--until",
            "0.03",
            "--accuracy",
            "3e-3",
            "--workers",
            "1",
            "--fmu",
            str(fmu_path),
            "--json",
            str(out),
            "--no-progress",
        ]
    )
    report = json.loads(out.read_text())
    ref = report["reference"]
    assert ref["converges"] and 0.32 <= ref["order"] <= 4
    assert math.isclose(ref["order"], math.log2(ref["d1"] / ref["d2"]))
    rows = {r["name"]: r for r in report["candidates"]}
    assert len(rows) == 4 and all(r["error"] > 0 and r["cpu_per_second"] > 0 for r in rows.values())
    within = [r for r in rows.values() if r["error"] + ref["uncertainty"] <= 3e-3]
    assert code == (0 if within else 1)
    if within:
        assert report["choice"] == min(within, key=lambda r: r["cpu_per_second"])["name"]
    for name in report["front"]:  # nothing beats a front member in both
        f = rows[name]
        assert not any(r["error"] < f["error"] and r["cpu_per_second"] < f["cpu_per_second"] for r in rows.values())


@pytest.mark.parametrize(
    "scene, args, wanted",
    [
        ("{", [], "not JSON"),
        ('{"parameters": {"nx": 28}}', [], "set the discretization"),
        ('{"parameters": {"lenght": 1.0}}', [], "are not the FMU's"),
        ('{"drive": {"amplitude": NaN}}', [], "a finite number"),
        ('{"drive": {"phase": 1}}', [], "unknown keys"),
        ("{}", ["--accuracy", "0"], "--accuracy"),
        ("{}", ["--until", "100"], "--until"),
        (None, [], "no such file"),
    ],
)
def test_bad_scenes_are_refused_with_what_is_allowed(fmu_path, tmp_path, capsys, scene, args, wanted):
    path = tmp_path / "scene.json"
    if scene is not None:
        path.write_text(scene)
    assert sizing.main([str(path), "--fmu", str(fmu_path), *args]) == 2
    assert wanted in capsys.readouterr().err
