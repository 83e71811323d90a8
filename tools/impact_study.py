"""Convergence after impact, per impact law (docs/impact-laws.md): the §5.2 scene run through
the FMU under time-step and mesh refinement, and what converges.

The scene (the paper's §5.2): the default plate released at t = 0 from its static shape under
8600 Pa (load 0 from t = 0), lower obstacle at -0.1 m only, no base motion; the plate swings
down and hits the obstacle again and again. Measured per run, with every internal step read
(h = dt):

  - the energy at 0.5 s as a share of E0 lost (E0 - E(0.5)) / E0 (energy_damped excluded:
    without damping it is 0);
  - the first three impact times: starts of contact (contact_vertices going from 0 to > 0)
    after at least 10 ms without any (an impact is a burst of short contacts; §5.2 has one
    near 0.068, 0.224 and 0.40 s);
  - corner_1 on a common grid of 2e-4 s over the first 0.3 s, for the successive differences
    max |corner_1(dt) - corner_1(dt/2)|.

Laws (FMU parameters beyond the scene): the paper's scheme (consistent mass, e = 0),
singular_p0, singular_p1dg, and the consistent mass with restitution 0.5.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from plateimpact.driver import PlateImpactFMU

SCENE = {"initial_load": 8600.0, "obstacle_upper_enabled": False}
LAWS = {
    "paper (consistent, e = 0)": {},
    "singular_p0": {"mass": 2},
    "singular_p1dg": {"mass": 3},
    "consistent, e = 0.5": {"restitution": 0.5},
}
DTS = (4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6)
STOP = 0.5  # s, energy horizon
CORNER_HORIZON = 0.3  # s, corner_1 comparison window
GRID = 2e-4  # s, common sample spacing of corner_1 (a multiple of every dt)
QUIET = 0.01  # s without contact before a contact counts as a new impact


@dataclass
class Run:
    law: str
    dt: float
    nx: int
    ny: int
    e0: float = math.nan
    energy: float = math.nan  # at STOP
    lost: float = math.nan  # (E0 - E(STOP)) / E0
    ledger: float = math.nan  # |E - (E0 + in - diss - damped)| / E0 at STOP
    impacts: list = field(default_factory=list)  # first three contact onsets, s
    corner: np.ndarray = None  # corner_1 at k * GRID, k = 1..CORNER_HORIZON/GRID
    wall: float = 0.0  # s
    steps: int = 0


def run(fmu, law, dt, nx=14, ny=5, stop=STOP, extra=None):
    params = dict(SCENE, dt=dt, nx=nx, ny=ny, **LAWS.get(law, {}), **(extra or {}))
    r = Run(law=law, dt=dt, nx=nx, ny=ny)
    t0 = time.perf_counter()
    with PlateImpactFMU(fmu, **params) as plate:
        vr = {n: plate.vars[n].valueReference for n in ("corner_1", "contact_vertices")}
        r.e0 = plate.outputs()["energy"]
        n = round(stop / dt)
        per_grid = round(GRID / dt)
        n_corner = round(CORNER_HORIZON / GRID)
        corner = []
        last_contact = -math.inf
        for k in range(1, n + 1):
            plate.fmu.doStep(currentCommunicationPoint=(k - 1) * dt, communicationStepSize=dt)
            if plate.fmu.getInteger([vr["contact_vertices"]])[0] > 0:
                if k * dt - last_contact > QUIET and len(r.impacts) < 3:
                    r.impacts.append(k * dt)
                last_contact = k * dt
            if k % per_grid == 0 and len(corner) < n_corner:
                corner.append(plate.fmu.getReal([vr["corner_1"]])[0])
        plate.time = n * dt
        out = plate.outputs()
    r.wall = time.perf_counter() - t0
    r.steps = n
    r.energy = out["energy"]
    r.lost = (r.e0 - r.energy) / r.e0
    r.ledger = (
        abs(out["energy"] - (r.e0 + out["energy_input"] - out["energy_dissipated"] - out["energy_damped"])) / r.e0
    )
    r.corner = np.array(corner)
    return r


def successive(values):
    """Successive differences |v_k - v_{k+1}| and their ratios d_{k+1}/d_k."""
    d = [abs(a - b) for a, b in zip(values, values[1:])]
    ratios = [b / a if a > 0 else math.nan for a, b in zip(d, d[1:])]
    return d, ratios


def corner_differences(runs):
    """max |corner_1(dt_k) - corner_1(dt_{k+1})| over the common grid, and ratios."""
    d = [float(np.max(np.abs(a.corner - b.corner))) for a, b in zip(runs, runs[1:])]
    ratios = [b / a if a > 0 else math.nan for a, b in zip(d, d[1:])]
    return d, ratios


def verdict(ratios, tolerance=0.6):
    """'converges' when the last two successive-difference ratios are <= tolerance (observed
    order >= log2(1/tolerance) = 0.74 under halving), 'does not converge' when the last ratio
    is >= 0.9, 'unclear' otherwise."""
    tail = [r for r in ratios[-2:] if not math.isnan(r)]
    if tail and all(r <= tolerance for r in tail):
        return "converges"
    if tail and tail[-1] >= 0.9:
        return "does not converge"
    return "unclear"


def observed_order(ratio):
    return -math.log2(ratio) if ratio and ratio > 0 and not math.isnan(ratio) else math.nan
