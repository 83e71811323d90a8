"""The scenes, written once: the default scene's base (the paper's §5.1 forced oscillation,
0.09 sin(2 pi 10 t) m on the default plate: 14x5 Argyris, obstacles at +-0.1 m), the scenes of
the accuracy reports (docs/input-accuracy.md, docs/system-model.md) at dt = 1e-5 s, and the
reference they are measured against: the run whose base is exact at every internal step.

  smooth  base 0.09 sin(2 pi 10 t) s(t), s = sin^2(pi t / 0.1) for t < 0.05 s, 1 after
          (z, z', z'' all start at 0: a causal master loses nothing at the start)
  paper   base 0.09 sin(2 pi 10 t) from t = 0 (a kink out of rest: c w = 5.7 m/s at t = 0+)
"""

from __future__ import annotations

import math

import numpy as np

from .driver import PlateImpactFMU

DT = 1e-5
AMPLITUDE, FREQUENCY = 0.09, 10.0  # the default scene's base, m and Hz
RAMP = 0.05  # s, the smooth scene's ramp-in
FIRST_IMPACT = {"smooth": 0.06, "paper": 0.045}  # horizons before the first impact, s


def sine(amplitude, frequency, t):
    """Value and first two derivatives of amplitude·sin(2πf t)."""
    w = 2.0 * math.pi * frequency
    return (amplitude * math.sin(w * t), amplitude * w * math.cos(w * t), -amplitude * w * w * math.sin(w * t))


def default_base(t):
    """The default scene's base at t: 0.09 sin(2π·10 t) m and its first two derivatives."""
    return sine(AMPLITUDE, FREQUENCY, t)


def base(scene, t):
    """Value, first and second derivative of the scene's base displacement at t."""
    z, zd, zdd = default_base(t)
    if scene == "paper" or t >= RAMP:
        return z, zd, zdd
    a = math.pi / (2 * RAMP)
    s, sd, sdd = math.sin(a * t) ** 2, a * math.sin(2 * a * t), 2 * a * a * math.cos(2 * a * t)
    return z * s, zd * s + z * sd, zdd * s + 2 * zd * sd + z * sdd


def run_derivatives(fmu, scene, h, stop):
    n = round(stop / h)
    out = np.empty(n)
    with PlateImpactFMU(fmu, dt=DT) as plate:
        for k in range(n):
            out[k] = plate.step(h, base=base(scene, k * h))["corner_1"]
    return out


def errors(run, ref, h, scene):
    """max |run - ref| before the first impact and over the whole run, at the points k h."""
    stride = round(h / DT)
    sampled = ref[stride - 1 :: stride][: len(run)]
    diff = np.abs(run - sampled)
    before = round(FIRST_IMPACT[scene] / h)
    return float(diff[:before].max()), float(diff.max())
