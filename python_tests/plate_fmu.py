"""Drive PlateImpact.fmu the way a co-simulation master does (fmpy's FMU2Slave), for the tests.

    with PlateRun(fmu_path, nx=6, ny=2, initial_load=1000.0) as run:
        out0 = run.outputs()                       # the static state at t = 0
        out = run.step(1e-3, base=(z, zdot, zddot), load=(p, pdot))

Parameters are given by their modelDescription names; inputs as a value or a tuple
(value, first derivative, second derivative) at the start of the step — inside the step the FMU
follows value + d1 s + d2 s²/2. Derivatives not given are set to 0 at every step, so nothing
stale is ever left in the FMU. Outputs come back as a dict keyed by output name.
"""
import sys
from pathlib import Path

# The tests drive the FMU with the same driver the examples give users.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "examples"))
from plateimpact import PlateImpactFMU  # noqa: E402

# name: (value reference, FMI type)
PARAMETERS = {
    "length": (0, "Real"),
    "width": (1, "Real"),
    "thickness": (2, "Real"),
    "youngs_modulus": (3, "Real"),
    "poisson_ratio": (4, "Real"),
    "density": (5, "Real"),
    "nx": (6, "Integer"),
    "ny": (7, "Integer"),
    "element": (8, "Integer"),  # Enumeration: argyris = 1, fvs = 2
    "obstacle_lower": (9, "Real"),
    "obstacle_upper": (10, "Real"),
    "obstacle_lower_enabled": (11, "Boolean"),
    "obstacle_upper_enabled": (12, "Boolean"),
    "dt": (13, "Real"),
    "beta": (14, "Real"),
    "initial_load": (15, "Real"),
    "modes": (16, "Integer"),
    "base_input_mode": (17, "Integer"),  # Enumeration InputMode: hold = 1, linear = 2, quadratic = 3
    "load_input_mode": (18, "Integer"),
}
ELEMENTS = {"argyris": 1, "fvs": 2}
VR_BASE, VR_LOAD = 20, 21
REAL_OUTPUTS = {
    "corner_1": 30,
    "corner_2": 31,
    "free_edge_mid": 32,
    "energy": 33,
    "energy_dissipated": 34,
    "energy_input": 35,
    "qp_kkt_residual_max": 37,
}
INTEGER_OUTPUTS = {"contact_vertices": 36, "qp_iterations_total": 38, "qp_iterations_max": 39}



class PlateRun(PlateImpactFMU):
    """One FMU instance from instantiation to initialization; a context manager. Unlike the
    examples' driver, step() sets both inputs every time (0 when not given), so nothing stale
    is ever left in the FMU."""

    def __init__(self, fmu_path, base0=0.0, load0=0.0, **parameters):
        unknown = set(parameters) - set(PARAMETERS)
        if unknown:
            raise KeyError(f"unknown parameter(s) {sorted(unknown)}")
        super().__init__(fmu_path, base0=base0, load0=load0, **parameters)
        self.steps = 0  # communication steps taken

    def step(self, h, base=0.0, load=0.0, derivatives=True):
        """One fmi2DoStep of size h from self.time with the given input signals; the outputs."""
        out = super().step(h, base=base, load=load, derivatives=derivatives)
        self.steps += 1
        return out
