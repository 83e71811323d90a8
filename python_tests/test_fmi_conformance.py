"""FMI 2.0 co-simulation conformance of PlateImpact.fmu (fmpy as the importer).

- the model description validates and agrees with the binary's variable table;
- the catalogue of wrong calls: each runs in a process of its own, must return fmi2Error, must be
  named in the log, and the process must end normally (exit code 0, no crash);
- FMU states (get/set and serialize/deserialize), fmi2Reset and concurrent instances must
  reproduce runs bit for bit.

The processes run this file as a script: python test_fmi_conformance.py --child DIR CASE runs one
case; --serve DIR is a warm server (Python, fmpy and this module imported once) that runs each case
named on its stdin in a fork of itself and answers one JSON line per case (issue 46: the imports
were most of a case's time, and under the sanitizer's preloaded runtime more so).
"""

import ctypes
import json
import math
import os
import re
import struct
import subprocess
import sys
import threading
import time

import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    fmi2DoStepStatus,
    fmi2LastSuccessfulTime,
    fmi2Terminated,
)
from state_bytes import HEADER, with_checksum

from plateimpact import PlateImpactFMU

# The sanitizer stage of test.sh runs this file against the ASan+UBSan build (pytest.ini).
pytestmark = pytest.mark.sanitizer

FMI_ERROR = 3
FMI_DISCARD = 2

# A short scene with impacts: released from the static shape under 8600 Pa, which presses the
# plate against the upper obstacle at 5 cm, with base motion and a varying load. Communication
# step H = 10 dt.
SCENE = {"dt": 1e-4, "initial_load": 8600.0, "obstacle_lower": -0.05, "obstacle_upper": 0.05}
H = 1e-3
# Variants of the scene for the reproducibility tests: the default Argyris mesh (small enough
# for the solver's complete modal basis), a finer one (sparse factor), the FVS element, and the
# reduced modal model.
CONFIGS = {
    "argyris": SCENE,
    "argyris_fine": dict(SCENE, nx=28, ny=10),
    "fvs": dict(SCENE, element=2, nx=20, ny=7),
    "reduced_modal": dict(SCENE, modes=20),
    # the laws of docs/theory.md §11-13: the singular mass carries contact impulses in its state
    "singular_laws": dict(SCENE, mass=2, restitution=0.5, damping_mass=5.0, damping_stiffness=1e-5),
    "modal_restitution_damping": dict(SCENE, restitution=0.3, damping_mass=2.0),
    # the energy-conserving engine (docs/theory.md §17): its own state format and early return
    "conserving": dict(SCENE, mass=2, time_scheme=2),
    # exact free flight and sub-stepped contact steps (docs/theory.md §21), damped and driven
    "flow": dict(SCENE, mass=2, time_scheme=3, contact_substeps=8, damping_mass=2.0),
}
# The sanitizer stage runs reset and two threads on the configurations whose instances are cheap
# to make under ASan (the flow and the conserving engine, both on the default mesh with the
# singular mass): reset and the threads are the FMI layer's and the cache's logic, the same for
# every engine, and every engine's stepping and state code runs under ASan in the FMU state test
# of its own configuration. The other configurations name those two tests (repeats_paths).
SANITIZER_CONFIGS = ("conserving", "flow")


def configs_sparing_the_sanitizer(test):
    return [
        c
        if c in SANITIZER_CONFIGS
        else pytest.param(
            c,
            marks=pytest.mark.repeats_paths(
                f"test_fmi_conformance.py::{test}[flow]",
                f"test_fmi_conformance.py::test_fmu_state_get_set_and_serialize_are_bit_identical[{c}]",
            ),
        )
        for c in sorted(CONFIGS)
    ]


# A coarse mesh for the checks of the FMI layer that do not depend on the discretization.
FAST = {"nx": 4, "ny": 2}


# ---------------------------------------------------------------------------------------------
# Helpers


def session(unzipdir, name="plate", logging_on=False):
    """One instance of the package's driver, instantiated, not initialized; every message it
    logs is in .log as (status, category, message)."""
    s = PlateImpactFMU(unzipdir, instance_name=name, instantiate=False)
    s.instantiate(logging_on)
    return s


def vr(session, name):
    return session.vars[name].valueReference


def set_values(session, values):
    for name, value in values.items():
        session.set(name, value)


def bits(session):
    """Every output, bit for bit (float.hex tells -0.0 from 0.0)."""
    return tuple(v.hex() if isinstance(v, float) else v for n, v in session.outputs().items() if n != "time")


def inputs_at(t):
    """Base motion and load with their first and second time derivatives at t."""
    w, f = 2 * math.pi * 20.0, 2 * math.pi * 7.0
    base = (0.005 * math.sin(w * t), 0.005 * w * math.cos(w * t), -0.005 * w * w * math.sin(w * t))
    load = (200.0 * math.cos(f * t), -200.0 * f * math.sin(f * t), -200.0 * f * f * math.cos(f * t))
    return base, load


def drive(session, k0, k1, record=True):
    """Communication steps k0..k1-1 of length H with inputs and input derivatives."""
    trace = []
    refs = [vr(session, "base_displacement"), vr(session, "load")]
    for k in range(k0, k1):
        t = k * H
        base, load = inputs_at(t)
        session.fmu.setReal(refs, [base[0], load[0]])
        session.fmu.setRealInputDerivatives([r for r in refs for _ in (1, 2)], [1, 2, 1, 2], [*base[1:], *load[1:]])
        session.fmu.doStep(t, H)
        if record:
            trace.append(bits(session))
    return trace


def full_run(session, parameters, steps=30):
    session.initialize(parameters)
    return [bits(session)] + drive(session, 0, steps)


def norm(text):
    return re.sub(r"[^a-z0-9]", "", text.lower())


@pytest.fixture(scope="module")
def unzipped(extracted_fmu):
    return extracted_fmu


# ---------------------------------------------------------------------------------------------
# Model description


def test_validate_fmu_reports_no_problems(fmu_path):
    from fmpy.validation import validate_fmu

    assert validate_fmu(str(fmu_path)) == []


# What each causality implies for a variable: its variabilities, whether it has a start value.
CAUSALITY = {
    "parameter": ({"fixed"}, True),
    "input": ({"continuous"}, True),
    "output": ({"continuous", "discrete"}, False),
}


def declared_start(v):
    """A variable's declared start value as the binary returns it."""
    return v.start == "true" if v.type == "Boolean" else float(v.start)


def test_variables_are_named_once_and_described(unzipped):
    variables = read_model_description(str(unzipped)).modelVariables
    assert len({v.name for v in variables}) == len(variables)
    assert len({v.valueReference for v in variables}) == len(variables)
    assert [v.name for v in variables if not v.description] == []


def test_variables_follow_their_causality(unzipped):
    for v in read_model_description(str(unzipped)).modelVariables:
        variabilities, has_start = CAUSALITY[v.causality]
        assert v.variability in variabilities, v.name
        assert (v.start is not None) == has_start, v.name
        if v.causality != "parameter":  # inputs and outputs: Real continuous, the others discrete
            assert v.variability == ("continuous" if v.type == "Real" else "discrete"), v.name
        if v.type == "Enumeration" and has_start:
            assert int(v.start) in {int(i.value) for i in v.declaredType.items}, v.name


def test_every_real_has_a_declared_unit(unzipped):
    md = read_model_description(str(unzipped))
    defined = {u.name for u in md.unitDefinitions}
    reals = [v for v in md.modelVariables if v.type == "Real"]
    assert [(v.name, v.unit) for v in reals if v.unit not in defined] == []
    assert {v.unit for v in reals} == defined  # and no definition is unused
    assert [v.name for v in md.modelVariables if v.type != "Real" and v.unit] == []


def test_model_description_declares_the_co_simulation(unzipped):
    md = read_model_description(str(unzipped))
    assert [c.name for c in md.logCategories] == ["logStatusError", "logStatusWarning", "logInfo", "logAll"]
    cs = md.coSimulation
    assert cs.modelIdentifier == "PlateImpact"
    assert cs.canHandleVariableCommunicationStepSize and cs.canInterpolateInputs
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate and cs.canNotUseMemoryManagementFunctions
    assert int(cs.maxOutputDerivativeOrder) == 0
    assert [u.variable.name for u in md.outputs] == [v.name for v in md.modelVariables if v.causality == "output"]
    assert re.fullmatch(r"[0-9a-f]{8}-[0-9a-f]{4}-5[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}", md.guid)


def test_binary_agrees_with_model_description(unzipped):
    """Every declared variable is readable with its type and starts at its declared start value,
    also after fmi2Reset (which must undo the mesh set after the reads of the parameters and
    inputs: nx, ny are FAST's before the outputs are read in each round, so the plate built is the
    coarse one — issue 54: the default plate, built for this test alone in its worker, was 15-20 s
    of the sanitizer stage's CPU); the GUID of the XML is the one compiled into the binary."""
    md = read_model_description(str(unzipped))
    assert md.guid.encode() in (unzipped / "binaries" / "linux64" / "PlateImpact.so").read_bytes()
    s = session(unzipped)
    try:
        for round_ in range(2):
            s.fmu.setupExperiment(startTime=0.0)
            s.fmu.enterInitializationMode()
            # the parameters and inputs first: an output read in initialization mode builds the
            # plate of the parameters set so far (test_parameter_change_in_initialization_mode_rebuilds)
            variables = sorted(md.modelVariables, key=lambda v: v.causality == "output")
            for k, v in enumerate(variables):
                if v.causality == "output" and variables[k - 1].causality != "output":
                    set_values(s, FAST)
                if v.type == "Real":
                    value = s.fmu.getReal([v.valueReference])[0]
                elif v.type in ("Integer", "Enumeration"):
                    value = s.fmu.getInteger([v.valueReference])[0]
                else:
                    value = bool(s.fmu.getBoolean([v.valueReference])[0])
                if v.start is not None:
                    assert value == declared_start(v), (round_, v.name, value)
            s.fmu.exitInitializationMode()
            s.fmu.terminate()
            s.fmu.reset()
        assert s.errors() == []
    finally:
        s.free()


# ---------------------------------------------------------------------------------------------
# The catalogue of wrong calls, each in a child process


class ChildContext:
    def __init__(self, unzipdir):
        self.unzipdir = unzipdir
        self.session = None
        self.calls = []  # one entry per expect_error: {"raised", "status", "type"}
        self.notes = {}

    def open(self, logging_on=False, guid=None):
        self.session = PlateImpactFMU(self.unzipdir, instance_name="child", instantiate=False, guid=guid)
        self.session.instantiate(logging_on)  # the session keeps the log even if this fails
        return self.session.fmu

    def expect_error(self, function):
        try:
            function()
            self.calls.append({"raised": False, "status": 0, "type": ""})
        except FMICallException as e:
            self.calls.append({"raised": True, "status": e.status, "type": "FMICallException"})
        except Exception as e:
            # fmpy's answer to fmi2Instantiate returning NULL; anything else is a failure
            status = FMI_ERROR if str(e) == "Failed to instantiate model" else None
            self.calls.append({"raised": True, "status": status, "type": f"{type(e).__name__}: {e}"})

    def raw_call(self, name, argtypes, *args):
        """Call an fmi2 function fmpy's FMU2Slave does not wrap; fmi2Error raises as usual."""
        function = getattr(self.session.fmu.dll, name)
        function.argtypes = [ctypes.c_void_p] + argtypes
        function.restype = ctypes.c_int
        status = function(self.session.fmu.component, *args)
        if status > 1:
            raise FMICallException(function=name, status=status)

    def start(self, parameters=None):
        self.open()
        self.session.initialize(dict(FAST, **(parameters or {})))
        return self.session.fmu


def _after_error(ctx, fmu):
    """After fmi2Error: fmi2DoStep is an illegal call in state error, fmi2Reset works."""
    ctx.expect_error(lambda: fmu.doStep(0.0, 1e-3))
    fmu.reset()
    ctx.notes["reset_after_error"] = True


def _bad_parameter(values):
    def case(ctx):
        fmu = ctx.open()
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        set_values(ctx.session, values)
        ctx.expect_error(fmu.exitInitializationMode)
        _after_error(ctx, fmu)

    return case


def _corrupt_state(mutate):
    def case(ctx):
        fmu = ctx.start(SCENE)
        drive(ctx.session, 0, 2, record=False)
        state = fmu.getFMUstate()
        blob = fmu.serializeFMUstate(state)
        fmu.freeFMUstate(state)
        ctx.expect_error(lambda: fmu.deSerializeFMUstate(mutate(blob)))
        fmu.reset()
        ctx.notes["reset_after_error"] = True

    return case


def _put_double(blob, index, value):
    """Patch value `index` of a serialized state and repair its checksum, so that the decoder's
    own checks of the values are what the case exercises (a plain patch is refused earlier, by
    the checksum: test_state_integrity.py)."""
    offset = HEADER + 8 * index
    return with_checksum(blob[:offset] + struct.pack("d", value) + blob[offset + 8 :])


def _case_without_error_log(ctx):
    fmu = ctx.open()
    fmu.setDebugLogging(False, ["logStatusError"])
    ctx.expect_error(lambda: fmu.doStep(0.0, 1e-3))


def _me_set_time(ctx):
    ctx.start()
    ctx.expect_error(lambda: ctx.raw_call("fmi2SetTime", [ctypes.c_double], 0.0))


def _step_failure(ctx):
    fmu = ctx.start({"obstacle_upper_enabled": False})
    fmu.setReal([vr(ctx.session, "base_displacement")], [-0.5])  # the clamp 40 cm below the lower obstacle
    ctx.expect_error(lambda: fmu.doStep(0.0, 1e-3))
    _after_error(ctx, fmu)


def _status_discard(ctx):
    fmu = ctx.start()
    fmu.doStep(0.0, 1e-3)
    ctx.expect_error(lambda: fmu.getStatus(fmi2DoStepStatus))


def _wrong_guid(ctx):
    ctx.expect_error(lambda: ctx.open(guid="00000000-0000-5000-8000-000000000000"))


CATALOGUE = {
    # illegal call sequences
    "dostep_before_init": (
        lambda c: c.expect_error(lambda: c.open().doStep(0.0, 1e-3)),
        ["illegal call sequence", "fmi2DoStep", "instantiated"],
    ),
    "getreal_before_init": (
        lambda c: c.expect_error(lambda: c.open().getReal([vr(c.session, "corner_1")])),
        ["illegal call sequence", "fmi2GetReal", "instantiated"],
    ),
    "exit_init_before_enter": (
        lambda c: c.expect_error(lambda: c.open().exitInitializationMode()),
        ["illegal call sequence", "fmi2ExitInitializationMode"],
    ),
    "setreal_parameter_after_init": (
        lambda c: c.expect_error(lambda: c.start().setReal([vr(c.session, "length")], [1.0])),
        ["illegal call sequence", "fmi2SetReal", "length", "stepComplete"],
    ),
    "setinteger_parameter_after_init": (
        lambda c: c.expect_error(lambda: c.start().setInteger([vr(c.session, "nx")], [20])),
        ["illegal call sequence", "fmi2SetInteger", "nx"],
    ),
    "setboolean_parameter_after_init": (
        lambda c: c.expect_error(lambda: c.start().setBoolean([vr(c.session, "obstacle_lower_enabled")], [False])),
        ["illegal call sequence", "obstacle_lower_enabled"],
    ),
    "dostep_after_terminate": (
        lambda c: c.expect_error(lambda: (c.start().terminate(), c.session.fmu.doStep(0.0, 1e-3))),
        ["illegal call sequence", "fmi2DoStep", "terminated"],
    ),
    "cancel_step": (
        lambda c: c.expect_error(lambda: c.start().cancelStep()),
        ["illegal call sequence", "fmi2CancelStep"],
    ),
    "setreal_output": (
        lambda c: c.expect_error(lambda: c.start().setReal([vr(c.session, "corner_1")], [0.0])),
        ["corner_1", "output"],
    ),
    "unknown_value_reference": (
        lambda c: c.expect_error(lambda: c.start().getReal([99])),
        ["unknown value reference 99"],
    ),
    "wrong_type": (lambda c: c.expect_error(lambda: c.start().getReal([vr(c.session, "nx")])), ["nx", "Integer"]),
    "no_string_variables": (
        lambda c: c.expect_error(lambda: c.start().getString([vr(c.session, "length")])),
        ["String"],
    ),
    # fmi2DoStep arguments
    "wrong_communication_point": (
        lambda c: c.expect_error(lambda: c.start().doStep(0.5, 1e-3)),
        ["currentCommunicationPoint", "0.5"],
    ),
    "step_size_zero": (
        lambda c: c.expect_error(lambda: c.start().doStep(0.0, 0.0)),
        ["communicationStepSize", "must be > 0"],
    ),
    "step_size_negative": (
        lambda c: c.expect_error(lambda: c.start().doStep(0.0, -1e-3)),
        ["communicationStepSize", "-0.001", "must be > 0"],
    ),
    # Any step the grid resolves is taken (docs/theory.md §15); one shorter than 1e-9 dt is not.
    "step_size_below_grid_resolution": (
        lambda c: c.expect_error(lambda: c.start().doStep(0.0, 5e-15)),
        ["h = 5e-15", "shorter than the smallest step", "dt = 1.0000000000000001e-05", "1e-9 dt"],
    ),
    # non-finite values
    "nan_input": (
        lambda c: c.expect_error(lambda: c.start().setReal([vr(c.session, "load")], [float("nan")])),
        ["load", "nan"],
    ),
    "inf_input": (
        lambda c: c.expect_error(lambda: c.start().setReal([vr(c.session, "base_displacement")], [float("inf")])),
        ["base_displacement", "inf"],
    ),
    "nan_parameter": (
        lambda c: c.expect_error(lambda: c.open().setReal([vr(c.session, "youngs_modulus")], [float("nan")])),
        ["youngs_modulus", "nan"],
    ),
    "nan_input_derivative": (
        lambda c: c.expect_error(
            lambda: c.start().setRealInputDerivatives([vr(c.session, "load")], [1], [float("nan")])
        ),
        ["load", "nan"],
    ),
    # input derivatives
    "input_derivative_order_3": (
        lambda c: c.expect_error(lambda: c.start().setRealInputDerivatives([vr(c.session, "load")], [3], [1.0])),
        ["order 3", "load"],
    ),
    "input_derivative_of_parameter": (
        lambda c: c.expect_error(lambda: c.start().setRealInputDerivatives([vr(c.session, "length")], [1], [1.0])),
        ["value reference 0", "not a Real input"],
    ),
    "output_derivatives": (
        lambda c: c.expect_error(lambda: c.start().getRealOutputDerivatives([vr(c.session, "corner_1")], [1])),
        ["fmi2GetRealOutputDerivatives", "not supported"],
    ),
    # enumeration outside its items
    "bad_enumeration_item": (
        lambda c: c.expect_error(lambda: c.open().setInteger([8], [3])),
        ["element", "argyris", "fvs"],
    ),
    "bad_mass_item": (
        lambda c: c.expect_error(lambda: c.open().setInteger([50], [4])),
        ["mass", "consistent", "singular_p0", "singular_p1dg"],
    ),
    # invalid parameters, rejected by fmi2ExitInitializationMode
    "restitution_negative": (
        _bad_parameter({"restitution": -0.1}),
        ["invalid parameter", "restitution", "0 <= restitution <= 1"],
    ),
    "restitution_above_one": (
        _bad_parameter({"restitution": 1.5}),
        ["invalid parameter", "restitution", "0 <= restitution <= 1"],
    ),
    "damping_mass_negative": (
        _bad_parameter({"damping_mass": -1.0}),
        ["invalid parameter", "damping_mass", "0 <= damping_mass"],
    ),
    "damping_stiffness_negative": (
        _bad_parameter({"damping_stiffness": -1e-5}),
        ["invalid parameter", "damping_stiffness", "0 <= damping_stiffness"],
    ),
    "singular_mass_without_massless_vertices": (
        _bad_parameter({"element": 2, "mass": 3}),
        ["invalid parameter mass = singular_p1dg", "massless directions", "contact vertices"],
    ),
    "singular_mass_with_modes": (
        _bad_parameter({"mass": 2, "modes": 10}),
        ["invalid parameter", "modes", "singular mass"],
    ),
    "singular_mass_with_small_beta": (
        _bad_parameter({"mass": 2, "beta": 0.2}),
        ["invalid parameter", "beta", "0.25 <= beta", "singular mass"],
    ),
    "poisson_ratio_half": (_bad_parameter({"poisson_ratio": 0.5}), ["invalid parameter", "poisson_ratio"]),
    "poisson_ratio_zero": (_bad_parameter({"poisson_ratio": 0.0}), ["invalid parameter", "poisson_ratio"]),
    "poisson_ratio_negative": (_bad_parameter({"poisson_ratio": -0.2}), ["invalid parameter", "poisson_ratio"]),
    "length_zero": (_bad_parameter({"length": 0.0}), ["invalid parameter", "length"]),
    "length_negative": (_bad_parameter({"length": -1.2}), ["invalid parameter", "length"]),
    "width_zero": (_bad_parameter({"width": 0.0}), ["invalid parameter", "width"]),
    "thickness_negative": (_bad_parameter({"thickness": -0.01}), ["invalid parameter", "thickness"]),
    "youngs_modulus_zero": (_bad_parameter({"youngs_modulus": 0.0}), ["invalid parameter", "youngs_modulus"]),
    "density_negative": (_bad_parameter({"density": -7770.0}), ["invalid parameter", "density"]),
    "nx_zero": (_bad_parameter({"nx": 0}), ["invalid parameter", "nx"]),
    "ny_negative": (_bad_parameter({"ny": -3}), ["invalid parameter", "ny"]),
    "obstacle_lower_zero": (_bad_parameter({"obstacle_lower": 0.0}), ["invalid parameter", "obstacle_lower"]),
    "obstacle_lower_positive": (_bad_parameter({"obstacle_lower": 0.05}), ["invalid parameter", "obstacle_lower"]),
    "obstacle_upper_zero": (_bad_parameter({"obstacle_upper": 0.0}), ["invalid parameter", "obstacle_upper"]),
    "obstacle_upper_negative": (_bad_parameter({"obstacle_upper": -0.05}), ["invalid parameter", "obstacle_upper"]),
    "dt_zero": (_bad_parameter({"dt": 0.0}), ["invalid parameter", "dt"]),
    "dt_negative": (_bad_parameter({"dt": -1e-5}), ["invalid parameter", "dt"]),
    # found by fuzz/parameters.cpp: a denormal dt was accepted and the energy came out NaN; every
    # parameter now has a range that keeps the scheme's arithmetic finite
    "dt_denormal": (_bad_parameter({"dt": 5e-324}), ["invalid parameter", "dt", "1e-12"]),
    "youngs_modulus_huge": (_bad_parameter({"youngs_modulus": 1e300}), ["invalid parameter", "youngs_modulus"]),
    "density_denormal": (_bad_parameter({"density": 5e-324}), ["invalid parameter", "density"]),
    "length_huge": (_bad_parameter({"length": 1e200}), ["invalid parameter", "length"]),
    "initial_load_huge": (_bad_parameter({"initial_load": 1e300}), ["invalid parameter", "initial_load"]),
    "beta_negative": (_bad_parameter({"beta": -0.1}), ["invalid parameter", "beta"]),
    "beta_above_half": (_bad_parameter({"beta": 0.6}), ["invalid parameter", "beta"]),
    "beta_zero_dt_unstable": (
        _bad_parameter({"beta": 0.0, "dt": 1e-5}),
        ["invalid parameter", "dt = 1e-05", "beta = 0", ("kappa", "stab")],
    ),
    # logging
    "unknown_log_category": (
        lambda c: c.expect_error(lambda: c.open().setDebugLogging(True, ["logEverything"])),
        ["unknown log category", "logEverything"],
    ),
    # corrupt serialized FMU states
    "state_wrong_magic": (_corrupt_state(lambda b: b"X" + b[1:]), ["fmi2DeSerializeFMUstate", "magic"]),
    "state_truncated": (_corrupt_state(lambda b: b[:-8]), ["fmi2DeSerializeFMUstate", "wrong size"]),
    "state_too_short": (_corrupt_state(lambda b: b[:10]), ["fmi2DeSerializeFMUstate", "header"]),
    "state_extra_bytes": (_corrupt_state(lambda b: b + bytes(8)), ["fmi2DeSerializeFMUstate", "wrong size"]),
    "state_other_guid": (
        _corrupt_state(lambda b: b[:16] + bytes([b[16] ^ 1]) + b[17:]),
        ["fmi2DeSerializeFMUstate", "GUID"],
    ),
    "state_bad_machine_state": (
        _corrupt_state(lambda b: _put_double(b, 0, 12345.0)),
        ["fmi2DeSerializeFMUstate", "corrupt", "state"],
    ),
    "state_nan_parameter": (
        _corrupt_state(lambda b: _put_double(b, 2, float("nan"))),
        ["fmi2DeSerializeFMUstate", "corrupt", "length"],
    ),
    # others
    "wrong_guid": (_wrong_guid, ["wrong GUID"]),
    "model_exchange_function": (_me_set_time, ["fmi2SetTime", "Model Exchange"]),
    "status_not_available": (_status_discard, ["fmi2GetStatus", "fmi2DoStepStatus"]),
    "step_failure": (_step_failure, ["fmi2DoStep", "failed"]),
}
# Expected status of the first call of a case, when not fmi2Error.
EXPECTED_STATUS = {"status_not_available": FMI_DISCARD}


def _child_main(unzipdir, case):
    ctx = ChildContext(unzipdir)
    unexpected = None
    try:
        CATALOGUE[case][0](ctx)
    except Exception as e:  # reported to the parent, which fails the test
        unexpected = repr(e)
    log = ctx.session.log if ctx.session else []
    if ctx.session:
        ctx.session.free()
    print(json.dumps({"calls": ctx.calls, "log": log, "notes": ctx.notes, "unexpected": unexpected}))
    sys.stdout.flush()


CASE_SECONDS = 120  # a case that takes longer is killed (SIGALRM) and fails as a crash


def _serve(unzipdir):
    """Runs each case named on stdin in a fork of this process (a fresh process image for the FMU:
    the server never loads it) and prints {"returncode", "stdout", "stderr"} as one JSON line: the
    fork's exit code (negative: the signal that ended it) and what it wrote."""
    import signal
    import tempfile

    for line in sys.stdin:
        case = line.strip()
        with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
            sys.stdout.flush()
            sys.stderr.flush()
            pid = os.fork()
            if pid == 0:  # the case: its output into the files, its end its exit code
                code = 1
                try:
                    os.dup2(out.fileno(), 1)
                    os.dup2(err.fileno(), 2)
                    signal.alarm(CASE_SECONDS)
                    _child_main(unzipdir, case)
                    code = 0
                except BaseException:
                    import traceback

                    traceback.print_exc()
                finally:
                    sys.stdout.flush()
                    sys.stderr.flush()
                    os._exit(code)
            _, status = os.waitpid(pid, 0)
            out.seek(0)
            err.seek(0)
            answer = {
                "returncode": os.waitstatus_to_exitcode(status),
                "stdout": out.read().decode(errors="replace"),
                "stderr": err.read().decode(errors="replace"),
            }
        print(json.dumps(answer), flush=True)


def _run_cases(unzipped, cases):
    """(returncode, stdout, stderr) per case, run one after the other by one --serve process."""
    server = subprocess.Popen(
        [sys.executable, __file__, "--serve", str(unzipped)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    outcomes = {}
    try:
        for case in cases:
            server.stdin.write(case + "\n")
            server.stdin.flush()
            line = server.stdout.readline()
            if not line:  # the server itself died: every case left fails with its exit code
                code = server.wait()
                outcomes.update({c: (code, "", f"--serve ended with {code}") for c in cases if c not in outcomes})
                break
            answer = json.loads(line)
            outcomes[case] = (answer["returncode"], answer["stdout"], answer["stderr"])
    finally:
        server.stdin.close()
        server.wait(timeout=CASE_SECONDS)
    return outcomes


@pytest.fixture(scope="module")
def catalogue_outcomes(unzipped):
    """All catalogue cases, each in a process of its own (forks of a few warm servers, several at a
    time); conftest.py keeps the catalogue's tests in one pytest-xdist worker, so this runs once."""
    from concurrent.futures import ThreadPoolExecutor

    servers = max(2, min(8, os.cpu_count() or 2))
    cases = sorted(CATALOGUE)
    shares = [cases[k::servers] for k in range(servers)]
    with ThreadPoolExecutor(servers) as pool:
        parts = list(pool.map(lambda share: _run_cases(unzipped, share), shares))
    return {case: outcome for part in parts for case, outcome in part.items()}


@pytest.mark.parametrize("case", sorted(CATALOGUE))
def test_catalogue(catalogue_outcomes, case):
    returncode, stdout, stderr = catalogue_outcomes[case]
    assert returncode == 0, f"child crashed (exit code {returncode}): {stderr[-2000:]}"
    outcome = json.loads(stdout.strip().splitlines()[-1])
    assert outcome["unexpected"] is None, outcome["unexpected"]
    calls = outcome["calls"]
    assert calls, "the case made no checked call"
    assert all(c["raised"] for c in calls), calls
    assert calls[0]["status"] == EXPECTED_STATUS.get(case, FMI_ERROR), calls
    assert all(c["status"] in (FMI_ERROR, FMI_DISCARD) for c in calls), calls
    if "reset_after_error" in outcome["notes"] or len(calls) > 1:
        assert outcome["notes"].get("reset_after_error"), outcome
    messages = " | ".join(m[2] for m in outcome["log"] if m[0] >= FMI_DISCARD)
    for keyword in CATALOGUE[case][1]:
        alternatives = keyword if isinstance(keyword, tuple) else (keyword,)
        assert any(norm(a) in norm(messages) for a in alternatives), f"{keyword!r} not in log: {messages}"
    if len(calls) > 1:  # a second call after the error: the illegal call sequence in state error
        assert "illegal call sequence: fmi2DoStep is not allowed in state error" in messages


def test_errors_are_not_logged_once_switched_off(unzipped):
    """Errors are logged by default (loggingOn=false); fmi2SetDebugLogging can switch them off."""
    ctx = ChildContext(str(unzipped))
    ctx.expect_error(lambda: ctx.open().doStep(0.0, 1e-3))
    assert any(m[0] == FMI_ERROR and m[1] == "logStatusError" for m in ctx.session.log)
    ctx.session.free()
    ctx = ChildContext(str(unzipped))
    _case_without_error_log(ctx)
    assert ctx.calls == [{"raised": True, "status": FMI_ERROR, "type": "FMICallException"}]
    assert ctx.session.log == []
    ctx.session.free()


def test_logging_on_traces_with_log_all(unzipped):
    s = session(unzipped, logging_on=True)
    try:
        s.initialize(SCENE)
        drive(s, 0, 2, record=False)
        categories = {m[1] for m in s.log}
        assert "logAll" in categories
        assert any("fmi2DoStep" in m[2] for m in s.log)
        s.log.clear()
        s.fmu.setDebugLogging(False, [])  # all categories off
        drive(s, 2, 4, record=False)
        with pytest.raises(FMICallException):
            s.fmu.doStep(0.0, H)  # wrong time: error, but logging is off
        assert s.log == []
    finally:
        s.free()


# ---------------------------------------------------------------------------------------------
# Co-simulation behaviour


def test_status_functions_and_tolerant_step_sizes(unzipped):
    s = session(unzipped)
    try:
        s.initialize(SCENE)
        t = 0.0
        for k in range(5):
            h = H * (1 + (-1) ** k * 3e-13)  # wobble in the last digits, as importers do
            s.fmu.doStep(t * (1 + 1e-14), h)
            t += h
            assert s.fmu.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(t, rel=1e-12)
        assert s.fmu.getBooleanStatus(fmi2Terminated) is False
        s.fmu.terminate()
        assert s.fmu.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(5 * H, rel=1e-12)
        assert s.errors() == []
    finally:
        s.free()


def test_start_time_offsets_the_communication_points(unzipped):
    s, zero = session(unzipped), session(unzipped)
    try:
        s.fmu.setupExperiment(startTime=2.0)
        s.fmu.enterInitializationMode()
        set_values(s, dict(SCENE, **FAST))
        s.fmu.exitInitializationMode()
        zero.initialize(dict(SCENE, **FAST))
        for k in range(3):
            s.fmu.doStep(2.0 + k * H, H)
            zero.fmu.doStep(k * H, H)
        assert s.fmu.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(2.0 + 3 * H, rel=1e-12)
        assert bits(s) == bits(zero)  # the plate does not depend on the clock's origin
        with pytest.raises(FMICallException):
            s.fmu.doStep(3 * H, H)  # a communication point on the wrong clock
    finally:
        s.free()
        zero.free()


def test_input_derivatives_act_and_reset_when_the_value_is_set(unzipped):
    def one_step(with_derivative, set_value_again):
        s = session(unzipped)
        try:
            s.initialize(dict(SCENE, **FAST))
            s.fmu.setReal([vr(s, "load")], [100.0])
            if with_derivative:
                s.fmu.setRealInputDerivatives([vr(s, "load"), vr(s, "load")], [1, 2], [5e5, 1e8])
            if set_value_again:
                s.fmu.setReal([vr(s, "load")], [100.0])  # a plain held value again: derivatives 0
            s.fmu.doStep(0.0, 5 * H)
            return bits(s)
        finally:
            s.free()

    held = one_step(False, False)
    assert one_step(True, True) == held
    assert one_step(True, False) != held


def test_parameter_change_in_initialization_mode_rebuilds(unzipped):
    """An output read in initialization mode builds the simulation early; a later parameter
    change must be honoured."""
    s, fresh = session(unzipped), session(unzipped)
    try:
        s.fmu.setupExperiment(startTime=0.0)
        s.fmu.enterInitializationMode()
        set_values(s, dict(FAST, dt=1e-4))
        before = s.fmu.getReal([vr(s, "corner_1")])[0]
        set_values(s, {"initial_load": 8600.0})
        after = s.fmu.getReal([vr(s, "corner_1")])[0]
        s.fmu.exitInitializationMode()
        assert after != before
        fresh.initialize(dict(FAST, dt=1e-4, initial_load=8600.0))
        assert bits(s) == bits(fresh)
        assert drive(s, 0, 5) == drive(fresh, 0, 5)
    finally:
        s.free()
        fresh.free()


def test_simulate_fmu_runs(fmu_path):
    """fmpy's simulate_fmu: it extracts and loads a fresh copy of the FMU, runs and unloads it. On
    FAST's coarse mesh (issue 54: the default mesh's plate, built again in the fresh library, was
    14 s of the sanitizer stage's CPU; what is checked here is fmpy's path through the FMI layer)."""
    from fmpy import simulate_fmu

    result = simulate_fmu(
        str(fmu_path),
        stop_time=0.01,
        output_interval=1e-3,
        start_values={"dt": 1e-4, "initial_load": 8600.0, **FAST},
    )
    assert len(result) == 11
    assert result["corner_1"][0] != 0.0 and all(math.isfinite(x) for x in result["energy"])


# ---------------------------------------------------------------------------------------------
# Reproducibility: FMU states, reset, independent instances


@pytest.mark.parametrize("config", sorted(CONFIGS))
def test_fmu_state_get_set_and_serialize_are_bit_identical(unzipped, config):
    s = session(unzipped)
    other = session(unzipped)
    try:
        s.initialize(CONFIGS[config])
        drive(s, 0, 10, record=False)
        state = s.fmu.getFMUstate()
        at_t1 = bits(s)
        first = drive(s, 10, 40)
        assert len(set(first)) > 1

        s.fmu.setFMUstate(state)
        assert bits(s) == at_t1
        assert s.fmu.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(10 * H, rel=1e-12)
        assert drive(s, 10, 40) == first

        blob = s.fmu.serializeFMUstate(state)
        s.fmu.freeFMUstate(state)
        restored = s.fmu.deSerializeFMUstate(blob)
        s.fmu.setFMUstate(restored)
        assert bits(s) == at_t1
        assert drive(s, 10, 40) == first
        s.fmu.freeFMUstate(restored)

        # a second instance, never initialized, continues from the serialized state
        restored = other.fmu.deSerializeFMUstate(blob)
        other.fmu.setFMUstate(restored)
        other.fmu.freeFMUstate(restored)
        assert bits(other) == at_t1
        assert drive(other, 10, 40) == first
        assert s.errors() == [] and other.errors() == []
    finally:
        s.free()
        other.free()


def test_fmu_state_restores_from_error_and_before_initialization(unzipped):
    s, fresh = session(unzipped), session(unzipped)
    try:
        expected = full_run(fresh, SCENE, steps=5)
        early = s.fmu.getFMUstate()  # state "instantiated", default parameters
        s.initialize(SCENE)
        drive(s, 0, 3, record=False)
        good = s.fmu.getFMUstate()
        reference = drive(s, 3, 8)
        s.fmu.setFMUstate(good)
        with pytest.raises(FMICallException):
            s.fmu.setReal([vr(s, "load")], [float("nan")])
        with pytest.raises(FMICallException):
            s.fmu.doStep(3 * H, H)  # illegal in state error
        s.fmu.setFMUstate(good)  # back from the error state
        assert drive(s, 3, 8) == reference
        s.fmu.setFMUstate(early)  # back before initialization: parameters can be set again
        assert full_run(s, SCENE, steps=5) == expected
        s.fmu.freeFMUstate(early)
        s.fmu.freeFMUstate(good)
    finally:
        s.free()
        fresh.free()


@pytest.mark.parametrize("config", configs_sparing_the_sanitizer("test_reset_reproduces_a_fresh_instance"))
def test_reset_reproduces_a_fresh_instance(unzipped, config):
    scene = CONFIGS[config]
    s = session(unzipped)
    fresh = session(unzipped)
    try:
        first = full_run(s, scene)
        s.fmu.terminate()
        s.fmu.reset()
        second = full_run(s, scene)
        # reset from the error state
        with pytest.raises(FMICallException):
            s.fmu.doStep(1.0, H)
        s.fmu.reset()
        third = full_run(s, scene)
        assert first == second == third == full_run(fresh, scene)
    finally:
        s.free()
        fresh.free()


def test_instances_are_independent_interleaved(unzipped):
    a, b = session(unzipped, "a"), session(unzipped, "b")
    ref_a, ref_b = session(unzipped, "ra"), session(unzipped, "rb")
    scene = dict(SCENE, **FAST)
    other = dict(scene, initial_load=-6000.0, beta=0.3)
    try:
        expected_a = full_run(ref_a, scene)
        expected_b = full_run(ref_b, other)
        a.initialize(scene)
        b.initialize(other)
        trace_a, trace_b = [bits(a)], [bits(b)]
        for k in range(30):
            trace_a += drive(a, k, k + 1)
            trace_b += drive(b, k, k + 1)
        assert trace_a == expected_a and trace_b == expected_b
        assert expected_a != expected_b
    finally:
        for s in (a, b, ref_a, ref_b):
            s.free()


@pytest.mark.parametrize("config", configs_sparing_the_sanitizer("test_two_threads_match_sequential_runs"))
def test_two_threads_match_sequential_runs(unzipped, config):
    """Every engine (sparse factor, complete modal basis, reduced modes) and both elements:
    two instances stepped at once in two threads give what they give one after the other."""
    # beta is the Newmark law's own (the condensed laws refuse it): the second scene differs by the load there.
    newmark = CONFIGS[config].get("time_scheme", 1) == 1
    other = dict(CONFIGS[config], initial_load=-6000.0, **({"beta": 0.3} if newmark else {}))
    scenes = {"a": CONFIGS[config], "b": other}

    def run(name):
        s = session(unzipped, name)
        try:
            return full_run(s, scenes[name], steps=100)
        finally:
            s.free()

    sequential = {name: run(name) for name in scenes}
    results, spans, failures = {}, {}, []
    barrier = threading.Barrier(len(scenes))

    def worker(name):
        try:
            barrier.wait()
            begin = time.perf_counter()
            results[name] = run(name)
            spans[name] = (begin, time.perf_counter())
        except Exception as e:  # reported below
            failures.append(repr(e))

    threads = [threading.Thread(target=worker, args=(name,)) for name in scenes]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert failures == []
    assert results == sequential
    assert sequential["a"] != sequential["b"]
    # the two runs did overlap in time (ctypes releases the GIL inside the FMU calls)
    (a0, a1), (b0, b1) = spans["a"], spans["b"]
    assert max(a0, b0) < min(a1, b1)


if __name__ == "__main__" and len(sys.argv) == 4 and sys.argv[1] == "--child":
    _child_main(sys.argv[2], sys.argv[3])
if __name__ == "__main__" and len(sys.argv) == 3 and sys.argv[1] == "--serve":
    _serve(sys.argv[2])
