"""Stops through fmpy (docs/theory.md §25, issue 52): the parameters in the table of variables with
the whole plate as their default, the tip-stop scene as a master drives it, and the refusals."""

from __future__ import annotations

import re

import fmpy
import numpy as np
import predictability as pr
import pytest

from plateimpact import FMUError, PlateImpactFMU, default_base

STOP = dict(obstacle_lower=-0.05, obstacle_lower_x_min=1.0, obstacle_upper_enabled=False)
EDGES = [f"obstacle_{side}_{c}" for side in ("lower", "upper") for c in ("x_min", "x_max", "y_min", "y_max")]


def test_the_stops_are_parameters_whose_default_is_the_whole_plate(fmu_path):
    md = fmpy.read_model_description(str(fmu_path))
    variables = {v.name: v for v in md.modelVariables}
    for name in EDGES:
        v = variables[name]
        assert v.causality == "parameter" and v.type == "Real" and v.unit == "m"
        # The default rectangle reaches past the largest plate the ranges allow (length, width <= 1e4 m).
        assert float(v.start) == (1e4 if name.endswith("max") else 0.0), name
        assert float(v.min) == 0.0 and float(v.max) == 1e4


@pytest.mark.parametrize("law", [{}, {"time_scheme": "flow", "mass": "singular_p0"}])
def test_tip_stop_holds_the_corners_and_lets_the_middle_pass(fmu_path, law):
    """The corners (1.2, 0) and (1.2, 0.4) are contact points of the stop x >= 1.0: never below
    −0.05 m by more than roundoff (1e-12 m, as test_stops.cpp), while the probe at (0.6, 0.2), off
    the stop, passes below it (as the clamp does: the base reaches −0.09 m)."""
    lowest = {"corner_1": 1.0, "corner_2": 1.0, "probe_1": 1.0}
    with PlateImpactFMU(fmu_path, **STOP, **law, probe_count=1, probe_1_x=0.6, probe_1_y=0.2) as plate:
        for k in range(10000):  # 1 s: the tip lands on the stop from ≈ 0.03 s on
            out = plate.step(1e-4, base=default_base(k * 1e-4))
            for name in lowest:
                lowest[name] = min(lowest[name], out[name])
        assert out["contact_onsets_lower"] > 0 and out["contact_onsets_upper"] == 0
    assert lowest["corner_1"] >= -0.05 - 1e-12 and lowest["corner_2"] >= -0.05 - 1e-12, lowest
    assert lowest["probe_1"] < -0.05, lowest


@pytest.mark.parametrize(
    "bad, says",
    [
        (dict(obstacle_lower_x_min=1.1, obstacle_lower_x_max=1.0), "x_min <= x_max"),
        (dict(obstacle_upper_y_min=0.5), "meets the plate"),
        (dict(obstacle_lower_x_min=0.96, obstacle_lower_x_max=1.0), "nearest to this one is (0.942857142857143, 0)"),
        (dict(obstacle_lower_x_min=2e4), "every edge in [0, 1e4] m"),
    ],
)
def test_bad_stops_are_refused_with_the_allowed_range(fmu_path, bad, says):
    with pytest.raises(FMUError) as refused:
        with PlateImpactFMU(fmu_path, **bad):
            pass
    assert says in str(refused.value)


def test_tip_stop_converges_at_second_order_in_dt_through_its_landings(fmu_path):
    """The stop under the tip on 12×4 cells (predictability.SCENES["tip_stop"]: x = 1.0 m on a mesh
    line), flow law, over 0.1 s: the tip lands on the stop from 0.0165 s on. The flow law's error is
    made in the contact steps and falls at second order in the contact sub-step (docs/theory.md §21),
    so each halving of dt divides the difference of successive runs by about 4 (measured 0.24–0.25,
    docs/stop_convergence.json). The band [1/6, 1/3] is an order within [1.58, 2.58]: a first-order
    error (1/2), or none at all (runs that stop converging at the landings), fails. About 1 s CPU."""
    scene = pr.SCENES["tip_stop"]
    runs = [
        pr.simulate(fmu_path, scene, dict(scene.params, **pr.LAWS["flow"], dt=dt), 0.1, f"dt = {dt:g}")
        for dt in (1e-5, 5e-6, 2.5e-6, 1.25e-6)
    ]
    assert all(r.onsets[-1, 0] > 0 for r in runs)  # the window holds landings on the stop
    diffs = [np.max(np.abs(a.corner - b.corner)) for a, b in zip(runs, runs[1:])]
    for coarse, fine in zip(diffs, diffs[1:]):
        assert 1 / 6 <= fine / coarse <= 1 / 3, diffs


def test_a_refused_step_names_the_internal_step_it_could_not_take(fmu_path):
    """A base input past the lower obstacle (the clamp cannot leave the gap, docs/theory.md §25) is
    refused at the first internal step of the communication step, and the FMU's error names both
    times: the communication point and that internal step's end, one dt later (not the point twice)."""
    with PlateImpactFMU(fmu_path, nx=4, ny=2, dt=1e-5, obstacle_lower=-0.05) as plate:
        plate.step(1e-4)
        with pytest.raises(Exception):
            plate.step(1e-4, base=-0.06)
        said = " ".join(m for s, _, m in plate.log if s >= 3)
    found = re.search(r"step from t = (\S+) failed at t = (\S+?):", said)
    assert found, said
    start, failed = float(found.group(1)), float(found.group(2))
    assert start == pytest.approx(1e-4, rel=1e-12) and failed - start == pytest.approx(1e-5, rel=1e-9), said
