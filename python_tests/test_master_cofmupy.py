"""CoFmuPy (pip `cofmupy` 1.0.0, a JSON-configured co-simulation master) runs the configurations of
examples/masters/ on PlateImpact.fmu and gets fmpy's outputs bit for bit (docs/masters.md).

As released, CoFmuPy's FMI 2.0 handler reads every output with fmi2GetReal and sets every start
value with fmi2SetReal: the plate's first step fails on the Integer output contact_vertices. The
runner examples/masters/cofmupy_run.py makes the handler type-aware (`type_aware()`); this test
runs it, with that fix, in CoFmuPy's own interpreter:
  - the default scene from a CSV source (cofmupy_default_scene.json), 0.1 s in steps of 1e-4 s
    (impacts from 0.05 s on), the CSV written at CoFmuPy's own communication times;
  - the §5.2 release (cofmupy_release.json: nx = 16, an Integer; obstacle_upper_enabled = false, a
    Boolean), 0.1 s in steps of 1e-3 s (the first impact near 0.068 s);
and compares every step's corner_1 and energy with fmpy.simulate_fmu fed the same values. The
arithmetic is the same (the same binary, the same calls, the same input bits), so the tolerance
is zero.

CoFmuPy pins fmpy 0.3.20 (the suite's venv has 0.3.32, with which CoFmuPy's master fails on the
model description's step size), so it has a venv of its own, made once:
    python3 -m venv .deps/cofmupy && .deps/cofmupy/bin/pip install cofmupy==1.0.0
(or PLATEIMPACT_COFMUPY_PYTHON names its interpreter). Without it the test is skipped, saying so.
"""

import csv
import json
import os
import subprocess
from pathlib import Path

import fmpy
import numpy as np
import pytest

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples" / "masters"
PYTHON = os.environ.get("PLATEIMPACT_COFMUPY_PYTHON", str(REPO / ".deps" / "cofmupy" / "bin" / "python"))
DEFAULT_STEP, RELEASE_STEP, STOP = 1e-4, 1e-3, 0.1
RELEASE = {"nx": 16, "initial_load": 8600.0, "obstacle_upper_enabled": False}

pytestmark = pytest.mark.skipif(
    not os.access(PYTHON, os.X_OK),
    reason=f"CoFmuPy's venv is not there ({PYTHON}): python3 -m venv .deps/cofmupy && "
    ".deps/cofmupy/bin/pip install cofmupy==1.0.0 (docs/masters.md)",
)


def configuration(name, tmp_path, fmu_path):
    """The example configuration with the FMU as built and every file below tmp_path."""
    config = json.loads((EXAMPLES / name).read_text())
    config["fmus"][0]["path"] = str(fmu_path)
    for connection in config["connections"]:
        if connection["source"]["type"] == "csv":
            connection["source"]["path"] = str(tmp_path / "base_displacement.csv")
    storage = config["data_storages"][0]["config"]
    storage["path"] = str(tmp_path / Path(storage["path"]).parent.name / Path(storage["path"]).name)
    target = tmp_path / name
    target.write_text(json.dumps(config))
    return target, Path(storage["path"])


def stored(path):
    """The storage's rows: time (each step's end, on CoFmuPy's clock), corner_1, energy."""
    with path.open() as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in ("time", "corner_1", "energy")}


def test_cofmupy_with_type_aware_handler_matches_fmpy_bit_for_bit(fmu_path, tmp_path):
    assert fmu_path.is_file(), f"FMU not built: {fmu_path} (build it or set PLATEIMPACT_FMU)"
    default_config, default_csv = configuration("cofmupy_default_scene.json", tmp_path, fmu_path)
    release_config, release_csv = configuration("cofmupy_release.json", tmp_path, fmu_path)
    base_csv = tmp_path / "base_displacement.csv"
    command = [PYTHON, str(EXAMPLES / "cofmupy_run.py"), str(default_config), str(DEFAULT_STEP), str(STOP)]
    command += [str(release_config), str(RELEASE_STEP), str(STOP), "--write-base", str(base_csv)]
    done = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-4000:]

    # fmpy on the same input values: the CSV's samples at k h (its times are CoFmuPy's clock)
    rows = np.loadtxt(base_csv, delimiter=",", skiprows=1)
    n = round(STOP / DEFAULT_STEP)
    signal = np.array(
        list(zip(np.arange(n + 1) * DEFAULT_STEP, rows[: n + 1, 1])),
        dtype=[("time", float), ("base_displacement", float)],
    )
    ours = fmpy.simulate_fmu(
        str(fmu_path), stop_time=STOP, output_interval=DEFAULT_STEP, input=signal, output=["corner_1", "energy"]
    )
    theirs = stored(default_csv)
    assert len(theirs["time"]) == n
    assert np.allclose(theirs["time"], ours["time"][1:], rtol=0, atol=1e-12)  # the step's end, CoFmuPy's clock
    assert np.abs(ours["corner_1"]).max() >= 0.1 - 1e-12, "no impact within the horizon"
    for name in ("corner_1", "energy"):
        assert np.array_equal(theirs[name], ours[name][1:]), (name, np.abs(theirs[name] - ours[name][1:]).max())

    ours = fmpy.simulate_fmu(
        str(fmu_path), stop_time=STOP, output_interval=RELEASE_STEP, start_values=RELEASE, output=["corner_1", "energy"]
    )
    theirs = stored(release_csv)
    assert len(theirs["time"]) == round(STOP / RELEASE_STEP)
    assert ours["corner_1"].min() <= -0.1 + 1e-12, "the release did not reach the obstacle"
    for name in ("corner_1", "energy"):
        assert np.array_equal(theirs[name], ours[name][1:]), (name, np.abs(theirs[name] - ours[name][1:]).max())
