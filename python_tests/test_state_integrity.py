"""Integrity of saved FMU states: a serialized state carries an XXH64 checksum of its bytes
(fmu/core/StateFormat.h), verified before anything is decoded. Every single-bit flip of a small
state, and 10 000 random single-bit flips of the default plate's state, must be refused with a
message naming what failed; the instance stays usable (a good state restores it and the run
continues bit-identically)."""

import math
import random

import pytest
from fmpy.fmi1 import FMICallException
from plate_fmu import PlateRun
from state_bytes import HEADER, checksum

# The sanitizer stage of test.sh runs this file against the ASan+UBSan build (pytest.ini).
pytestmark = pytest.mark.sanitizer

TINY = dict(nx=1, ny=1, element="fvs", dt=1e-4)
WHAT = ("checksum", "magic", "GUID", "format version", "wrong size", "header")


def saved_state(run, steps=3):
    for _ in range(steps):
        run.step(run_h(run), base=0.01)
    state = run.fmu.getFMUstate()
    blob = bytes(run.fmu.serializeFMUstate(state))
    run.fmu.freeFMUstate(state)
    return blob


def run_h(run):
    return 10 * run.fmu.getReal([run.vars["dt"].valueReference])[0]


def refused(run, blob):
    before = len(run.log)
    try:
        state = run.fmu.deSerializeFMUstate(blob)
    except FMICallException:
        messages = " ".join(m for _, _, m in run.log[before:])
        assert any(w in messages for w in WHAT), messages
        return True
    run.fmu.freeFMUstate(state)
    return False


def flipped(blob, bit):
    data = bytearray(blob)
    data[bit // 8] ^= 1 << (bit % 8)
    return bytes(data)


def outputs_after(run, blob, steps=3):
    state = run.fmu.deSerializeFMUstate(blob)
    run.fmu.setFMUstate(state)
    run.fmu.freeFMUstate(state)
    return [run.step(run_h(run), base=0.01)["corner_1"] for _ in range(steps)]


def test_every_single_bit_flip_of_a_small_state_is_refused(fmu_path):
    with PlateRun(fmu_path, **TINY) as run:
        blob = saved_state(run)
        assert checksum(blob) == int.from_bytes(blob[72:80], "little")  # the layout the tests know
        t = run.time
        expected = [run.step(run_h(run), base=0.01)["corner_1"] for _ in range(3)]
        accepted = [bit for bit in range(8 * len(blob)) if not refused(run, flipped(blob, bit))]
        assert accepted == [], f"{len(accepted)} of {8 * len(blob)} flipped bits accepted, e.g. {accepted[:5]}"
        run.time = t  # the good state still restores the instance, after all those errors
        assert outputs_after(run, blob) == expected
    print(f"{8 * len(blob)} single-bit flips of a {len(blob)}-byte state: all refused")


def test_random_bit_flips_of_the_default_state_are_refused(fmu_path):
    rng = random.Random(20261123)
    with PlateRun(fmu_path) as run:
        blob = saved_state(run, steps=2)
        bits = rng.sample(range(8 * len(blob)), 10_000)
        accepted = [bit for bit in bits if not refused(run, flipped(blob, bit))]
        assert accepted == [], accepted[:5]
        payload = [bit for bit in bits if bit >= 8 * HEADER]
        assert len(payload) > 9000  # most flips hit the values, not only the header
    print(f"10000 random single-bit flips of a {len(blob)}-byte state: all refused")


@pytest.mark.parametrize("damage", ["truncated", "zeros", "empty"])
def test_other_damage_is_refused(fmu_path, damage):
    with PlateRun(fmu_path, **TINY) as run:
        blob = saved_state(run)
        bad = {"truncated": blob[: len(blob) // 2], "zeros": bytes(len(blob)), "empty": b""}[damage]
        assert refused(run, bad)


@pytest.mark.parametrize("field, offset", [("z", 0), ("qp_iterations_max", 13)])
def test_a_state_the_model_refuses_leaves_the_instance_as_it_was(fmu_path, field, offset):
    """A deliberate edit (checksum repaired) that puts NaN into the simulation's part of a state:
    the value table accepts it, the model refuses it at fmi2SetFMUstate with a clear error (a NaN
    count was cast to int before — undefined behaviour found by fuzz/deserialize_state.cpp), and
    the instance is left as it was: a good state still continues bit-identically."""
    import struct

    from state_bytes import with_checksum

    with PlateRun(fmu_path, **TINY) as run:
        blob = saved_state(run)
        values = struct.unpack(f"{(len(blob) - HEADER) // 8}d", blob[HEADER:])
        # The model's part: 6 inputs x (5 + 9 history), the clamp's position and velocity, the probes'
        # count and places (1 + 2 x 4: the FMI 2.0 slots), then the simulation flag and base; the
        # scheme's state starts with 5 vectors of n.
        simulation = 2 + sum(1 for v in run.md.modelVariables if v.causality != "output") + 6 * 14 + 2 + 9 + 2
        n = int(values[simulation + 1])
        index = simulation + 3 + 5 * n + offset
        patched = list(values)
        patched[index] = float("nan")
        bad = with_checksum(blob[:HEADER] + struct.pack(f"{len(patched)}d", *patched))
        state = run.fmu.deSerializeFMUstate(bad)
        before = len(run.log)
        with pytest.raises(FMICallException):
            run.fmu.setFMUstate(state)
        run.fmu.freeFMUstate(state)
        assert any("corrupt state" in m for _, _, m in run.log[before:]), run.log[before:]
        t = run.time
        run.time = t
        good = outputs_after(run, blob)
        assert all(map(math.isfinite, good))
    with PlateRun(fmu_path, **TINY) as fresh:
        saved_state(fresh)
        fresh.time = t
        assert outputs_after(fresh, blob) == good  # the same continuation as a fresh instance's


@pytest.mark.parametrize("written_on, accepted", [("aarch64-linux", False), ("x86_64-windows", True)])
def test_a_state_of_another_architecture_is_refused_by_name(fmu_path, written_on, accepted):
    """The header names the platform that wrote a state (bytes 80..95). A state of another CPU
    architecture is refused with a message naming both platforms (a run continued from it would not
    be the run it came from: docs/theory.md §20); one of the same architecture on another OS
    (x86_64-windows computes the bits x86_64-linux does) is taken and continues bit for bit. Here the
    platform field is patched (checksum repaired); python_tests/test_experiments_platforms.py
    restores a real linux state with the aarch64 and x86_64-windows binaries."""
    from state_bytes import PLATFORM, with_checksum

    with PlateRun(fmu_path, **TINY) as run:
        blob = saved_state(run)
        assert blob[PLATFORM].rstrip(b"\0") == b"x86_64-linux"  # this suite runs on x86-64 Linux
        t = run.time
        expected = [run.step(run_h(run), base=0.01)["corner_1"] for _ in range(3)]
        field = written_on.encode().ljust(PLATFORM.stop - PLATFORM.start, b"\0")
        other = with_checksum(blob[: PLATFORM.start] + field + blob[PLATFORM.stop :])
        run.time = t
        if accepted:
            assert outputs_after(run, other) == expected
            return
        before = len(run.log)
        with pytest.raises(FMICallException):
            run.fmu.deSerializeFMUstate(other)
        message = " ".join(m for _, _, m in run.log[before:])
        assert "saved by the aarch64-linux binary" in message and "this is the x86_64-linux binary" in message, message
        assert outputs_after(run, blob) == expected  # the instance is unharmed
