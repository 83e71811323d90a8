"""Drive PlateImpact.fmu the way a co-simulation master does (fmpy's FMU2Slave), for the tests.

    with PlateRun(fmu_path, nx=6, ny=2, initial_load=1000.0) as run:
        out0 = run.outputs()                       # the static state at t = 0
        out = run.step(1e-3, base=(z, zdot, zddot), load=(p, pdot))

Parameters are given by their modelDescription names; inputs as a value or a tuple
(value, first derivative, second derivative) at the start of the step — inside the step the FMU
follows value + d1 s + d2 s²/2. Derivatives not given are set to 0 at every step, so nothing
stale is ever left in the FMU. Outputs come back as a dict keyed by output name.
"""
import atexit
import shutil
from pathlib import Path

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

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

_extracted = {}  # (resolved path, mtime) -> (unzip directory, model description)


def _unzipped(fmu_path):
    path = Path(fmu_path).resolve()
    if not path.is_file():
        raise FileNotFoundError(f"FMU not found: {path} (build it, or set PLATEIMPACT_FMU)")
    key = (str(path), path.stat().st_mtime_ns)
    if key not in _extracted:
        unzipdir = extract(str(path))
        atexit.register(shutil.rmtree, unzipdir, ignore_errors=True)
        _extracted[key] = (unzipdir, read_model_description(str(path)))
    return _extracted[key]


def _signal(x):
    """A value or (value[, d1[, d2]]) -> (value, d1, d2)."""
    if isinstance(x, (tuple, list)):
        x = tuple(float(v) for v in x) + (0.0,) * (3 - len(x))
        return x[:3]
    return (float(x), 0.0, 0.0)


class PlateRun:
    """One FMU instance from instantiation to initialization; a context manager."""

    def __init__(self, fmu_path, base0=0.0, load0=0.0, **parameters):
        unknown = set(parameters) - set(PARAMETERS)
        if unknown:
            raise KeyError(f"unknown parameter(s) {sorted(unknown)}")
        self.fmu_path = fmu_path
        self.parameters = dict(parameters)
        if isinstance(self.parameters.get("element"), str):
            self.parameters["element"] = ELEMENTS[self.parameters["element"]]
        self.base0, self.load0 = float(base0), float(load0)
        self.time = 0.0
        self.steps = 0  # communication steps taken
        self._fmu = None
        self._initialized = False

    def __enter__(self):
        unzipdir, md = _unzipped(self.fmu_path)
        fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                        modelIdentifier=md.coSimulation.modelIdentifier, instanceName="plate")
        fmu.instantiate(loggingOn=False)
        self._fmu = fmu
        try:
            fmu.setupExperiment(startTime=0.0)
            fmu.enterInitializationMode()
            for name, value in self.parameters.items():
                vr, kind = PARAMETERS[name]
                if kind == "Real":
                    fmu.setReal([vr], [float(value)])
                elif kind == "Integer":
                    fmu.setInteger([vr], [int(value)])
                else:
                    fmu.setBoolean([vr], [bool(value)])
            fmu.setReal([VR_BASE, VR_LOAD], [self.base0, self.load0])
            fmu.exitInitializationMode()
            self._initialized = True
        except BaseException:
            self._free()
            raise
        return self

    def __exit__(self, *exc):
        self._free()
        return False

    def _free(self):
        if self._fmu is not None:
            if self._initialized:
                try:
                    self._fmu.terminate()
                except Exception:
                    pass  # after a failed step: fmi2FreeInstance is still allowed
            self._fmu.freeInstance()
            self._fmu = None

    def step(self, h, base=0.0, load=0.0):
        """One fmi2DoStep of size h from self.time with the given input signals; the outputs."""
        b, p = _signal(base), _signal(load)
        fmu = self._fmu
        fmu.setReal([VR_BASE, VR_LOAD], [b[0], p[0]])
        fmu.setRealInputDerivatives([VR_BASE, VR_LOAD, VR_BASE, VR_LOAD], [1, 1, 2, 2],
                                    [b[1], p[1], b[2], p[2]])
        fmu.doStep(currentCommunicationPoint=self.time, communicationStepSize=h)
        self.steps += 1
        self.time += h  # the FMU accepts the rounding of this sum (relative time tolerance)
        return self.outputs()

    def outputs(self):
        names, vrs = zip(*REAL_OUTPUTS.items())
        out = dict(zip(names, self._fmu.getReal(list(vrs))))
        names, vrs = zip(*INTEGER_OUTPUTS.items())
        out.update(zip(names, self._fmu.getInteger(list(vrs))))
        out["time"] = self.time
        return out
