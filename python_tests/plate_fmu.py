"""PlateRun: the package's FMU driver as the tests use it (fmpy's FMU2Slave underneath).

    with PlateRun(fmu_path, nx=6, ny=2, initial_load=1000.0) as run:
        out0 = run.outputs()                       # the static state at t = 0
        out = run.step(1e-3, base=(z, zdot, zddot), load=(p, pdot))

Parameters are given by their modelDescription names (an unknown name is a KeyError); inputs
as a value or a tuple (value, first derivative, second derivative) at the start of the step —
inside the step the FMU follows value + d1 s + d2 s²/2. Unlike the bare driver, step() sets both
inputs every time, with derivatives (0 when not given) unless derivatives=False, so nothing
stale is ever left in the FMU. Outputs come back as a dict keyed by output name.
"""

from plateimpact import PlateImpactFMU


class PlateRun(PlateImpactFMU):
    """One FMU instance from instantiation to initialization; a context manager."""

    def __init__(self, fmu_path, base0=0.0, load0=0.0, **parameters):
        super().__init__(fmu_path, base0=base0, load0=load0, **parameters)
        self.steps = 0  # communication steps taken

    def step(self, h, base=0.0, load=0.0, derivatives=True):
        """One fmi2DoStep of size h from self.time with the given input signals; the outputs."""
        out = super().step(h, base=base, load=load, derivatives=derivatives)
        self.steps += 1
        return out
