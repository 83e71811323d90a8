"""The FMU's cache of discretizations (solver/plate/DiscretizationCache.h, README "Performance"):
instances of the same plate in one process share its modal basis, and the shared plate gives the
golden output bit for bit, as one built alone does (PLATEIMPACT_CACHE_MB=0: the cache off).

The CPU it saves is measured, not asserted: `tools/instance_setup.py` prints the first and the
second instance's ExitInitializationMode CPU and their ratio (docs/contributing.md)."""

from __future__ import annotations

import re

import pytest
from test_golden import QEMU_WINDOW, STEP, golden_inputs, mismatches, read_golden

from plateimpact import PlateImpactFMU

pytestmark = pytest.mark.sanitizer

SHARED = re.compile(r"discretization: (\d+) of (\d+) parts shared from the process's cache")


def run(fmu_path, inputs, steps):
    """The outputs at every communication point, and the instance's cache line (shared, parts)."""
    lines = []
    rows = []
    with PlateImpactFMU(fmu_path, logger=lambda status, category, message: lines.append(message)) as plate:
        rows.append({"time": 0.0, **plate.outputs()})
        for k in range(steps):
            plate.step(STEP, base=inputs[k])
            rows.append({"time": (k + 1) * STEP, **plate.outputs()})
    found = [SHARED.search(m) for m in lines if SHARED.search(m)]
    assert len(found) == 1, lines
    return rows, (int(found[0].group(1)), int(found[0].group(2)))


def test_a_shared_plate_gives_the_golden_output_bit_for_bit(fmu_path, monkeypatch):
    golden = read_golden()[: QEMU_WINDOW + 1]  # past the first impacts of both obstacles
    inputs = golden_inputs(golden)
    monkeypatch.setenv("PLATEIMPACT_CACHE_MB", "0")  # off (the FMU reads it at every lookup)
    alone, (shared, parts) = run(fmu_path, inputs, QEMU_WINDOW)
    assert shared == 0 and parts >= 3  # off: every part built by the instance
    monkeypatch.delenv("PLATEIMPACT_CACHE_MB")  # on, the default budget
    run(fmu_path, inputs, 1)  # builds the plate, or shares it with an earlier test of this process
    second, (shared, parts) = run(fmu_path, inputs, QEMU_WINDOW)
    assert shared == parts >= 3  # the space, the clamped plate, the modal basis
    assert mismatches(golden, alone) == []
    assert mismatches(golden, second) == []


def test_a_plate_built_with_one_obstacle_is_not_shared_with_one_that_has_both(fmu_path):
    """Each contact row knows which obstacles hold it (docs/theory.md §25): a plate discretized with
    the upper obstacle off must not be served to an instance with both (its rows would ignore the
    upper one). After the one-obstacle instance, the golden window of the default scene, with both
    obstacles, still matches the golden output bit for bit."""
    golden = read_golden()[: QEMU_WINDOW + 1]
    inputs = golden_inputs(golden)
    with PlateImpactFMU(fmu_path, obstacle_upper_enabled=False) as plate:
        plate.step(STEP, base=inputs[0])
    rows, _ = run(fmu_path, inputs, QEMU_WINDOW)
    assert not mismatches(golden, rows)
    assert rows[-1]["contact_onsets_upper"] > 0  # the window reaches the upper obstacle
