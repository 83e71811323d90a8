"""Shaker.fmu and the two-way system model (issue 20, item 4): SineSweep.fmu -> Shaker.fmu <-> PlateImpact.fmu.

The shaker alone (through fmpy):
- its step response against the exact solution of the driven damped oscillator, within the
  trapezoidal rule's phase error (bound derived below), and second order in dt;
- its energy ledger (energy = drive_work + plate_work - damper_loss) closing to roundoff for any
  sequence of steps, off the dt grid included;
- FMU states round-tripping bit for bit; bad parameters, forces and steps refused with a logged
  fmi2Error.
"""

import math
from pathlib import Path

import numpy as np
import pytest
from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
)
from fmpy.validation import validate_fmu

REPO = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def shaker_fmu(fmu_path):
    path = fmu_path.parent / "Shaker.fmu"
    assert path.is_file(), f"Shaker.fmu not built next to {fmu_path}"
    return path


class Shaker:
    """One Shaker.fmu instance through fmpy, initialized with `parameters`."""

    def __init__(self, path, messages=None, **parameters):
        md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        log = messages if messages is not None else []
        # kept alive as long as the instance
        self._logger = fmi2CallbackLoggerTYPE(lambda env, name, status, category, text: log.append(text.decode()))
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = self._logger
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self.fmu = FMU2Slave(
            guid=md.guid, unzipDirectory=extract(str(path)), modelIdentifier="Shaker", instanceName="shaker"
        )
        self.fmu.instantiate(callbacks=self.callbacks, loggingOn=False)
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        for name, value in parameters.items():
            self.fmu.setReal([self.vr[name]], [value])
        self.fmu.exitInitializationMode()
        self.t = 0.0

    def step(self, h, drive=0.0, plate=0.0):
        self.fmu.setReal([self.vr["drive_force"], self.vr["plate_force"]], [drive, plate])
        self.fmu.doStep(currentCommunicationPoint=self.t, communicationStepSize=h)
        self.t += h

    def get(self, *names):
        return self.fmu.getReal([self.vr[n] for n in names])

    def free(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


def step_response(t, m, k, c, force):
    """x(t) of m x'' + c x' + k x = force (constant from t = 0), x(0) = x'(0) = 0, underdamped."""
    omega = math.sqrt(k / m)
    zeta = c / (2 * math.sqrt(k * m))
    wd = omega * math.sqrt(1 - zeta**2)
    decay = np.exp(-zeta * omega * t)
    return force / k * (1 - decay * (np.cos(wd * t) + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * t)))


def step_response_error(path, dt, m=20.0, k=3158.0, c=50.0, force=100.0, stop=1.0, h=1e-2):
    shaker = Shaker(path, mass=m, stiffness=k, damping=c, dt=dt)
    times, x = [], []
    for n in range(1, round(stop / h) + 1):
        shaker.step(h, drive=force)
        times.append(n * h)
        x.append(shaker.get("armature_displacement")[0])
    shaker.free()
    return np.abs(np.array(x) - step_response(np.array(times), m, k, c, force)).max()


def test_shaker_fmu_validates(shaker_fmu):
    assert validate_fmu(str(shaker_fmu)) == []


def test_step_response_matches_the_exact_oscillator_to_second_order(shaker_fmu):
    # The trapezoidal rule keeps the amplitude of a free oscillation and lags its phase by
    # (omega tau)^2 / 12 per radian, so after the time t the error is at most
    # (force / k) (1 + decay terms) omega t (omega tau)^2 / 12: with omega = 12.57 rad/s (2 Hz),
    # tau = 1e-3 s, t = 1 s, force / k = 0.0317 m this is 0.0317 * 12.57 * 1.58e-4 / 12 = 5.2e-6 m.
    # The bound 1e-5 m allows the damping's own (smaller) O(tau^2) error; halving dt must divide
    # the error by about 4 (between 3.5 and 4.5).
    coarse = step_response_error(shaker_fmu, 1e-3)
    fine = step_response_error(shaker_fmu, 5e-4)
    assert coarse < 1e-5, coarse
    assert 3.5 < coarse / fine < 4.5, (coarse, fine)


def test_ledger_closes_to_roundoff_for_any_steps(shaker_fmu):
    rng = np.random.default_rng(20)
    shaker = Shaker(shaker_fmu, mass=3.0, stiffness=2e4, damping=15.0, dt=1e-4)
    scale = 0.0
    for _ in range(400):
        h = float(rng.uniform(1e-5, 3e-3))  # mostly off the dt grid: ceil(h/dt) substeps of h/n
        shaker.step(h, drive=float(rng.normal(0, 500)), plate=float(rng.normal(0, 200)))
        energy, drive, plate, loss = shaker.get("energy", "drive_work", "plate_work", "damper_loss")
        scale = max(scale, abs(drive), abs(plate), loss, energy)
        # The ledger adds one rounded term per substep (at most 30 here, 12 000 in all), each
        # exact to a few ulps of the running sums: 1e-11 relative to the largest sum is many
        # orders above roundoff and many below any scheme error (the trapezoidal rule's
        # energy error at this dt would be ~(omega dt)^2 = 7e-4 relative).
        assert abs(energy - (drive + plate - loss)) <= 1e-11 * scale
    assert loss > 0 and scale > 1.0  # not vacuous
    shaker.free()


def test_fmu_state_round_trips_bit_for_bit(shaker_fmu):
    shaker = Shaker(shaker_fmu, dt=1e-4)
    for k in range(50):
        shaker.step(3.3e-4, drive=100 * math.sin(k / 5))
    names = ("armature_displacement", "armature_velocity", "armature_acceleration", "energy", "damper_loss")
    state = shaker.fmu.deSerializeFMUstate(shaker.fmu.serializeFMUstate(shaker.fmu.getFMUstate()))
    t0 = shaker.t
    runs = []
    for _ in range(2):
        shaker.fmu.setFMUstate(state)
        shaker.t = t0
        for k in range(50):
            shaker.step(7.1e-4, drive=50 * math.cos(k / 3), plate=-10.0)
        runs.append(shaker.get(*names))
    assert runs[0] == runs[1]
    shaker.free()


@pytest.mark.parametrize(
    "name, value, words",
    [
        ("mass", 0.0, "mass = 0"),
        ("mass", 2e12, "mass"),
        ("stiffness", -1.0, "stiffness"),
        ("damping", -0.5, "damping"),
        ("dt", 0.0, "dt = 0"),
    ],
)
def test_bad_parameters_are_refused_with_the_range(shaker_fmu, name, value, words):
    messages = []
    with pytest.raises(FMICallException):
        Shaker(shaker_fmu, messages, **{name: value})
    assert any(words in m and "allowed" in m for m in messages), messages


def test_bad_forces_and_steps_are_refused(shaker_fmu):
    messages = []
    shaker = Shaker(shaker_fmu, messages, dt=1e-9)
    with pytest.raises(FMICallException):
        shaker.fmu.setReal([shaker.vr["drive_force"]], [2e12])
    assert any("drive_force" in m and "1e12" in m for m in messages), messages
    shaker.fmu.reset()
    shaker.fmu.setupExperiment(startTime=0.0)
    shaker.fmu.setReal([shaker.vr["dt"]], [1e-9])
    shaker.fmu.enterInitializationMode()
    shaker.fmu.exitInitializationMode()
    with pytest.raises(FMICallException):
        shaker.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=10.0)
    assert any("substeps" in m for m in messages), messages
    shaker.fmu.freeInstance()  # after fmi2Error: only free, reset or set a state


# -- the two-way system through libcosimpy: python_tests/test_carrier.py (demos/shaker.py) ------
