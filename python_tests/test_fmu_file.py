"""A missing, unreadable or broken FMU is a clear Python error before any master sees it (a
fresh machine once handed libcosim a missing file and died in add_local_slave)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from cosim import run_libcosim, system_execution

from plateimpact import PlateImpactFMU
from plateimpact.fmufile import FMUFileError, fmu_file


def test_missing_fmu_is_named_before_any_master(tmp_path, fmu_path):
    missing = tmp_path / "nowhere" / "PlateImpact.fmu"
    for call in (
        lambda: PlateImpactFMU(missing),
        lambda: run_libcosim(missing, fmu_path, 1e-4, 1e-3),
        lambda: run_libcosim(fmu_path, missing, 1e-4, 1e-3),
        lambda: system_execution({"sweep": fmu_path, "shaker": missing, "plate": fmu_path}, {}, "tlm", h=1e-4),
    ):
        with pytest.raises(FMUFileError, match="FMU not found: .*nowhere"):
            call()


def test_broken_fmu_files_are_refused_with_the_reason(tmp_path):
    not_zip = tmp_path / "text.fmu"
    not_zip.write_text("not an archive")
    with pytest.raises(FMUFileError, match="not a zip archive"):
        fmu_file(not_zip)
    import zipfile

    empty = tmp_path / "empty.fmu"
    with zipfile.ZipFile(empty, "w") as z:
        z.writestr("binaries/readme.txt", "x")
    with pytest.raises(FMUFileError, match="without modelDescription.xml"):
        fmu_file(empty)
    with pytest.raises(FMUFileError, match="not an extracted FMU"):
        fmu_file(tmp_path)


def test_a_built_fmu_passes(fmu_path):
    assert fmu_file(fmu_path) == fmu_path.resolve()


def test_a_missing_demonstration_fmu_names_the_target_that_builds_it(tmp_path):
    """demos/shaker.py after `bash run.sh`: build/SineSweep.fmu is missing and run.sh does not build it;
    the message names the setup target that does (issue 71)."""
    for relative, target in (("SineSweep.fmu", "SineSweepFmu"), ("fmi3/SineSweep.fmu", "SineSweepFmu3")):
        with pytest.raises(FMUFileError) as refused:
            fmu_file(tmp_path / relative)
        assert f"bash scripts/setup.sh {target}" in str(refused.value), refused.value
    with pytest.raises(FMUFileError) as refused:
        fmu_file(tmp_path / "PlateImpact.fmu")
    assert "bash run.sh" in str(refused.value)


def test_the_shaker_demo_says_what_builds_its_fmus():
    """demos/shaker.py's usage said `bash run.sh` builds SineSweep.fmu and Shaker.fmu; run.sh builds the
    run_sh target (CMakeLists.txt: PlateImpact's FMUs and plate_bench), not these (issue 71). Its usage names
    the setup targets that do, which CMake defines (add_fmu(SineSweep ...), add_fmu(Shaker ...))."""
    repo = Path(__file__).resolve().parent.parent
    usage = (repo / "demos" / "shaker.py").read_text().split('"""')[1]
    run_sh = (
        re.search(
            r"foreach\(target ([^)]*)\)\s*if\(TARGET \$\{target\}\)\s*add_dependencies\(run_sh",
            (repo / "CMakeLists.txt").read_text(),
        )
        .group(1)
        .split()
    )
    for fmu, target in (("SineSweep", "SineSweepFmu"), ("Shaker", "ShakerFmu")):
        assert target not in run_sh, run_sh
        assert re.search(rf"bash scripts/setup.sh [^\n#]*\b{target}\b[^\n]*# builds [^\n]*{fmu}\.fmu", usage), usage
    line = next(s for s in usage.splitlines() if s.strip().startswith("bash run.sh"))
    assert "SineSweep" not in line and "Shaker" not in line, line
