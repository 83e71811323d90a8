"""The predictability horizon (docs/performance.md, "The predictability horizon"; tools/predictability.py):
two runs of the default scene whose base amplitudes differ at roundoff level agree to roundoff
through free flight and the first impacts, and part exponentially later — the signature of
sensitive dependence, not of a slow scheme. One core, about 2 s."""

import numpy as np
import predictability as pr

SCENE = pr.SCENES["default"]
FLOW = dict(pr.LAWS["flow"], dt=1e-5)
STOP = 0.7  # s; the twins part by 1e-4 m at 0.48 s (docs/predictability.json)


def test_roundoff_twins_agree_through_free_flight_and_part_later(fmu_path):
    run = pr.simulate(fmu_path, SCENE, FLOW, STOP, "run")
    twin = pr.simulate(fmu_path, SCENE, FLOW, STOP, "twin", amplitude_factor=1 + 1e-14)
    again = pr.simulate(fmu_path, SCENE, FLOW, 0.1, "again")
    # Deterministic: the same inputs give the same bits (else "differ at roundoff" means nothing).
    assert np.array_equal(again.corner, run.corner[: len(again.corner)])
    sep = np.abs(run.corner - twin.corner)
    # Before the first impact (0.0495 s; 0.045 s is scenes.FIRST_IMPACT["paper"]) the flow scheme's
    # free flight is the exact linear modal flow: a change of 1e-14 of the amplitude moves corner_1
    # by about 1e-14 x 0.1 m = 1e-15 m; 1e-12 m leaves a factor 1000 for roundoff. A scheme that
    # amplified in free flight, or a perturbation that did not stay small, fails here.
    free = run.t <= 0.045
    assert sep[free].max() <= 1e-12, sep[free].max()
    assert sep[free].max() > 0  # the perturbation reached the plate
    # Through the first impacts (to 0.1 s) it stays at roundoff x growth.
    assert sep[run.t <= 0.1].max() <= 1e-11, sep[run.t <= 0.1].max()
    # ... and later the twins part: by more than 1e-4 m before 0.7 s (measured at 0.48 s, the
    # separation growing like exp(56 t): a 45 % margin on the time is a factor 2e5 on the separation).
    t_star = pr.first_exceedance(run.t, sep, 1e-4)
    assert t_star is not None and t_star < STOP, sep.max()
    # Exponential, not a drift: the first times of each decade 1e-12 ... 1e-5 m lie on a line
    # ln(eps) = a + lambda t with every local slope within a factor 2 of lambda.
    g = pr.growth(run.t, sep)
    assert g["clean"] and g["rate"] > 10.0, g
