"""One copy of the FMU's code per process (fmu/core/PrimaryCopy.h, README "Performance"): fmpy's
simulate_fmu extracts the FMU into a new folder at every call and unloads its library with the
instance, so each call loads a fresh copy; the first copy of a build pins itself and the later ones
forward every FMI call to it, so that the discretization cache outlives them. Each scenario runs in
a fresh interpreter (the test process has loaded the FMU already); the FMU's log line
"discretization: s of n parts shared from the process's cache" says what an instance's setup did.

The CPU saved is measured, not asserted: tools/instance_setup.py --simulate-fmu prints the first and
the next calls' ExitInitializationMode CPU and their ratio."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent

# Runs simulate_fmu on each FMU (file or folder) of argv[2:] in turn and prints, per call, the
# instance's cache line (shared, parts), the process's resident memory (MB) and a digest of the
# results. argv[1]: the published primary's variable to print at the end, or "-". With "exec" as
# the last argument the script runs the first call, then replaces itself (os.execv: the same pid,
# the same environment) by the same script without it.
SCRIPT = r"""
import ctypes, hashlib, json, os, re, sys
from fmpy import simulate_fmu
SHARED = re.compile(r"discretization: (\d+) of (\d+) parts shared from the process's cache")
args = sys.argv[1:]
execs = args[-1] == "exec"
if execs:
    args = args[:-1]
variable, fmus = args[0], args[1:]
def rss_mb():
    with open("/proc/self/status") as f:
        return next(int(l.split()[1]) for l in f if l.startswith("VmRSS")) / 1024
for k, fmu in enumerate(fmus):
    lines = []
    result = simulate_fmu(fmu, stop_time=0.01, output_interval=1e-3, debug_logging=True,
                          logger=lambda *a: lines.append(a[-1].decode() if isinstance(a[-1], bytes) else str(a[-1])))
    found = [SHARED.search(m).groups() for m in lines if SHARED.search(m)]
    digest = hashlib.sha256(result.tobytes()).hexdigest()
    print(json.dumps({"cache": [list(map(int, g)) for g in found], "rss": rss_mb(), "digest": digest}), flush=True)
    if execs:
        os.execv(sys.executable, [sys.executable, __file__, variable] + fmus[1:])
if variable != "-":
    libc = ctypes.CDLL(None)
    libc.getenv.restype = ctypes.c_char_p
    value = libc.getenv(variable.encode())
    print(json.dumps({"published": value.decode() if value else None, "pid": os.getpid()}), flush=True)
"""


def run(folder, *arguments, variable="-"):
    """The script's lines (dicts) from a fresh interpreter."""
    script = folder / "simulate_fmu_calls.py"
    script.write_text(SCRIPT)
    done = subprocess.run(
        [sys.executable, str(script), variable, *map(str, arguments)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]


@pytest.mark.sanitizer
@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_a_second_simulate_fmu_shares_the_first_ones_plate_bit_for_bit(version, fmu_path, fmu3, tmp_path):
    fmu = fmu_path if version == "fmi2" else fmu3
    variable = f"PLATEIMPACT_FMI{version[-1]}_PRIMARY_PlateImpact"
    first, second, published = run(tmp_path, fmu, fmu, variable=variable)
    ((shared, parts),) = first["cache"]
    assert shared == 0 and parts >= 3  # the process's first: it builds the space, M and K, the modes
    assert second["cache"] == [[parts, parts]]  # a new copy of the library, every part shared
    assert second["digest"] == first["digest"]  # the results, bit for bit
    # "<build id>:<pid>:<the first copy's library in the folder simulate_fmu extracted it to>"
    build, pid, location = published["published"].split(":", 2)
    assert int(pid) == published["pid"] and location.endswith("/PlateImpact.so") and len(build) > 32


def test_twenty_simulate_fmu_calls_keep_one_copy_and_one_cache(fmu_path, tmp_path):
    """Twenty calls, each with its own copy of the library: the resident memory after the second
    call grows by less than 1 MB a call on average. One copy more kept loaded per call would add its
    pages (the library is 3.3 MB, about 2 MB of it touched) and its own cache (the default plate's
    modal basis alone is 734² doubles, 4.3 MB): over 6 MB a call. Measured: 0.17 MB a call, fmpy's
    own (its model description and result arrays), as much as before this change."""
    rows = run(tmp_path, *[fmu_path] * 20)
    assert all(row["cache"][0][0] == row["cache"][0][1] for row in rows[1:])  # every later call shared
    assert len({row["digest"] for row in rows}) == 1
    growth = (rows[-1]["rss"] - rows[1]["rss"]) / (len(rows) - 2)
    assert growth < 1.0, [round(row["rss"], 1) for row in rows]


def other_build(extracted: Path, target: Path) -> Path:
    """The FMU folder `extracted` copied with its library's GNU build id changed: the same code,
    another build for PrimaryCopy (as a rebuilt library is)."""
    shutil.copytree(extracted, target)
    library = target / "binaries" / "linux64" / "PlateImpact.so"
    notes = subprocess.run(["readelf", "-n", str(library)], capture_output=True, text=True, check=True).stdout
    build_id = bytes.fromhex(notes.split("Build ID:")[1].split()[0])
    data = library.read_bytes()
    assert data.count(build_id) == 1
    library.write_bytes(data.replace(build_id, bytes([build_id[0] ^ 0xFF]) + build_id[1:]))
    return target


def test_a_copy_of_another_build_runs_its_own_code(fmu_path, tmp_path):
    extracted = tmp_path / "original"
    with zipfile.ZipFile(fmu_path) as archive:
        archive.extractall(extracted)
    other = other_build(extracted, tmp_path / "other")
    first, foreign, again, published = run(
        tmp_path, fmu_path, other, fmu_path, variable="PLATEIMPACT_FMI2_PRIMARY_PlateImpact"
    )
    parts = first["cache"][0][1]
    assert first["cache"] == [[0, parts]]
    assert foreign["cache"] == [[0, parts]]  # not forwarded: its own code, its own (empty) cache
    assert again["cache"] == [[parts, parts]]  # the primary is still the first copy, its cache whole
    assert foreign["digest"] == first["digest"] == again["digest"]
    assert str(other) not in published["published"]


@pytest.mark.sanitizer
def test_a_value_left_before_an_exec_is_replaced(fmu_path, tmp_path):
    """os.execv keeps the pid and the environment: the variable then names a library this new
    process image has not loaded. Its first copy becomes the primary (no forwarding into what is not
    there); its second shares."""
    rows = run(tmp_path, fmu_path, fmu_path, fmu_path, "exec", variable="PLATEIMPACT_FMI2_PRIMARY_PlateImpact")
    before, first, second, published = rows
    parts = before["cache"][0][1]
    assert before["cache"] == [[0, parts]] and first["cache"] == [[0, parts]] and second["cache"] == [[parts, parts]]
    assert first["digest"] == second["digest"] == before["digest"]


@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_the_library_exports_every_function_of_the_header_and_nothing_else(version, fmu_path, fmu3, tmp_path):
    """fmi2Exports.cpp and fmi3Exports.cpp write the list of exported functions by hand (each
    forwards to this copy's implementation or the primary's): one per <name>TYPE of the standard's
    header, none more (the implementations, plateimpactOwn_*, stay inside)."""
    header = (REPO / "fmu" / "headers" / version / f"{version}FunctionTypes.h").read_text()
    header = re.sub(r"/\*.*?\*/", "", header, flags=re.S)
    expected = set(re.findall(rf"\btypedef\s[^;(]*?\b({version}\w+)TYPE\s*\(", header))
    fmu = fmu_path if version == "fmi2" else fmu3
    with zipfile.ZipFile(fmu) as archive:
        member = next(
            n
            for n in archive.namelist()
            if n.endswith("linux64/PlateImpact.so") or n.endswith("x86_64-linux/PlateImpact.so")
        )
        library = Path(archive.extract(member, tmp_path))
    text = subprocess.run(
        ["nm", "-D", "--defined-only", str(library)], capture_output=True, text=True, check=True
    ).stdout
    exported = {line.split()[-1] for line in text.splitlines() if line.strip()}
    assert len(expected) > 40 and exported == expected, (expected - exported, exported - expected)


def copies(library: Path, folder: Path, names=("first", "second")):
    """`library` copied into one folder per name (as importers extract an FMU to a new folder)."""
    paths = []
    for name in names:
        (folder / name).mkdir(parents=True)
        paths.append(folder / name / library.name)
        shutil.copy2(library, paths[-1])
    return paths


def guid_of(fmu):
    with zipfile.ZipFile(fmu) as archive:
        return re.search(r'guid="([^"]+)"', archive.read("modelDescription.xml").decode()).group(1)


def test_copies_loaded_and_unloaded_by_a_c_master_are_clean_under_memcheck(fmu_path, tmp_path):
    """python_tests/copies_driver.c: the first copy, a second from another folder, that one again
    (unloaded in between, so loaded anew), the first again; the later runs share the first one's
    plate and repeat its outputs bit for bit. Under memcheck: a forwarding copy's load and unload
    leave nothing behind (no definite or indirect leak), and nothing reads freed or unmapped memory."""
    valgrind = shutil.which("valgrind")
    assert valgrind, "valgrind is not installed (bash scripts/packages.sh base)"
    with zipfile.ZipFile(fmu_path) as archive:
        library = Path(archive.extract("binaries/linux64/PlateImpact.so", tmp_path / "fmu"))
    if b"__asan_init" in library.read_bytes():
        pytest.skip("a sanitizer build of the FMU (AddressSanitizer and valgrind exclude each other)")
    first, second = copies(library, tmp_path / "copies")
    from test_valgrind import compile_master, memcheck_run

    driver = compile_master("cc", REPO / "python_tests" / "copies_driver.c", tmp_path / "copies_driver")
    proc = memcheck_run(
        valgrind, driver.parent / "plateimpact.supp", driver, guid_of(fmu_path), first, second, second, first
    )
    assert "copies_driver: all checks passed" in proc.stdout, proc.stdout + proc.stderr[-4000:]
    assert proc.returncode == 0 and "ERROR SUMMARY: 0 errors" in proc.stderr, proc.stderr[-6000:]


def test_copies_of_the_win64_dll_share_the_first_ones_plate_under_wine(tmp_path):
    """The Windows side (GetModuleHandleEx's pin, the PE time stamp, the environment through
    kernel32): the same C master built with mingw-w64, the dual FMU's win64 DLL copied into two
    folders."""
    from test_win64 import DUAL, WINE

    compiler = shutil.which("x86_64-w64-mingw32-gcc")
    if not (DUAL.is_file() and compiler and WINE.exists()):
        pytest.skip("no dual-platform FMU, mingw-w64 or Wine (bash scripts/build-win64.sh)")
    with zipfile.ZipFile(DUAL) as archive:
        if "binaries/win64/PlateImpact.dll" not in archive.namelist():
            pytest.skip("the dual-platform FMU has no win64 binary (bash scripts/build-win64.sh)")
        dll = Path(archive.extract("binaries/win64/PlateImpact.dll", tmp_path / "fmu"))
    first, second = copies(dll, tmp_path / "copies")
    driver = tmp_path / "copies_driver.exe"
    subprocess.run(
        [
            compiler,
            "-std=c99",
            "-O1",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-static",
            f"-I{REPO / 'fmu' / 'headers' / 'fmi2'}",
            str(REPO / "python_tests" / "copies_driver.c"),
            "-o",
            str(driver),
        ],
        check=True,
    )
    windows = ["Z:" + str(p).replace("/", "\\") for p in (first, second, second, first)]
    env = dict(os.environ, WINEDEBUG="-all", WINEPREFIX=str(REPO / "build-win64" / "wineprefix"))
    env["WINEDLLOVERRIDES"] = "mscoree,mshtml="
    proc = subprocess.run(
        [str(WINE), str(driver), guid_of(DUAL), *windows], capture_output=True, text=True, timeout=300, env=env
    )
    assert "copies_driver: all checks passed" in proc.stdout, proc.stdout + proc.stderr[-4000:]


THREADS = r"""
import json, re, sys, threading
from plateimpact import PlateImpactFMU
from plateimpact.driver import unzipped
SHARED = re.compile(r"discretization: (\d+) of (\d+) parts shared")
folders = sys.argv[1:]
for folder in folders:
    unzipped(folder)  # the model descriptions read here: lxml's schema parsing is not for two threads
barrier = threading.Barrier(2)
results = {}
def run(folder, key, wait):
    lines = []
    if wait:
        barrier.wait()  # both copies make their first FMI call at the same moment
    with PlateImpactFMU(folder, nx=4, ny=2, dt=1e-4, initial_load=8600.0,
                        logger=lambda s, c, m: lines.append(m)) as plate:
        for _ in range(5):
            out = plate.step(1e-3)
    cache = [list(map(int, SHARED.search(m).groups())) for m in lines if SHARED.search(m)]
    results[key] = {"cache": cache, "outputs": out}
threads = [threading.Thread(target=run, args=(folders[k], k, True)) for k in (0, 1)]
for t in threads:
    t.start()
for t in threads:
    t.join()
run(folders[2], 2, False)
print(json.dumps(results))
"""


@pytest.mark.sanitizer
def test_two_copies_starting_in_two_threads_at_once(fmu_path, tmp_path):
    """Two copies from two folders make their first FMI call at the same moment in two threads
    (each decides once whether it is the primary or forwards: core/PrimaryCopy.h); a third copy
    after them. Every instance runs whole and gives the same outputs; the third shares its plate
    with one of them (whichever became the primary)."""
    extracted = tmp_path / "fmu"
    with zipfile.ZipFile(fmu_path) as archive:
        archive.extractall(extracted)
    folders = [tmp_path / name for name in ("a", "b", "c")]
    for folder in folders:
        shutil.copytree(extracted, folder)
    script = tmp_path / "threads.py"
    script.write_text(THREADS)
    done = subprocess.run(
        [sys.executable, str(script), *map(str, folders)], capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, done.stderr[-3000:]
    results = json.loads(done.stdout.splitlines()[-1])
    assert results["0"]["outputs"] == results["1"]["outputs"] == results["2"]["outputs"]
    parts = results["2"]["cache"][0][1]
    assert parts >= 3 and results["2"]["cache"] == [[parts, parts]]
