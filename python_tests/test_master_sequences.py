"""The FMI 3.0 call sequences of fmusim (the modelica Reference-FMUs' simulator, v0.0.39,
fmusim/FMI3CSSimulation.c), replayed through fmpy's low-level FMU3Slave on the default scene
(input samples every 1e-4 s over 0.2 s, linearly interpolated between them as fmusim does):

- plain: the inputs set before every step;
- early return: the step ends at a contact onset or release, the next one starts there with the
  inputs interpolated at that time;
- event mode with early return: after the event, event mode and back to step mode, and the next
  step is taken **without setting the inputs again** (fmusim's `inputApplied`; a legal sequence:
  the inputs keep their values) — the sequence that once inflated the energy 2000x;
- intermediate update: the outputs recorded at every internal grid point from the callback;
- an FMU state serialized to bytes at 0.1 s and restored into a new instance.

Each against the plain run: energy at 0.2 s within 10 % (the same scene, other communication
points: the runs are not the same trajectory after the first impacts, and 10 % is the spread of
fmpy's own early return and event mode runs), the free corner never beyond the obstacles, the
restored state bit for bit. The intermediate values at the communication points are the regular
samples of the same run, bit for bit, and those between follow a run stepped at h = dt.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from fmpy.fmi3 import FMU3Slave

H, STOP, DT = 1e-4, 0.2, 1e-5
GAP = 0.1  # the default obstacles at +-0.1 m


@pytest.fixture(scope="module")
def unzipped(unzipped3):  # conftest.py: the FMI 3.0 FMU, extracted
    return unzipped3


def base_at(t):
    """fmusim's continuous input: the CSV samples (every H) linearly interpolated at t."""
    k = min(int(math.floor(t / H + 1e-9)), round(STOP / H) - 1)
    t0, t1 = k * H, (k + 1) * H
    z0, z1 = (0.09 * math.sin(2 * math.pi * 10.0 * t0), 0.09 * math.sin(2 * math.pi * 10.0 * t1))
    return z0 + (z1 - z0) * (t - t0) / (t1 - t0)


def is_close(a, b):
    """fmusim's FMIIsClose (FMIUtil.c): within 1e-5 absolute, or relative. An early return one
    dt = 1e-5 before a regular point counts as reaching it: the next step is 1.1e-4 long."""
    return abs(a - b) <= 1e-5 or abs(a - b) <= 1e-5 * max(abs(a), abs(b))


class Fmusim:
    """fmusim's FMI3CSSimulate, call for call, with fmpy's FMU3Slave."""

    def __init__(
        self, unzipped, start=None, early_return=False, event_mode=False, intermediate=False, stop=STOP, drive=True
    ):
        self.unzipdir, self.md = unzipped
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.start = dict(start or {})
        self.early_return, self.event_mode, self.intermediate = early_return, event_mode, intermediate
        self.stop = stop
        self.base = base_at if drive else (lambda t: 0.0)  # the CSV's one column, or none
        self.samples = []  # (t, corner_1, energy) at every communication point
        self.intermediate_samples = []
        self.events = 0

    def _slave(self):
        return FMU3Slave(
            guid=self.md.guid,
            unzipDirectory=self.unzipdir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName="plate",
        )

    def _sample(self, s, t, into):
        corner, energy = s.getFloat64([self.vr["corner_1"], self.vr["energy"]])
        into.append((t, corner, energy))

    def run(self, save_at=None, restore=None):
        s = self._slave()
        recorded = [self.vr["corner_1"], self.vr["energy"]]

        def callback(env, t, set_requested, get_allowed, finished, can_return_early, requested, early_time):
            if get_allowed:
                self._sample(s, t, self.intermediate_samples)
            requested[0] = False

        s.instantiate(
            eventModeUsed=self.event_mode,
            earlyReturnAllowed=self.early_return,
            intermediateUpdate=callback if self.intermediate else None,
            requiredIntermediateVariables=recorded if self.intermediate else None,
        )
        time = 0.0
        if restore is not None:
            state = s.deserializeFMUState(restore[1])
            s.setFMUState(state)
            s.freeFMUState(state)
            time = restore[0]
        else:
            for name, value in self.start.items():
                if isinstance(value, int):
                    s.setInt32([self.vr[name]], [value])
                else:
                    s.setFloat64([self.vr[name]], [value])
            s.enterInitializationMode(startTime=0.0, stopTime=self.stop)
            s.setFloat64([self.vr["base_displacement"]], [self.base(0.0)])
            s.exitInitializationMode()
            if self.event_mode:
                while s.updateDiscreteStates()[0]:
                    pass
                s.enterStepMode()
            self._sample(s, time, self.samples)
        steps = round(time / H)
        input_applied = False
        saved = None
        while not (time > self.stop or is_close(time, self.stop)):
            regular = (steps + 1) * H
            h = regular - time
            if not input_applied:
                s.setFloat64([self.vr["base_displacement"]], [self.base(time)])
            event, terminate, early, last = s.doStep(time, h)
            time = last if early and last < regular else regular
            if is_close(time, regular):
                steps += 1
            self._sample(s, time, self.samples)
            if self.event_mode and event:
                self.events += 1
                s.enterEventMode()
                while s.updateDiscreteStates()[0]:
                    pass
                s.enterStepMode()
                self._sample(s, time, self.samples)
                input_applied = True
            else:
                input_applied = False
            if save_at is not None and saved is None and is_close(time, save_at):
                state = s.getFMUState()
                saved = (time, s.serializeFMUState(state))
                s.freeFMUState(state)
        s.terminate()
        s.freeInstance()
        return saved

    @property
    def energy(self):
        return self.samples[-1][2]

    @property
    def corner_max(self):
        return max(abs(c) for _, c, _ in self.samples + self.intermediate_samples)


SCHEMES = {
    "newmark": {},
    "conserving": {"mass": 2, "time_scheme": 2},
}
MODES = {"quadratic": 3, "linear": 2}


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("mode", MODES)
def test_event_mode_without_re_set_inputs_keeps_the_energy(unzipped, scheme, mode):
    start = {**SCHEMES[scheme], "base_input_mode": MODES[mode]}
    plain = Fmusim(unzipped, start)
    plain.run()
    events = Fmusim(unzipped, start, early_return=True, event_mode=True)
    events.run()
    early = Fmusim(unzipped, start, early_return=True)
    early.run()
    assert events.events > 10  # the sequence was exercised: the impacts of 0.05..0.2 s
    for run in (events, early):
        assert run.energy == pytest.approx(plain.energy, rel=0.10), (scheme, mode, run.energy, plain.energy)
        assert run.corner_max <= GAP * (1 + 1e-9)
    assert plain.corner_max <= GAP * (1 + 1e-9)


# Free vibration between close obstacles (test_fmi3.FREE_FLIGHT): pressed onto the lower one at
# t = 0 and released; no input moves, so the internal steps do not depend on the communication
# points, and a run at h = dt is the exact reference of the intermediate values, impacts included.
FREE_FLIGHT = {"initial_load": -1500.0, "obstacle_lower": -0.01, "obstacle_upper": 0.01}


def test_intermediate_update_records_every_internal_step(unzipped):
    stop = 0.06  # past the first impact of the default scene (0.0495 s)
    run = Fmusim(unzipped, intermediate=True, stop=stop)
    run.run()
    plain = Fmusim(unzipped, stop=stop)
    plain.run()
    # The communication points as without the callback, bit for bit; between them every internal
    # grid point strictly inside each step (9 per step of 10 dt), in order.
    assert run.samples == plain.samples
    times = np.array([t for t, _, _ in run.intermediate_samples])
    assert len(times) == 9 * round(stop / H)
    grid = np.sort(np.concatenate((times, np.arange(1, round(stop / H) + 1) * H)))
    assert np.allclose(np.diff(np.concatenate(([0.0], grid))), DT, rtol=1e-6)
    assert run.corner_max <= GAP * (1 + 1e-9)


def test_intermediate_values_are_the_internal_steps_bit_for_bit(unzipped):
    stop = 0.03  # the plate crosses the 2 cm gap and hits the upper obstacle
    run = Fmusim(unzipped, FREE_FLIGHT, intermediate=True, stop=stop, drive=False)
    run.run()
    fine = Fmusim(unzipped, FREE_FLIGHT, stop=stop)
    s = fine._slave()
    s.instantiate()
    vr = fine.vr
    for name, value in FREE_FLIGHT.items():
        s.setFloat64([vr[name]], [value])
    s.enterInitializationMode(startTime=0.0, stopTime=stop)
    s.exitInitializationMode()
    at_dt = {}
    for k in range(round(stop / DT)):
        s.doStep(k * DT, DT)
        at_dt[k + 1] = tuple(s.getFloat64([vr["corner_1"], vr["energy"]]))
    s.terminate()
    s.freeInstance()
    recorded = run.intermediate_samples + run.samples[1:]
    assert any(abs(c) >= 0.01 * (1 - 1e-12) for _, c, _ in recorded)  # impacts inside the window
    for t, corner, energy in recorded:
        assert (corner, energy) == at_dt[round(t / DT)], t


def test_state_serialized_and_restored_in_a_new_instance_continues_bit_for_bit(unzipped):
    straight = Fmusim(unzipped, early_return=True, event_mode=True)
    saved = straight.run(save_at=0.1)
    assert saved is not None
    resumed = Fmusim(unzipped, early_return=True, event_mode=True)
    resumed.run(restore=saved)
    tail = [x for x in straight.samples if x[0] > saved[0] + 1e-12]
    assert resumed.samples == tail[: len(resumed.samples)] and len(resumed.samples) == len(tail)
