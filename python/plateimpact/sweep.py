"""The sine-sweep controller as a Python object, and the master loop that drives the FMU with
it through input derivatives (examples/sine_sweep.py is its command line).

    z(t) = A sin φ(t),  φ(t) = 2π ∫₀ᵗ f(s) ds
    linear:      f(t) = f0 + (f1 − f0) t/T,   φ = 2π (f0 t + (f1 − f0) t²/(2T))
    logarithmic: f(t) = f0 (f1/f0)^(t/T),     φ = 2π f0 T (e^{kt} − 1)/ln(f1/f0),  k = ln(f1/f0)/T

After t = T the frequency stays at f1 (docs/theory.md §9; SineSweep.fmu computes the same).
"""

from __future__ import annotations

import math

from .driver import PlateImpactFMU

CSV_COLUMNS = (
    "time",
    "frequency",
    "base",
    "corner_1",
    "corner_2",
    "free_edge_mid",
    "energy",
    "energy_dissipated",
    "energy_input",
    "energy_damped",
    "contact_vertices",
)


def rayleigh_for_band(zeta, f_low, f_high):
    """Rayleigh coefficients (a, b) of C = a M + b K with damping ratio zeta at f_low and at
    f_high (docs/theory.md §13: zeta(w) = a/(2w) + b w/2; between the two it is a little below
    zeta, outside it grows)."""
    w1, w2 = 2 * math.pi * f_low, 2 * math.pi * f_high
    return 2 * zeta * w1 * w2 / (w1 + w2), 2 * zeta / (w1 + w2)


class SineSweep:
    """A linear or logarithmic sine sweep z(t) = A sin φ(t) with φ' = 2π f(t).

    The controller is stateless and exact: every quantity is a closed-form function of t, so
    the signal handed to the FMU at any communication point is the one a direct evaluation
    gives, whatever the step size."""

    def __init__(self, amplitude, f_start, f_end, duration, law="linear"):
        if law not in ("linear", "log"):
            raise ValueError("law must be 'linear' or 'log'")
        if duration <= 0 or f_start <= 0 or f_end <= 0:
            raise ValueError("duration and frequencies must be positive")
        self.amplitude = float(amplitude)
        self.f0, self.f1, self.T = float(f_start), float(f_end), float(duration)
        self.law = law
        self._ln = math.log(self.f1 / self.f0)  # log law: k = ln(f1/f0)/T

    # -- the law ------------------------------------------------------------------------------
    def frequency(self, t):
        """Instantaneous frequency f(t) in Hz (f1 after the end of the sweep)."""
        s = min(max(t, 0.0), self.T)
        if self.law == "linear" or self._ln == 0.0:
            return self.f0 + (self.f1 - self.f0) * s / self.T
        return self.f0 * math.exp(self._ln * s / self.T)

    def phase(self, t):
        """φ(t), φ'(t) = 2π f(t), φ''(t) = 2π f'(t): phase in rad and its two derivatives."""
        two_pi = 2.0 * math.pi
        s = min(max(t, 0.0), self.T)
        if self.law == "linear" or self._ln == 0.0:
            slope = (self.f1 - self.f0) / self.T
            phi = two_pi * (self.f0 * s + 0.5 * slope * s * s)
            d2 = two_pi * slope
        else:
            k = self._ln / self.T
            phi = two_pi * self.f0 * math.expm1(k * s) / k
            d2 = two_pi * self.f0 * k * math.exp(k * s)
        if t > self.T:  # hold f1: phase grows linearly, no chirp any more
            return phi + two_pi * self.f1 * (t - self.T), two_pi * self.f1, 0.0
        return phi, two_pi * self.frequency(t), d2

    def __call__(self, t):
        """The base signal at t: (z, ż, z̈) — value and the two derivatives the FMU takes."""
        phi, d1, d2 = self.phase(t)
        s, c = math.sin(phi), math.cos(phi)
        a = self.amplitude
        return a * s, a * c * d1, a * (c * d2 - s * d1 * d1)


def run_sweep(fmu, sweep, stop_time, comm_step, progress=None, **parameters):
    """Drive the FMU with the controller for stop_time; returns a list of CSV rows (dicts).

    The master loop: at each communication point t_k the controller is asked for
    (z, ż, z̈)(t_k), the FMU is advanced by comm_step with those inputs, and the outputs at
    t_{k+1} are recorded beside the controller's base value and frequency at t_{k+1}."""
    n = round(stop_time / comm_step)
    if abs(n * comm_step - stop_time) > 1e-9 * stop_time:
        raise ValueError("stop_time must be a whole number of communication steps")
    rows = []

    def record(t, plate):
        o = plate.outputs()
        rows.append(
            {"time": t, "frequency": sweep.frequency(t), "base": sweep(t)[0], **{k: o[k] for k in CSV_COLUMNS[3:]}}
        )

    with PlateImpactFMU(fmu, **parameters) as plate:
        record(0.0, plate)
        for k in range(n):
            plate.step(comm_step, base=sweep(k * comm_step))
            record((k + 1) * comm_step, plate)
            if progress is not None:
                progress.update(1)
    return rows
