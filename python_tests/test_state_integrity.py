"""Integrity of saved FMU states: a serialized state carries an XXH64 checksum of its bytes
(fmu/StateFormat.h), verified before anything is decoded. Every single-bit flip of a small
state, and 10 000 random single-bit flips of the default plate's state, must be refused with a
message naming what failed; the instance stays usable (a good state restores it and the run
continues bit-identically)."""

import random

import pytest
from fmpy.fmi1 import FMICallException
from plate_fmu import PlateRun
from state_bytes import HEADER, checksum

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
