"""fmu-manipulation-toolbox (pip, requirements.txt) wraps PlateImpact.fmu in a container FMU from
the descriptions of examples/masters/ (FMI 2.0, and FMI 3.0 with the two arrays dropped: the
toolbox cannot size an array by a structural parameter), and the container, stepped by fmpy,
gives the plate's own outputs bit for bit (docs/masters.md).

Each container runs the default scene for 0.06 s (base values every 1e-4 s, the container's own
step; the first impact near 0.05 s) and the §5.2 release for 0.1 s (the parameters set on the
container as plateimpact.<name>, communicated every 1e-3 s: ten container steps, as the plate
alone takes them on its grid). The container's binary only forwards the same calls with the same
values, so the tolerance is zero. Both containers are compared with the FMI 2.0 plate alone
(the FMI 3.0 plate gives the same bits: python_tests/test_fmi3.py).
"""

import shutil
from pathlib import Path

import fmpy
import numpy as np
import pytest

from plateimpact.driver import unzipped

assembly = pytest.importorskip(
    "fmu_manipulation_toolbox.assembly", reason="fmu-manipulation-toolbox is not installed (requirements.txt)"
)

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples" / "masters"
H = 1e-4  # the container's step and the default scene's communication step
DEFAULT_STOP, RELEASE_STOP, RELEASE_STEP = 0.06, 0.1, 1e-3
RELEASE = {"nx": 16, "initial_load": 8600.0, "obstacle_upper_enabled": False}
OUTPUTS = ["corner_1", "energy"]


def container(plate, description, fmi_version, tmp_path):
    folder = tmp_path / f"fmi{fmi_version}"
    folder.mkdir()
    shutil.copy(plate, folder / "PlateImpact.fmu")
    shutil.copy(EXAMPLES / description, folder / description)
    # FMI 3.0: the parameters exposed by name (container_plate_fmi3.csv): the toolbox cannot size the
    # parameter arrays probe_x, probe_y that -auto-parameter would expose too.
    auto = fmi_version == 2
    built = assembly.Assembly(description, default_step_size=H, fmu_directory=folder, default_auto_parameter=auto)
    built.make_fmu(fmi_version=fmi_version)
    made = folder / Path(description).with_suffix(".fmu").name
    assert made.is_file(), f"no container built from {description}"
    return made


def scenes(fmu, prefix="", shared=False):
    """The default scene and the release through fmpy; shared: on the FMU extracted once per process,
    its library kept loaded (plateimpact.driver.unzipped: both runs build the plate once)."""
    t = np.arange(round(DEFAULT_STOP / H) + 1) * H
    signal = np.array(
        list(zip(t, 0.09 * np.sin(2 * np.pi * 10 * t))), dtype=[("time", float), ("base_displacement", float)]
    )
    where = dict(zip(("filename", "model_description"), unzipped(fmu))) if shared else dict(filename=str(fmu))
    default = fmpy.simulate_fmu(**where, stop_time=DEFAULT_STOP, output_interval=H, input=signal, output=OUTPUTS)
    release = fmpy.simulate_fmu(
        **where,
        stop_time=RELEASE_STOP,
        output_interval=RELEASE_STEP,
        start_values={prefix + name: value for name, value in RELEASE.items()},
        output=OUTPUTS,
    )
    return default, release


@pytest.fixture(scope="module")
def plate_alone(fmu_path):
    assert fmu_path.is_file(), f"FMU not built: {fmu_path} (build it or set PLATEIMPACT_FMU)"
    return scenes(fmu_path, shared=True)


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_container_gives_the_plates_outputs_bit_for_bit(fmu_path, plate_alone, fmi_version, tmp_path):
    plate = fmu_path if fmi_version == 2 else fmu_path.parent / "fmi3" / "PlateImpact.fmu"
    assert plate.is_file(), f"FMU not built: {plate}"
    description = "container_plate.csv" if fmi_version == 2 else "container_plate_fmi3.csv"
    wrapped = container(plate, description, fmi_version, tmp_path)
    assert fmpy.read_model_description(str(wrapped)).fmiVersion == f"{fmi_version}.0"
    theirs, ours = scenes(wrapped, prefix="plateimpact."), plate_alone
    assert np.abs(ours[0]["corner_1"]).max() >= 0.1 - 1e-12, "no impact within the horizon"
    assert ours[1]["corner_1"].min() <= -0.1 + 1e-12, "the release did not reach the obstacle"
    for a, b in zip(theirs, ours):
        assert np.array_equal(a["time"], b["time"])
        for name in OUTPUTS:
            assert np.array_equal(a[name], b[name]), (name, np.abs(a[name] - b[name]).max())
