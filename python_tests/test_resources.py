"""Resources (issue 23): every instance says what it will cost before it spends it, and refuses
what exceeds memory_limit before allocating it.

Each measurement of memory runs in a child process (a fresh interpreter with fmpy loaded), so
that the peak resident set size (VmHWM) belongs to that one instance: the child reads its
resident set just before fmi2ExitInitializationMode and its peak after it; the difference is
what the initialization allocated."""

import json
import math
import re
import subprocess
import sys
import textwrap
import time

import pytest
from fmpy.fmi1 import FMICallException

from plateimpact import PlateImpactFMU

# The child: instantiate with logging on, set the parameters, time fmi2ExitInitializationMode
# and measure memory around it; optionally under an address-space limit (MB above the current
# virtual size) to provoke an allocation failure. Prints one JSON line.
CHILD = textwrap.dedent(
    """
    import json, resource, sys, time
    from fmpy.fmi1 import FMICallException
    from plateimpact import PlateImpactFMU

    def status(key):
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1])  # kB

    fmu_path, parameters, headroom_mb = sys.argv[1], json.loads(sys.argv[2]), float(sys.argv[3])
    plate = PlateImpactFMU(fmu_path, logger=lambda *entry: None, initialize=False)
    plate.fmu.setupExperiment(startTime=0.0)
    plate.fmu.enterInitializationMode()
    for name, value in parameters.items():
        plate.set(name, value)
    if headroom_mb > 0:
        limit = (status("VmSize") + int(headroom_mb * 1024)) * 1024
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    rss_before = status("VmRSS")
    t0 = time.monotonic()
    try:
        plate.fmu.exitInitializationMode()
        ok = True
    except FMICallException:
        ok = False
    wall = time.monotonic() - t0
    peak = status("VmHWM")  # this image's peak: ru_maxrss would carry the parent's across exec
    plate.fmu.freeInstance()  # after fmi2Error too
    plate.fmu = None
    print(json.dumps({"ok": ok, "wall": wall, "extra_mb": (peak - rss_before) / 1024.0,
                      "log": [[s, c, m] for s, c, m in plate.log]}))
    """
)


def run_child(fmu_path, headroom_mb=0.0, **parameters):
    done = subprocess.run(
        [sys.executable, "-c", CHILD, str(fmu_path), json.dumps(parameters), str(headroom_mb)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr  # a crash or abort is a failure in itself
    return json.loads(done.stdout.strip().splitlines()[-1])


def estimate_of(log):
    """The estimated peak (MB) and initialization time (s) of the logInfo estimate line."""
    lines = [m for _, c, m in log if c == "logInfo" and "resource estimate:" in m]
    assert len(lines) == 1, log
    peak = float(re.search(r"memory peak (\d+) MB", lines[0]).group(1))
    init = float(re.search(r"initialization ~([0-9.e+-]+) s", lines[0]).group(1))
    return peak, init


def test_every_instance_logs_its_estimate_and_its_end(fmu_path):
    log = []
    with PlateImpactFMU(fmu_path, logger=lambda *entry: log.append(entry)):
        pass
    info = [m for _, c, m in log if c == "logInfo"]
    assert any("resource estimate: engine modal-complete, 734 free dofs" in m for m in info), info
    assert any(m.startswith("fmi2ExitInitializationMode: initialized in") for m in info), info


# The estimate counts what each phase allocates (element bases, the assembly's triplets and
# matrices, the clamped matrices, both sparse factors, the dense modal basis); what it leaves
# out is the allocator's and CHOLMOD's slack. Over the scaling table of docs/performance.md it
# is within 0.75-1.3 of the measured peak; asserted here within a factor of 1.5 either way.
FACTOR = 1.5


@pytest.mark.parametrize(
    "parameters",
    [
        {"nx": 56, "ny": 20},
        {"nx": 112, "ny": 40, "element": "fvs"},
        {"nx": 100, "ny": 36},
    ],
    ids=["argyris-56x20", "fvs-112x40", "argyris-100x36"],
)
def test_estimate_within_a_factor_of_the_measured_peak(fmu_path, parameters):
    child = run_child(fmu_path, **parameters)
    assert child["ok"], child["log"]
    estimated, init = estimate_of(child["log"])
    measured = child["extra_mb"]
    assert measured > 40.0  # large enough that the interpreter's own noise does not matter
    assert 1.0 / FACTOR <= estimated / measured <= FACTOR, (estimated, measured)
    steps = [m for _, c, m in child["log"] if c == "logInfo" and "initialization step" in m]
    if init >= 2.0:  # long initializations say what they are doing
        assert any("factorization of A" in m for m in steps), child["log"]
    else:
        assert steps == []


def test_400x400_is_refused_at_once_with_the_estimate_the_limit_and_the_parameter(fmu_path):
    child = run_child(fmu_path, nx=400, ny=400)
    assert not child["ok"]
    errors = [m for s, _, m in child["log"] if s >= 3]
    assert len(errors) == 1, child["log"]
    message = errors[0]
    assert message.startswith("fmi2ExitInitializationMode: refused before allocating")
    needed = float(re.search(r"needs an estimated (\d+) MB", message).group(1))
    assert needed > 2048.0
    assert "memory_limit = 2048 MB" in message and "raise memory_limit" in message
    # Refused before anything large was allocated, in well under the 8.7 minutes the issue saw
    # (a behavioural bound, not a benchmark: the prediction is O(1)).
    assert child["extra_mb"] < 50.0
    assert child["wall"] < 5.0


def test_the_limit_is_the_estimate(fmu_path):
    # A moderate mesh against a lowered budget: just above its estimate it initializes, just
    # below it is refused, naming both numbers.
    parameters = {"nx": 40, "ny": 14}
    with PlateImpactFMU(fmu_path, logger=lambda *entry: None, memory_limit=0, **parameters) as plate:
        estimated, _ = estimate_of(plate.log)
    above = math.ceil(estimated) + 1
    with PlateImpactFMU(fmu_path, memory_limit=above, **parameters) as plate:
        assert plate.step(1e-4)["time"] == pytest.approx(1e-4)
    below = estimated - 2
    with pytest.raises(FMICallException):
        PlateImpactFMU(fmu_path, memory_limit=below, **parameters)
    t0 = time.monotonic()
    plate = PlateImpactFMU(fmu_path, memory_limit=below, initialize=False, **parameters)
    try:
        plate.fmu.setupExperiment(startTime=0.0)
        plate.fmu.enterInitializationMode()
        for name, value in dict(parameters, memory_limit=below).items():
            plate.set(name, value)
        with pytest.raises(FMICallException):
            plate.fmu.exitInitializationMode()
        assert time.monotonic() - t0 < 5.0
        (message,) = plate.errors()
        assert f"memory_limit = {below:g} MB" in message and "raise memory_limit" in message
    finally:
        plate.close()


def test_an_allocation_failure_is_an_fmi2_error_and_the_instance_is_freed(fmu_path):
    # No budget, and an address space 150 MB larger than the child's: the 112 x 40 Argyris
    # mesh (about 340 MB) fails to allocate; std::bad_alloc becomes fmi2Error with a message.
    child = run_child(fmu_path, headroom_mb=150.0, nx=112, ny=40, memory_limit=0)
    assert not child["ok"]
    errors = [m for s, _, m in child["log"] if s >= 3]
    assert len(errors) == 1, child["log"]
    assert "out of memory while building the simulation (std::bad_alloc) after resource estimate" in errors[0]
