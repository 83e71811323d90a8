"""OMSimulator (OpenModelica's FMI/SSP master, built on demand by scripts/build-omsimulator.sh) runs
the SSPs of examples/masters/ with the FMI 2.0 PlateImpact.fmu and gets fmpy's outputs bit for bit
(docs/masters.md).

Each SSP is the example's SystemStructure.ssd zipped with the FMUs as built:
  - the §5.2 release (omsimulator_release.ssd: the plate alone, its start values nx = 16,
    initial_load = 8600 Pa, obstacle_upper_enabled = false in the SSD, the fixed-step master's
    annotation at 1e-3 s), 0.1 s (the first impact near 0.068 s);
  - the default scene (omsimulator_default_scene.ssd: SineSweep.fmu gives the clamp
    0.09 sin(2 pi 10 t), the master steps 1e-4 s), 0.06 s (the first impact near 0.05 s);
run by its command line, against fmpy.simulate_fmu fed the same input values at the same points
(the sweep's outputs, read through fmpy from SineSweep.fmu). The arithmetic is the same, so the
tolerance is zero.

Where OMSimulator is not built the test is skipped, saying how to build it.
"""

import csv
import os
import shutil
import subprocess
import zipfile
from pathlib import Path

import fmpy
import numpy as np
import pytest

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples" / "masters"
OMSIMULATOR = Path(
    os.environ.get("PLATEIMPACT_OMSIMULATOR", REPO / ".deps" / "omsimulator" / "install" / "bin" / "OMSimulator")
)
RELEASE = {"nx": 16, "initial_load": 8600.0, "obstacle_upper_enabled": False}
OUTPUTS = ["corner_1", "energy"]

pytestmark = pytest.mark.skipif(
    not os.access(OMSIMULATOR, os.X_OK),
    reason=f"OMSimulator is not built ({OMSIMULATOR}): OMSIMULATOR_SRC=<clone> OMSIMULATOR_3RDPARTY_SRC=<clone> "
    "bash scripts/build-omsimulator.sh (docs/masters.md)",
)


def ssp(ssd, fmus, target):
    """The SSP file: ssd as SystemStructure.ssd, each FMU under resources/."""
    with zipfile.ZipFile(target, "w") as archive:
        archive.write(EXAMPLES / ssd, "SystemStructure.ssd")
        for fmu in fmus:
            archive.write(fmu, f"resources/{fmu.name}")
    return target


def omsimulator(ssp_file, stop, tmp_path):
    """Run the CLI; its result CSV as {column: array}, one row per communication point (it writes
    each point twice: the last row of each time is kept)."""
    result = tmp_path / f"{ssp_file.stem}.csv"
    command = [str(OMSIMULATOR), str(ssp_file), f"--stopTime={stop}", f"--resultFile={result}"]
    done = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and result.is_file(), done.stdout[-3000:] + done.stderr[-3000:]
    with result.open() as f:
        rows = list(csv.reader(f))
    names, values = rows[0], np.array([[float(x) for x in row] for row in rows[1:]])
    last = {}
    for row in values:
        last[row[0]] = row
    table = np.array([last[t] for t in sorted(last)])
    return {name.split(".")[-1]: table[:, i] for i, name in enumerate(names)}


def test_omsimulator_release_is_fmpys_bit_for_bit(fmu_path, tmp_path):
    assert fmu_path.is_file(), f"FMU not built: {fmu_path} (build it or set PLATEIMPACT_FMU)"
    theirs = omsimulator(ssp("omsimulator_release.ssd", [fmu_path], tmp_path / "release.ssp"), 0.1, tmp_path)
    ours = fmpy.simulate_fmu(str(fmu_path), stop_time=0.1, output_interval=1e-3, start_values=RELEASE, output=OUTPUTS)
    assert ours["corner_1"].min() <= -0.1 + 1e-12, "the release did not reach the obstacle"
    assert np.allclose(theirs["time"], ours["time"], rtol=0, atol=1e-12)
    for name in OUTPUTS:
        assert np.array_equal(theirs[name], ours[name]), (name, np.abs(theirs[name] - ours[name]).max())


def test_omsimulator_default_scene_is_fmpys_bit_for_bit(fmu_path, tmp_path):
    sweep = fmu_path.parent / "SineSweep.fmu"
    assert fmu_path.is_file() and sweep.is_file(), f"FMUs not built: {fmu_path}, {sweep}"
    stop, h = 0.06, 1e-4
    theirs = omsimulator(
        ssp("omsimulator_default_scene.ssd", [sweep, fmu_path], tmp_path / "default.ssp"), stop, tmp_path
    )
    # the sweep's output at every communication point, as OMSimulator passes it to the plate
    values = fmpy.simulate_fmu(
        str(sweep),
        stop_time=stop,
        output_interval=h,
        start_values={"amplitude": 0.09, "start_frequency": 10.0, "end_frequency": 10.0, "ramp_time": 0.0},
        output=["base_displacement"],
    )
    signal = np.array(
        list(zip(values["time"], values["base_displacement"])), dtype=[("time", float), ("base_displacement", float)]
    )
    ours = fmpy.simulate_fmu(str(fmu_path), stop_time=stop, output_interval=h, input=signal, output=OUTPUTS)
    assert np.abs(ours["corner_1"]).max() >= 0.1 - 1e-12, "no impact within the horizon"
    assert np.allclose(theirs["time"], ours["time"], rtol=0, atol=1e-12)
    for name in OUTPUTS:
        assert np.array_equal(theirs[name], ours[name]), (name, np.abs(theirs[name] - ours[name]).max())


def test_the_fmi3_fmu_is_refused_in_omsimulator(fmu_path, tmp_path):
    """docs/masters.md says: take the FMI 2.0 FMU. This keeps that sentence true: when OMSimulator
    runs the FMI 3.0 release, the page must change."""
    plate = fmu_path.parent / "fmi3" / "PlateImpact.fmu"
    assert plate.is_file(), f"FMU not built: {plate}"
    folder = tmp_path / "fmi3"
    folder.mkdir()
    shutil.copy(plate, folder / "PlateImpact.fmu")
    target = ssp("omsimulator_release.ssd", [folder / "PlateImpact.fmu"], tmp_path / "release3.ssp")
    result = tmp_path / "release3.csv"
    done = subprocess.run(
        [str(OMSIMULATOR), str(target), "--stopTime=0.01", f"--resultFile={result}"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode != 0 or "error" in (done.stdout + done.stderr).lower(), done.stdout[-2000:]
