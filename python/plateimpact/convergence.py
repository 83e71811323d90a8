"""The error against the plate (docs/theory.md §26): a scene run through the FMU on several
configurations, the converged plate taken from a mesh ladder by Richardson extrapolation with the
*measured* order, and each configuration's error against it with its CPU per simulated second.

A scene is the FMU's parameters and a drive (a sine on base_displacement, given with its exact
derivatives, and a constant load), e.g. the paper's §5.2:

    {"parameters": {"initial_load": 8600, "obstacle_upper_enabled": false},
     "drive": {"amplitude": 0, "frequency": 10, "load": 0}}

A configuration is a dict of the FMU parameters that set the discretization (element, nx, ny,
modes, mass, time_scheme, dt, contact_substeps); the scene's parameters are the plate's.

The reported points are the three the FMU's error outputs cover: corner_1, corner_2 and
free_edge_mid. An error here is the largest distance of any of them from the converged plate over
the window, sampled at every communication point (SAMPLE s).
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .driver import PlateImpactFMU

REPORTED = ("corner_1", "corner_2", "free_edge_mid")
SAMPLE = 5e-4  # s: the communication step of every run, where the points are compared
DRIVE_KEYS = {"amplitude", "frequency", "load"}
# The parameters a configuration may set (the discretization); a scene sets the rest.
CONFIG_KEYS = {"element", "nx", "ny", "modes", "mass", "time_scheme", "dt", "contact_substeps", "beta"}
# The reference ladder (theory §26): the flow law (exact free flight) on the singular P0 mass at
# dt = 1e-5 s, its time error 1e-6-1e-5 m (docs/performance.md), far below the mesh's.
LADDER_LAW = {"time_scheme": "flow", "mass": "singular_p0", "dt": 1e-5}


class SceneError(ValueError):
    """A scene file that cannot be run, with what was wrong and what is allowed."""


@dataclass
class Scene:
    parameters: dict = field(default_factory=dict)
    amplitude: float = 0.0  # m, base_displacement = amplitude sin(2 pi frequency t)
    frequency: float = 10.0  # Hz
    load: float = 0.0  # Pa, constant from t = 0

    @staticmethod
    def from_dict(data, names=None) -> Scene:
        if not isinstance(data, dict):
            raise SceneError("a scene is a JSON object with 'parameters' and 'drive'")
        unknown = set(data) - {"parameters", "drive", "name"}
        if unknown:
            raise SceneError(f"unknown keys {sorted(unknown)}: a scene has 'parameters' and 'drive'")
        params = dict(data.get("parameters", {}))
        drive = dict(data.get("drive", {}))
        bad = set(drive) - DRIVE_KEYS
        if bad:
            raise SceneError(f"drive: unknown keys {sorted(bad)}; allowed {sorted(DRIVE_KEYS)}")
        for key, value in drive.items():
            if not isinstance(value, (int, float)) or not math.isfinite(value):
                raise SceneError(f"drive.{key} = {value!r}: a finite number (SI units: m, Hz, Pa)")
        if drive.get("frequency", 10.0) < 0:
            raise SceneError(f"drive.frequency = {drive['frequency']}: at least 0 Hz")
        if names is not None:
            unknown = set(params) - set(names)
            if unknown:
                raise SceneError(f"parameters {sorted(unknown)} are not the FMU's (its parameters: docs/variables.md)")
        owned = set(params) & CONFIG_KEYS - {"element"}
        if owned:
            raise SceneError(
                f"parameters {sorted(owned)} set the discretization, which the sizing chooses: leave them out"
            )
        return Scene(
            params,
            float(drive.get("amplitude", 0.0)),
            float(drive.get("frequency", 10.0)),
            float(drive.get("load", 0.0)),
        )

    @staticmethod
    def load_file(path, names=None) -> Scene:
        try:
            data = json.loads(Path(path).read_text())
        except FileNotFoundError:
            raise SceneError(f"{path}: no such file") from None
        except json.JSONDecodeError as e:
            raise SceneError(f"{path}: not JSON ({e})") from None
        return Scene.from_dict(data, names)

    def base(self, t):
        """base_displacement and its first two derivatives at t."""
        w = 2.0 * math.pi * self.frequency
        a = self.amplitude
        return (a * math.sin(w * t), a * w * math.cos(w * t), -a * w * w * math.sin(w * t))


@dataclass
class Run:
    config: dict
    points: np.ndarray  # (samples, 3): REPORTED at k SAMPLE, k = 1..n
    cpu_per_second: float  # process CPU of the stepping loop per simulated second
    setup_s: float  # wall time of instantiate + initialize
    estimate: np.ndarray | None = None  # discretization_error at each sample, when checked
    warned_at: float | None = None  # when the FMU said discretization_error became a bound


def communicate(plate, drives, n: int, step: float, refs):
    """n communication steps of `step` s from t = 0, each drive (input name, signal(t) -> value and its
    first two derivatives) set with its derivatives at the step's start; the values of `refs` after
    each step (n × len(refs)) and the process CPU time of the loop."""
    vrs = [plate.vars[name].valueReference for name, _ in drives]
    f = plate.fmu
    out = np.empty((n, len(refs)))
    cpu0 = time.process_time()
    for k in range(n):
        t = k * step
        values = [signal(t) for _, signal in drives]
        f.setReal(vrs, [v[0] for v in values])
        f.setRealInputDerivatives(
            [r for r in vrs for _ in (1, 2)], [1, 2] * len(vrs), [d for v in values for d in v[1:]]
        )
        f.doStep(currentCommunicationPoint=t, communicationStepSize=step)
        out[k] = f.getReal(refs)
    return out, time.process_time() - cpu0


def run(fmu, scene: Scene, config: dict, until: float, check=False) -> Run:
    """The scene on one configuration through the FMU, sampled every SAMPLE s up to `until`."""
    params = dict(scene.parameters, **config)
    if check:
        params["discretization_check"] = True
    t0 = time.perf_counter()
    n = round(until / SAMPLE)
    with PlateImpactFMU(fmu, base0=scene.base(0.0)[0], load0=scene.load, logger=lambda *a: None, **params) as plate:
        setup = time.perf_counter() - t0
        refs = [plate.vars[name].valueReference for name in REPORTED]
        if check:
            refs.append(plate.vars["discretization_error"].valueReference)
        values, cpu = communicate(plate, [("base_displacement", scene.base)], n, SAMPLE, refs)
        points, estimate = values[:, :3], (values[:, 3] if check else None)
        said = [m for s, _, m in plate.log if s == 1 and "discretization_error is a bound" in m]
    warned_at = float(said[0].split("from t = ")[1].split(" s")[0]) if said else None
    return Run(dict(config), points, cpu / until, setup, estimate, warned_at)


@dataclass
class Plate:
    """The converged plate of a scene: Richardson's extrapolation of a ladder h, h/2, h/4."""

    points: np.ndarray  # (samples, 3)
    order: float  # measured: log2(d1 / d2)
    d1: float  # max |u_h - u_h/2|
    d2: float  # max |u_h/2 - u_h/4|
    converges: bool
    uncertainty: float  # of the extrapolated plate: d2 / (2^p - 1), or d2 when it does not converge
    verdict: str

    def summary(self) -> dict:
        """What a report keeps of it: everything but the points."""
        return {k: getattr(self, k) for k in ("order", "d1", "d2", "converges", "uncertainty", "verdict")}


# Richardson's extrapolation is trusted only for a measured order in this range: below it the
# differences do not shrink enough to call the ladder converging (d2 > 0.8 d1), above it the
# rungs are too close for the difference to carry an order.
ORDER_RANGE = (0.32, 4.0)


def converged_plate(h: np.ndarray, h2: np.ndarray, h4: np.ndarray) -> Plate:
    """The ladder's extrapolation with the order measured on it (max norm over time and points)."""
    d1 = float(np.max(np.abs(h - h2)))
    d2 = float(np.max(np.abs(h2 - h4)))
    if d2 == 0.0 or d1 == 0.0:
        return Plate(h4, math.inf, d1, d2, True, 0.0, "the rungs agree to the last bit")
    p = math.log2(d1 / d2)
    if not ORDER_RANGE[0] <= p <= ORDER_RANGE[1]:
        return Plate(
            h4,
            p,
            d1,
            d2,
            False,
            max(d1, d2),
            f"does not converge: measured order {p:.2f} outside {ORDER_RANGE}; the finest rung is "
            f"the reference, uncertain by max(d1, d2)",
        )
    factor = 1.0 / (2.0**p - 1.0)
    return Plate(h4 + factor * (h4 - h2), p, d1, d2, True, factor * d2, f"converges, measured order {p:.2f} in h")


def error_curve(points: np.ndarray, plate: np.ndarray) -> np.ndarray:
    """The largest error of the reported points so far, at each sample."""
    n = min(len(points), len(plate))
    return np.maximum.accumulate(np.max(np.abs(points[:n] - plate[:n]), axis=1))


def ladder(base_config: dict, levels=3) -> list[dict]:
    """The mesh ladder h, h/2, h/4 from a configuration (nx, ny doubled at each rung)."""
    out = []
    for k in range(levels):
        c = dict(base_config)
        c["nx"], c["ny"] = base_config["nx"] * 2**k, base_config["ny"] * 2**k
        out.append(c)
    return out


def pareto(points):
    """Indices of the (cost, error) pairs no other pair beats in both."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def label(config: dict) -> str:
    """A configuration in a few words: 'argyris 28x10 m40 flow/singular_p0 dt1e-05'."""
    modes = config.get("modes", 0)
    law = config.get("time_scheme", "newmark")
    mass = config.get("mass", "consistent")
    sub = f" s{config['contact_substeps']}" if "contact_substeps" in config else ""
    return (
        f"{config.get('element', 'argyris')} {config['nx']}x{config['ny']} "
        f"{'complete' if not modes else f'm{modes}'} {law}/{mass} dt{config.get('dt', 1e-5):g}{sub}"
    )
