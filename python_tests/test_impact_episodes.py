"""Issue 53: impacts_lower / impacts_upper count impact episodes (docs/theory.md §14): a contact
with an obstacle after the whole plate was free of it for a quarter of its first natural period.
On the default scene they are what a person counts on corner_1's plot — a touch when corner_1
comes within 2 mm of an obstacle, counted again only after it crossed the middle — while the
contact onsets (every vertex's chatter) are many times more."""

import math

import fmpy
import numpy as np
import pytest

from plateimpact.driver import unzipped

STOP, STEP = 0.6, 1e-4
NEAR = 0.098  # m: within 2 mm of an obstacle at 0.1 m


@pytest.fixture(scope="module")
def default_scene(fmu_path):
    t = np.arange(round(STOP / STEP) + 1) * STEP
    base = np.array(
        list(zip(t, 0.09 * np.sin(2 * math.pi * 10 * t))), dtype=[("time", float), ("base_displacement", float)]
    )
    outputs = ["corner_1", "impacts_lower", "impacts_upper", "contact_onsets_lower", "contact_onsets_upper"]
    unzipdir, md = unzipped(fmu_path)  # extracted once per process, its library kept loaded
    return fmpy.simulate_fmu(
        unzipdir, model_description=md, stop_time=STOP, output_interval=STEP, input=base, output=outputs
    )


def plot_touches(t, corner, sign):
    """The times a person marks on the plot: corner_1 at the obstacle, once per swing."""
    touches, armed = [], True
    for ti, x in zip(t, sign * corner):
        if armed and x >= NEAR:
            touches.append(ti)
            armed = False
        if x < 0:
            armed = True
    return touches


@pytest.mark.parametrize("obstacle, sign", [("lower", -1.0), ("upper", 1.0)])
def test_impacts_are_the_episodes_a_person_counts_on_the_corners_plot(default_scene, obstacle, sign):
    r = default_scene
    touches = plot_touches(r["time"], r["corner_1"], sign)
    episodes = r[f"impacts_{obstacle}"]
    starts = r["time"][1:][np.diff(episodes) > 0]
    assert len(touches) >= 5  # 10 Hz drive over 0.6 s: about one per period and obstacle
    assert episodes[-1] == len(touches) == len(starts)
    # each episode starts where the plot shows the touch: within 5 ms (the corner is not always the
    # first point of the plate to arrive)
    assert np.max(np.abs(starts - np.array(touches))) <= 5e-3, (starts, touches)
    # the onsets count every vertex's chatter: many per episode
    assert r[f"contact_onsets_{obstacle}"][-1] >= 5 * episodes[-1]
