"""The two C1 elements agree on the default scene (the paper's §5.1 claim: "no significant
qualitative difference between the FVS and the Argyris approaches").

Both run the sine-base scene (0.09 sin(2π·10 t), obstacles ±0.1 m, dt = 1e-5) through the FMU.
Argyris on the default 14×5 grid (734 dofs); FVS on 28×10 (924 dofs: matched dofs). Measured
(plate_bench, identical scheme): the first impact at 0.0495–0.0496 s for both, the corner
trajectories before it within 0.6–0.8 % of the amplitude. On coarser FVS grids the gap is the
FVS discretization error, which shrinks with h: 2.1 % (14×5), 1.3 % (20×7), 0.63 % (28×10),
0.42 % (40×14) — so 1 % is met at matched dofs, not at matched cell count; the test also checks
that the gap shrinks under refinement, which is what makes the agreement a convergence fact.
"""

import numpy as np
import pytest
from plate_fmu import PlateRun

from plateimpact.scenes import default_base

H = 1e-4  # communication step
T_END = 0.06  # past the first impact (~0.0496 s)


def run(fmu_path, element, nx, ny):
    rows = []
    with PlateRun(fmu_path, element=element, nx=nx, ny=ny, dt=1e-5) as plate:
        for k in range(round(T_END / H)):
            out = plate.step(H, base=default_base(k * H))
            rows.append(((k + 1) * H, out["corner_1"], out["corner_2"], out["contact_vertices"]))
    return np.array(rows)


def first_impact(r):
    hit = np.nonzero(r[:, 3] > 0)[0]
    assert hit.size, "no impact in the horizon"
    return hit[0]


@pytest.fixture(scope="module")
def argyris(fmu_path):
    return run(fmu_path, "argyris", 14, 5)


def gap_before_first_impact(a, f):
    n = min(first_impact(a), first_impact(f))
    amplitude = np.max(np.abs(a[:n, 1:3]))
    return np.max(np.abs(a[:n, 1:3] - f[:n, 1:3])) / amplitude


def test_fvs_and_argyris_agree_before_and_at_the_first_impact(fmu_path, argyris):
    fvs = run(fmu_path, "fvs", 28, 10)
    # 1 % of the amplitude before the first impact (measured 0.6–0.8 %).
    assert gap_before_first_impact(argyris, fvs) <= 0.01
    # Time of the first impact to 1 % (measured 0–0.2 %; resolution: one communication step,
    # 1e-4 s = 0.2 % of 0.0496 s).
    ta, tf = argyris[first_impact(argyris), 0], fvs[first_impact(fvs), 0]
    assert abs(ta - tf) <= 0.01 * ta


def test_the_element_gap_shrinks_under_fvs_refinement(fmu_path, argyris):
    coarse = gap_before_first_impact(argyris, run(fmu_path, "fvs", 14, 5))
    fine = gap_before_first_impact(argyris, run(fmu_path, "fvs", 28, 10))
    # Halving h must cut the gap clearly (measured 2.1 % → 0.63 %, a factor 3.3; the FVS
    # displacement error converges at about O(h^1.5–2) on this clamped–free plate).
    assert fine < 0.5 * coarse
