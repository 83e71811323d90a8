"""A thin driver for PlateImpact.fmu on top of fmpy's FMU2Slave — the one the examples and
the tests use. Variable names, types and value references come from the FMU's model
description.

Users copy this: it shows how to set the parameters by name, feed inputs *with* their time
derivatives (fmpy's simulate_fmu cannot: its input-derivative path crashes, docs/theory.md) and
read the outputs every communication step.

    with PlateImpactFMU("build/PlateImpact.fmu", nx=14, ny=5, dt=1e-5) as plate:
        out = plate.step(1e-4, base=(z, zdot, zddot))
        print(out["corner_1"])

The FMU's log messages (status, category, message) are kept in `plate.log`; pass
`logger=callable(status, category, message)` to see them as they come. A call the FMU refuses
raises `FMUError` (an fmpy FMICallException) whose text carries the FMU's own error messages: what
was wrong and what is allowed.
"""

from __future__ import annotations

import atexit
import functools
import re
import shutil

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)

from .fmufile import fmu_file


class FMUError(FMICallException):
    """An FMI call the FMU refused, with the error messages it logged for it (the value, the
    variable and the allowed range): fmpy's own exception says only "failed with status 3"."""

    def __init__(self, error: FMICallException, messages):
        super().__init__(error.function, error.status)
        self.messages = list(messages)
        if self.messages:
            self.args = (f"{self.args[0]} The FMU says: " + " | ".join(self.messages),)


def _explained(method):
    """Runs a method of PlateImpactFMU; a refused call raises FMUError with what the FMU logged."""

    @functools.wraps(method)
    def run(self, *args, **kwargs):
        before = len(self.log)
        try:
            return method(self, *args, **kwargs)
        except FMUError:
            raise
        except FMICallException as e:
            raise FMUError(e, [m for s, _, m in self.log[before:] if s >= 3]) from e

    return run


# The outputs that read 0 unless the parameter stress_outputs is true.
STRESS_OUTPUTS = ("root_stress", "root_stress_peak", "max_stress", "max_stress_x", "max_stress_y")
ITEMS = re.compile(r"\((\d+ = \w+(?:, \d+ = \w+)*)\)$")


def switch_items(v) -> dict[str, int]:
    """The named items of an Integer switch (element, base_drive, ...), from the end of its
    description, where the build lists them: "... (1 = argyris, 2 = fvs)" -> {"argyris": 1,
    "fvs": 2}. Empty for any other variable."""
    match = ITEMS.search(v.description or "") if v.type in ("Integer", "Int32") else None
    if not match:
        return {}
    return {name: int(value) for value, name in (item.split(" = ") for item in match.group(1).split(", "))}


_extracted = {}  # (resolved path, mtime) -> (unzip directory, model description)


def unzipped(fmu_path):
    """(unzip directory, model description) of an FMU file, extracted once per process (and file
    version) and removed at exit, or of a directory holding an extracted FMU.

    fmpy unloads the library when an instance is freed; the FMU's cache of discretizations
    (instances of the same plate share its modal basis: README, "Performance") outlives it all the
    same: the first copy of the library loaded in a process stays loaded and serves every later one
    (fmu/core/PrimaryCopy.h)."""
    path = fmu_file(fmu_path)
    key = (str(path), path.stat().st_mtime_ns)
    if key not in _extracted:
        unzip_dir = str(path) if path.is_dir() else _extract(path)
        _extracted[key] = (unzip_dir, read_model_description(str(path)))
    return _extracted[key]


def _extract(path):
    unzip_dir = extract(str(path))
    atexit.register(shutil.rmtree, unzip_dir, ignore_errors=True)
    return unzip_dir


def signal(x):
    """An input given as a value or (value[, d1[, d2]]) -> (value, d1, d2)."""
    if isinstance(x, (tuple, list)):
        x = tuple(float(v) for v in x) + (0.0,) * (3 - len(x))
        return x[:3]
    return (float(x), 0.0, 0.0)


class PlateImpactFMU:
    """One PlateImpact instance: instantiate(), initialize(parameters), then step() and
    outputs(). The constructor does both first steps unless `initialize=False` (or
    `instantiate=False`: then not even the first). `fmu_path` is the .fmu file or a directory
    holding it extracted; `guid` replaces the model description's (an importer's mistake, for
    the tests of the FMU's checks)."""

    def __init__(
        self,
        fmu_path,
        start_time=0.0,
        instance_name="plate",
        logger=None,
        base0=0.0,
        load0=0.0,
        initialize=True,
        instantiate=True,
        guid=None,
        **parameters,
    ):
        self.unzip_dir, self.md = unzipped(fmu_path)
        self.vars = {v.name: v for v in self.md.modelVariables}
        self.log = []
        self._user_logger = logger
        # The ctypes objects must outlive the instance: keep them on it.
        self._logger = fmi2CallbackLoggerTYPE(self._on_log)
        self._callbacks = fmi2CallbackFunctions()
        self._callbacks.logger = self._logger
        self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self.fmu = FMU2Slave(
            guid=guid or self.md.guid,
            unzipDirectory=self.unzip_dir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=instance_name,
        )
        self.time = start_time
        self.instantiated = self._initialized = False
        # every output the model description declares, in its order
        self._out_refs = [(v.name, v) for v in self.md.modelVariables if v.causality == "output"]
        self._stress_on = False  # stress_outputs: off, the stress outputs read 0 and are not read (below)
        if instantiate:
            self.instantiate(logging_on=logger is not None)
        if instantiate and initialize:
            try:
                self.initialize(parameters, base0, load0)
            except BaseException:
                self.close()
                raise

    def instantiate(self, logging_on=False):
        self.fmu.instantiate(callbacks=self._callbacks, loggingOn=logging_on)
        self.instantiated = True

    def _on_log(self, env, instance, status, category, message):
        entry = (status, category.decode(errors="replace"), message.decode(errors="replace"))
        self.log.append(entry)
        if self._user_logger is not None:
            self._user_logger(*entry)

    def errors(self):
        """The messages logged with status fmi2Error or worse."""
        return [m for s, _, m in self.log if s >= 3]

    @_explained
    def initialize(self, parameters, base0=0.0, load0=0.0):
        self.enter_initialization(parameters, base0, load0)
        self.exit_initialization()

    @_explained
    def enter_initialization(self, parameters, base0=0.0, load0=0.0):
        """initialize() up to fmi2ExitInitializationMode, for a caller that times that call or
        expects it to fail: the experiment set up, the parameters and start inputs set."""
        self.fmu.setupExperiment(startTime=self.time)
        self.fmu.enterInitializationMode()
        for name, value in parameters.items():
            self.set(name, value)
        self.set("base_displacement", base0)
        self.set("load", load0)

    @_explained
    def exit_initialization(self):
        """fmi2ExitInitializationMode: the FMU builds the plate (or refuses its parameters)."""
        self.fmu.exitInitializationMode()
        self._initialized = True

    # -- variables by name ------------------------------------------------------------------
    @_explained
    def set(self, name, value):
        v = self.vars[name]
        if name == "stress_outputs":
            self._stress_on = bool(value)
        if v.type == "Real":
            self.fmu.setReal([v.valueReference], [float(value)])
        elif v.type == "Integer":
            if isinstance(value, str):  # a switch's item by name, e.g. element="fvs"
                items = switch_items(v)
                if value not in items:
                    raise ValueError(f"{name} = {value!r}: not one of its items {sorted(items)}")
                value = items[value]
            self.fmu.setInteger([v.valueReference], [int(value)])
        elif v.type == "Boolean":
            self.fmu.setBoolean([v.valueReference], [bool(value)])
        else:
            raise TypeError(f"{name}: unsupported type {v.type}")

    @_explained
    def outputs(self):
        # The stress outputs read 0 while stress_outputs is off, and the FMU warns of a read then (a
        # zero it never computed): they are not read, their 0 is given here.
        off = () if self._stress_on else STRESS_OUTPUTS
        real = [(n, v) for n, v in self._out_refs if v.type == "Real" and n not in off]
        ints = [(n, v) for n, v in self._out_refs if v.type == "Integer"]
        read = dict(zip((n for n, _ in real), self.fmu.getReal([v.valueReference for _, v in real])))
        read.update(zip((n for n, _ in ints), self.fmu.getInteger([v.valueReference for _, v in ints])))
        out = {n: read.get(n, 0.0) for n, _ in self._out_refs if n in read or n in off}
        out["time"] = self.time
        return out

    # -- time stepping ----------------------------------------------------------------------
    @_explained
    def step(self, h, base=None, load=None, derivatives=True):
        """Advance by h from self.time; the outputs after the step. base/load: a value or
        (value, first derivative, second derivative) at the step start; None keeps the input
        as it was. derivatives=False sets the values only, as ordinary importers do: the FMU
        then reconstructs the inputs inside the step (base_input_mode / load_input_mode)."""
        refs, values, orders, rates = [], [], [], []
        for name, given in (("base_displacement", base), ("load", load)):
            if given is None:
                continue
            value, d1, d2 = signal(given)
            vr = self.vars[name].valueReference
            refs.append(vr)
            values.append(value)
            orders += [1, 2]
            rates += [d1, d2]
        if refs:
            self.fmu.setReal(refs, values)
        if refs and derivatives:
            self.fmu.setRealInputDerivatives([r for r in refs for _ in (1, 2)], orders, rates)
        self.fmu.doStep(currentCommunicationPoint=self.time, communicationStepSize=h)
        self.time += h  # the FMU accepts the rounding of this sum (relative time tolerance)
        return self.outputs()

    def free(self):
        """fmi2FreeInstance alone (no fmi2Terminate first), once."""
        if self.instantiated:
            self.fmu.freeInstance()
            self.instantiated = False

    def close(self):
        """fmi2Terminate after an initialization, then fmi2FreeInstance; once."""
        if self._initialized:
            self._initialized = False
            try:
                self.fmu.terminate()
            except Exception:
                pass  # after a failed step: fmi2FreeInstance is still allowed
        self.free()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
