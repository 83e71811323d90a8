"""The dual-platform FMU (scripts/build-win64.sh -> build/dist/PlateImpact.fmu): both binaries
depend on nothing outside the archive but the C runtime, the archive is lean, and the win64 DLL
runs under Wine — life cycle, the default scene against linux64, a bad step — from a folder whose
path has spaces and non-ASCII characters. The FMI 3.0 FMU (build/dist/fmi3/PlateImpact.fmu) has
the same: its x86_64-windows binary under Wine against its x86_64-linux one.

Skipped when build/dist/PlateImpact.fmu or Wine is missing (test.sh builds it in its win64 stage).
"""

import csv
import os
import re
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DUAL = ROOT / "build" / "dist" / "PlateImpact.fmu"
WINE = Path("/usr/lib/wine/wine64")
WIN_DRIVER = ROOT / "build-win64" / "fmu_driver.exe"
LINUX_DRIVER = ROOT / "build" / "fmu_driver"
# FMI 3.0: build/dist/fmi3/PlateImpact.fmu with binaries/x86_64-windows, the C master
# python_tests/fmu3_driver.c built for both platforms.
DUAL3 = ROOT / "build" / "dist" / "fmi3" / "PlateImpact.fmu"
WIN_DRIVER3 = ROOT / "build-win64" / "fmu3_driver.exe"
LINUX_DRIVER3 = ROOT / "build" / "fmu3_driver"

pytestmark = pytest.mark.skipif(
    not (DUAL.is_file() and WINE.exists() and WIN_DRIVER.is_file() and LINUX_DRIVER.is_file()),
    reason="no dual-platform FMU or no Wine (bash scripts/build-win64.sh)",
)


@pytest.fixture(scope="module")
def unpacked(tmp_path_factory):
    """The dual FMU unpacked under a path with spaces and non-ASCII characters."""
    folder = tmp_path_factory.mktemp("win64") / "Plätte mit Lücken ü" / "PlateImpact fmu"
    folder.mkdir(parents=True)
    with zipfile.ZipFile(DUAL) as z:
        z.extractall(folder)
    return folder


def windows_path(path):
    return "Z:" + str(path).replace("/", "\\")


def wine(*args, timeout=300, driver=WIN_DRIVER):
    # mscoree, mshtml off: making the prefix (first use) starts no Wine Mono installer (one wine
    # process less; the drivers are plain C, no .NET or HTML)
    env = dict(os.environ, WINEDEBUG="-all", WINEPREFIX=str(ROOT / "build-win64" / "wineprefix"))
    env["WINEDLLOVERRIDES"] = "mscoree,mshtml="
    return subprocess.run([str(WINE), str(driver), *args], capture_output=True, text=True, env=env, timeout=timeout)


def test_archive_is_lean_and_carries_both_platforms_documentation_and_licences():
    assert DUAL.stat().st_size <= 4 * 1024 * 1024
    names = set(zipfile.ZipFile(DUAL).namelist())
    assert {"binaries/linux64/PlateImpact.so", "binaries/win64/PlateImpact.dll", "documentation/index.html"} <= names
    licences = {n for n in names if n.startswith("documentation/licenses/") and n.endswith(".txt")}
    assert {"documentation/licenses/CHOLMOD-Core-Cholesky.txt", "documentation/licenses/AMD.txt"} <= licences
    # no shared library besides the FMU's own two
    binaries = {n for n in names if n.startswith("binaries/") and not n.endswith("/")}
    assert binaries == {"binaries/linux64/PlateImpact.so", "binaries/win64/PlateImpact.dll"}
    z = zipfile.ZipFile(DUAL)
    index = z.read("documentation/index.html").decode()
    for name in re.findall(r'ScalarVariable name="([^"]+)"', z.read("modelDescription.xml").decode()):
        assert f"<code>{name}</code>" in index, name


def test_linux64_binary_needs_only_the_c_runtime(unpacked):
    so = unpacked / "binaries" / "linux64" / "PlateImpact.so"
    dynamic = subprocess.run(["readelf", "-d", str(so)], capture_output=True, text=True, check=True).stdout
    needed = set(re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", dynamic))
    assert needed <= {"libc.so.6", "libm.so.6", "ld-linux-x86-64.so.2"}, needed
    symbols = subprocess.run(["nm", "-D", "--defined-only", str(so)], capture_output=True, text=True, check=True)
    exported = [line.split()[-1] for line in symbols.stdout.splitlines() if line.split()[1] in "TDBRW"]
    assert exported and all(s.startswith("fmi2") for s in exported), exported


def test_win64_binary_imports_only_what_windows_ships(unpacked):
    dll = unpacked / "binaries" / "win64" / "PlateImpact.dll"
    dump = subprocess.run(
        ["x86_64-w64-mingw32-objdump", "-p", str(dll)], capture_output=True, text=True, check=True
    ).stdout
    imports = set(re.findall(r"DLL Name: (\S+)", dump))
    assert {i.lower() for i in imports} <= {"kernel32.dll", "msvcrt.dll"}, imports
    exports = re.findall(r"^\s+\[\s*\d+\]\s+(\S+)$", dump.split("[Ordinal/Name Pointer] Table")[1], re.M)
    assert len(exports) >= 30 and all(e.startswith("fmi2") for e in exports), exports


def test_win64_life_cycle_under_wine(unpacked):
    # instantiate, parameters, steps with input derivatives, get/set/serialize/deserialize FMU
    # states into a second instance, an illegal call, reset, free — every check inside the driver
    r = wine(windows_path(unpacked))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "all checks passed" in r.stdout


def test_win64_default_scene_matches_linux64(unpacked, tmp_path):
    """The default scene for 0.1 s (impacts from t = 0.05 s on) through both binaries of the same
    archive, fed the same input bits (the drivers compute the base with their own sine, since
    glibc's and mingw-w64's differ in the last bit at 2 pi 10 t = pi): every output, at every
    communication point, bit-identical — same sources, same factor (CHOLMOD from source), the
    vertex kernel's x86-64-v3 clone chosen alike on both."""
    linux_csv, win_csv = tmp_path / "linux.csv", tmp_path / "win.csv"
    subprocess.run([str(LINUX_DRIVER), "--scene", str(linux_csv), str(unpacked)], check=True, capture_output=True)
    r = wine("--scene", windows_path(win_csv), windows_path(unpacked))
    assert r.returncode == 0, r.stdout + r.stderr
    a = list(csv.reader(linux_csv.open()))
    b = list(csv.reader(win_csv.open()))
    assert len(a) == len(b) == 1002
    assert max(float(row[1]) for row in a[1:]) == pytest.approx(0.1, abs=1e-12)  # the corner reached the obstacle
    assert a == b


def test_win64_refuses_a_step_below_the_grid_resolution(unpacked):
    r = wine("--bad-step", windows_path(unpacked))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "fmi2Error" in r.stdout and "shorter than the smallest step" in r.stdout and "h = 5e-15" in r.stdout


def test_linux64_from_a_path_with_spaces_and_non_ascii(unpacked):
    from fmpy import read_model_description
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(str(unpacked / "modelDescription.xml"))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=str(unpacked), modelIdentifier="PlateImpact", instanceName="p")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.setReal([15], [8600.0])  # initial_load
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 1e-3)
    assert fmu.getReal([30])[0] > 0.0
    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(unpacked / "__pycache__", ignore_errors=True)


@pytest.fixture(scope="module")
def fmi3_runs(unpacked):
    """The FMI 3.0 FMU's x86_64-windows binary under Wine and its x86_64-linux one, each driven by
    python_tests/fmu3_driver.c built for its platform, unpacked under the same awkward path."""
    if not (DUAL3.is_file() and WIN_DRIVER3.is_file() and LINUX_DRIVER3.is_file()):
        pytest.skip("no FMI 3.0 FMU with x86_64-windows (bash scripts/build-win64.sh)")
    folder = unpacked.parent / "PlateImpact fmi3"
    with zipfile.ZipFile(DUAL3) as z:
        z.extractall(folder)
    import fmpy

    token = fmpy.read_model_description(str(DUAL3)).guid
    linux = subprocess.run(
        [str(LINUX_DRIVER3), str(folder / "binaries" / "x86_64-linux" / "PlateImpact.so"), token],
        capture_output=True,
        text=True,
        timeout=600,
    )
    win = wine(windows_path(folder / "binaries" / "x86_64-windows" / "PlateImpact.dll"), token, driver=WIN_DRIVER3)
    return linux, win, folder


def test_fmi3_windows_binary_imports_only_what_windows_ships_and_exports_fmi3(fmi3_runs):
    _, _, folder = fmi3_runs
    dll = folder / "binaries" / "x86_64-windows" / "PlateImpact.dll"
    dump = subprocess.run(
        ["x86_64-w64-mingw32-objdump", "-p", str(dll)], capture_output=True, text=True, check=True
    ).stdout
    assert {i.lower() for i in re.findall(r"DLL Name: (\S+)", dump)} <= {"kernel32.dll", "msvcrt.dll"}
    exports = re.findall(r"^\s+\[\s*\d+\]\s+(\S+)$", dump.split("[Ordinal/Name Pointer] Table")[1], re.M)
    assert len(exports) >= 60 and all(e.startswith("fmi3") for e in exports), exports
    licences = {p.name for p in (folder / "documentation" / "licenses").iterdir()}
    assert {"GCC-runtime-mingw-w64.txt", "mingw-w64-runtime-winpthreads.txt"} <= licences


def test_fmi3_windows_life_cycle_and_default_scene_match_linux(fmi3_runs):
    """The C master's FMI 3.0 life cycle (a wrong token refused, early return and event mode at
    every contact event of the default scene's 0.1 s, an FMU state serialized and restored, a bad
    call answered with fmi3Error) passes on both binaries, and every printed output at every
    communication point and event is the same bits: the same sources and factor, and the driver's
    base is made of + - * / and fmod only (as the FMI 2.0 binaries above, bit for bit)."""
    linux, win, _ = fmi3_runs
    assert linux.returncode == 0, linux.stderr[-2000:]
    assert win.returncode == 0, (win.stdout + win.stderr)[-2000:]
    assert win.stdout.rstrip().endswith("failures 0")
    rows = [line for line in linux.stdout.splitlines() if line.split()[0] in ("point", "event", "again")]
    assert len(rows) > 1000 and any(r.startswith("event") for r in rows)
    assert win.stdout.replace("\r\n", "\n") == linux.stdout
