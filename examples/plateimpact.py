"""A thin driver for PlateImpact.fmu on top of fmpy's FMU2Slave.

Users copy this: it shows how to set the parameters by name, feed inputs *with* their time
derivatives (fmpy's simulate_fmu cannot: its input-derivative path crashes, NOTES.md) and
read the outputs every communication step.

    with PlateImpactFMU("build/PlateImpact.fmu", nx=14, ny=5, dt=1e-5) as plate:
        plate.step(1e-4, base=(z, zdot, zddot))
        print(plate.outputs()["corner_1"])
"""
from __future__ import annotations

import math
import shutil
from pathlib import Path

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)

OUTPUTS = ("corner_1", "corner_2", "free_edge_mid", "energy", "energy_dissipated",
           "energy_input", "contact_vertices", "qp_kkt_residual_max",
           "qp_iterations_total", "qp_iterations_max")


class PlateImpactFMU:
    """One PlateImpact instance: parameters at construction, then step() and outputs()."""

    def __init__(self, fmu_path, start_time=0.0, instance_name="plate", logger=None,
                 unzip_dir=None, **parameters):
        self.fmu_path = str(fmu_path)
        self.md = read_model_description(self.fmu_path)
        self.vars = {v.name: v for v in self.md.modelVariables}
        self._own_dir = unzip_dir is None
        self.unzip_dir = unzip_dir or extract(self.fmu_path)
        self.fmu = FMU2Slave(guid=self.md.guid, unzipDirectory=self.unzip_dir,
                             modelIdentifier=self.md.coSimulation.modelIdentifier,
                             instanceName=instance_name)
        callbacks = None
        if logger is not None:
            # logger(componentEnvironment, instanceName, status, category, message), as fmpy's
            # printLogMessage; the ctypes objects must outlive the instance: keep them here.
            self._logger = fmi2CallbackLoggerTYPE(logger)
            callbacks = fmi2CallbackFunctions()
            callbacks.logger = self._logger
            callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
            callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self._callbacks = callbacks
        self.fmu.instantiate(callbacks=callbacks, loggingOn=logger is not None)
        self.time = start_time
        self.fmu.setupExperiment(startTime=start_time)
        self.fmu.enterInitializationMode()
        for name, value in parameters.items():
            self.set(name, value)
        self.fmu.exitInitializationMode()
        self._out_refs = [(n, self.vars[n]) for n in OUTPUTS if n in self.vars]

    # -- variables by name ------------------------------------------------------------------
    def set(self, name, value):
        v = self.vars[name]
        if v.type == "Real":
            self.fmu.setReal([v.valueReference], [float(value)])
        elif v.type in ("Integer", "Enumeration"):
            if isinstance(value, str):  # enumeration item by name, e.g. element="fvs"
                items = {i.name: i.value for i in v.declaredType.items}
                value = items[value]
            self.fmu.setInteger([v.valueReference], [int(value)])
        elif v.type == "Boolean":
            self.fmu.setBoolean([v.valueReference], [bool(value)])
        else:
            raise TypeError(f"{name}: unsupported type {v.type}")

    def outputs(self):
        real = [(n, v) for n, v in self._out_refs if v.type == "Real"]
        ints = [(n, v) for n, v in self._out_refs if v.type == "Integer"]
        out = dict(zip((n for n, _ in real), self.fmu.getReal([v.valueReference for _, v in real])))
        out.update(zip((n for n, _ in ints), self.fmu.getInteger([v.valueReference for _, v in ints])))
        return out

    # -- time stepping ----------------------------------------------------------------------
    def step(self, h, base=None, load=None):
        """Advance by h. base/load: value or (value, first derivative, second derivative)."""
        for name, signal in (("base_displacement", base), ("load", load)):
            if signal is None:
                continue
            value, *derivatives = signal if isinstance(signal, (tuple, list)) else (signal,)
            vr = self.vars[name].valueReference
            self.fmu.setReal([vr], [float(value)])
            for order, d in enumerate(derivatives, start=1):
                self.fmu.setRealInputDerivatives([vr], [order], [float(d)])
        self.fmu.doStep(currentCommunicationPoint=self.time, communicationStepSize=h)
        self.time += h

    def close(self):
        try:
            self.fmu.terminate()
        finally:
            self.fmu.freeInstance()
            if self._own_dir:
                shutil.rmtree(self.unzip_dir, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def sine(amplitude, frequency, t):
    """Value and first two derivatives of amplitude·sin(2πf t)."""
    w = 2.0 * math.pi * frequency
    return (amplitude * math.sin(w * t), amplitude * w * math.cos(w * t),
            -amplitude * w * w * math.sin(w * t))
