"""A communication step far shorter than the internal step dt, after the master set a new value
(OMSimulator's drifting clock ends a 1 s run with a step of 9.4e-14 s): the reconstruction of the
clamp (docs/theory.md §8) spreads the miss between where the input stands and the new value over
as far as the step's signal is read — the grid point ahead, up to dt away — not over the step
itself, whose slope miss/h read at dt would throw the clamp by miss·dt/h (it put the clamp at
-2.37 m, past the obstacle, and the FMU refused the step)."""

import math

from plate_fmu import PlateRun

H = 1e-4


def test_a_step_of_1e_13_s_continues_the_clamp_within_the_input(fmu_path):
    amplitude = 0.09
    with PlateRun(fmu_path, nx=6, ny=2) as run:
        t = 0.0
        for _ in range(200):
            run.step(H, base=amplitude * math.sin(2 * math.pi * 10 * t), derivatives=False)
            t += H
        run.step(9.4e-14, base=amplitude * math.sin(2 * math.pi * 10 * t), derivatives=False)
        t += 9.4e-14
        for _ in range(20):
            out = run.step(H, base=amplitude * math.sin(2 * math.pi * 10 * t), derivatives=False)
            t += H
            # The reconstruction stays with the values the master gave: within their amplitude,
            # up to the parabola's overshoot over one step (z''·H²/2 ≈ 0.09·(2π·10)²·1e-8/2 < 2e-7 m).
            assert abs(out["clamp_displacement"]) <= amplitude + 2e-7
            assert abs(out["clamp_displacement"] - amplitude * math.sin(2 * math.pi * 10 * t)) < 1e-3
