"""The source FMU (build/dist/PlateImpact-source.fmu): no binaries, sources/ with an FMI 3.0
buildDescription.xml valid against the schema fmpy ships that lists files the FMU has, the
licence texts of what the sources contain; compiled from its own sources/ by a plain CMake call
in a fresh folder, the result works.

Where test.sh's aarch64 stage ran, that compile is the one scripts/build-aarch64.sh made: it
builds the shipped aarch64-linux binary from exactly these sources/ by the plain CMake call (with
the cross toolchain file), and test_aarch64.py and test_experiments_platforms.py run that binary
under qemu-aarch64 — the life cycle, the default scene against x86-64 within 1e-6 (the smoke
experiment's scene, whose tolerances are ten times that: test_references.py's
test_tolerances_cover_the_platform_spread_the_suite_accepts) and three reference experiments
within their tolerances. The test then checks that the binary shipped is that build of these
sources and exports only fmi3* (issue 54: compiling the whole solver again here, natively, was
~51 s of the pytest stage's CPU). Elsewhere (no aarch64 build, or one of other sources) it
compiles here, natively (with clang where installed, else the default compiler, at -O1, about a
minute), and the result passes the smoke-test reference experiment through the validator
(FMI-LS-REF, the files it carries)."""

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import fmpy
import pytest
from lxml import etree

ROOT = Path(__file__).resolve().parent.parent
SOURCE_FMU = ROOT / "build" / "dist" / "PlateImpact-source.fmu"
# scripts/build-aarch64.sh: the source FMU extracted, and its CMake build with the cross toolchain
AARCH64_SOURCE = ROOT / "build-aarch64" / "source-fmu"
AARCH64_BUILD = ROOT / "build-aarch64" / "source-build"
DIST3 = ROOT / "build" / "dist" / "fmi3" / "PlateImpact.fmu"

pytestmark = pytest.mark.skipif(not SOURCE_FMU.is_file(), reason="source FMU not built")


def test_sources_build_description_and_licences():
    z = zipfile.ZipFile(SOURCE_FMU)
    names = set(z.namelist())
    assert not any(n.startswith("binaries/") for n in names)
    assert {"modelDescription.xml", "sources/buildDescription.xml", "sources/CMakeLists.txt"} <= names
    assert 'fmiVersion="3.0"' in z.read("modelDescription.xml").decode()
    from fmpy.validation import validate_fmu

    assert validate_fmu(str(SOURCE_FMU)) == []
    schema = etree.XMLSchema(file=str(Path(fmpy.__file__).parent / "schema" / "fmi3" / "fmi3BuildDescription.xsd"))
    root = etree.fromstring(z.read("sources/buildDescription.xml"))
    assert schema.validate(root), schema.error_log
    listed = [f.get("name") for f in root.iter("SourceFile")]
    assert listed and all(f"sources/{f}" in names for f in listed)
    assert (
        "sources/plateimpact/fmu/fmi3/fmi3Functions.cpp" in names
        and "sources/plateimpact/fmu/fmi2/fmi2Functions.cpp" not in names
    )
    for include in (i.get("name") for i in root.iter("IncludeDirectory")):
        assert any(n.startswith(f"sources/{include}/") for n in names), include
    for licence in ("CHOLMOD-Core-Cholesky", "AMD", "COLAMD", "Eigen", "xxHash", "PlateImpact"):
        assert f"documentation/licenses/{licence}.txt" in names
    assert "extra/org.fmi-standard.fmi-ls-ref/fmi-ls-manifest.xml" in names


def aarch64_build_of_these_sources():
    """The aarch64-linux binary scripts/build-aarch64.sh compiled from this source FMU, when the
    shipped FMI 3.0 FMU carries it: else None (then the test compiles here)."""
    binary = AARCH64_SOURCE / "binaries" / "aarch64-linux" / "PlateImpact.so"
    if not (binary.is_file() and DIST3.is_file() and (AARCH64_BUILD / "CMakeCache.txt").is_file()):
        return None
    with zipfile.ZipFile(SOURCE_FMU) as z:  # every file of the source FMU, the same bytes
        for info in z.infolist():
            extracted = AARCH64_SOURCE / info.filename
            if not info.is_dir() and not (extracted.is_file() and extracted.read_bytes() == z.read(info)):
                return None
    with zipfile.ZipFile(DIST3) as z:  # and the binary shipped is that build's
        if z.read("binaries/aarch64-linux/PlateImpact.so") != binary.read_bytes():
            return None
    return binary


@pytest.mark.skipif(shutil.which("cmake") is None or shutil.which("c++") is None, reason="no cmake or C++ compiler")
def test_compiled_from_its_own_sources_passes_the_smoke_test(tmp_path):
    binary = aarch64_build_of_these_sources()
    if binary is not None:
        # the plain CMake call on sources/ (the cross toolchain file its only addition), a fresh
        # build folder of its own; its result is run under qemu-aarch64 (module docstring)
        cache = (AARCH64_BUILD / "CMakeCache.txt").read_text()
        assert f"CMAKE_HOME_DIRECTORY:INTERNAL={(AARCH64_SOURCE / 'sources').resolve()}" in cache, cache[:2000]
        assert "CMAKE_TOOLCHAIN_FILE:" in cache and "aarch64-linux-gnu.cmake" in cache
        assert binary.read_bytes()[18] == 183  # e_machine EM_AARCH64
        nm = shutil.which("aarch64-linux-gnu-nm") or shutil.which("nm")
        symbols = subprocess.run([nm, "-D", "--defined-only", str(binary)], capture_output=True, text=True, check=True)
        exported = [line.split()[-1] for line in symbols.stdout.splitlines() if line.split()[1] in "TDBRW"]
        assert exported and all(s.startswith("fmi3") for s in exported), [s for s in exported if s[:4] != "fmi3"][:20]
        return
    fmu = tmp_path / "PlateImpact"
    with zipfile.ZipFile(SOURCE_FMU) as z:
        z.extractall(fmu)
    build = tmp_path / "build"
    env = dict(os.environ, CMAKE_BUILD_PARALLEL_LEVEL="2")
    if shutil.which("clang") and shutil.which("clang++"):
        # A second compiler's view of the sources where clang is installed (test.sh installs it
        # for the instrumented build; the release builds compile the same sources with GCC), and
        # the cheaper one: 51 s of CPU against GCC's 66 (issue 54, docs/contributing.md).
        env.update(CC="clang", CXX="clang++")
    for cmd in (
        # The documented call, at -O1 and as a unity build of one batch per target: what is
        # checked (the file list, the includes, the CMake file, the smoke experiment) depends on
        # neither, -O1 compiles in about half the time of -O3, and the unity build (Eigen parsed
        # and instantiated once per batch) in 88 s of CPU against 131 s one file at a time, one
        # batch for the whole library in less again (issue 54, docs/contributing.md). A file that
        # misses an #include shows in a build one file at a time (-DPLATEIMPACT_UNITY_BUILD=OFF,
        # docs/contributing.md), not here.
        [
            *("cmake", "-S", str(fmu / "sources"), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"),
            *("-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG", "-DCMAKE_C_FLAGS_RELEASE=-O1 -DNDEBUG"),
            "-DCMAKE_UNITY_BUILD=ON",
            "-DCMAKE_UNITY_BUILD_BATCH_SIZE=0",
        ],
        ["nice", "-n", "10", "cmake", "--build", str(build), "--parallel", str(os.cpu_count() or 1)],
    ):
        out = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=1800)
        assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    assert (fmu / "binaries" / "x86_64-linux" / "PlateImpact.so").is_file()
    out = subprocess.run(
        [sys.executable, "-m", "plateimpact.validate", str(fmu), "--master", "fmpy", "--experiment", "smoke"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert "PASS smoke (experiment/smoke-test, fmpy)" in out.stdout
