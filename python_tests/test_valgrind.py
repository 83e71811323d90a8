"""valgrind memcheck over the whole life of an instance, from a plain C master (fmu_driver.c):
instantiate -> parameters -> initialize -> steps with input derivatives -> FMU state get/set,
serialize/deserialize/free (also into a second instance) -> an error and its log -> reset ->
initialize again -> step -> terminate -> free, for the Argyris, FVS and reduced modal
configurations on 4 x 2 cells. No invalid access, no use of uninitialised memory, no definite
or indirect leak; the driver itself checks that restored and reset runs repeat bit for bit.

The driver is compiled here (cc, the FMI headers of fmu/headers/fmi2) and loads the FMU under test
($PLATEIMPACT_FMU or build/PlateImpact.fmu) from its unzipped folder, as importers do. The
sanitizer build cannot run under valgrind: it is skipped there (test.sh runs the sanitizer stage
without this file).
"""

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
DRIVER_SOURCE = HERE / "fmu_driver.c"
FMI_HEADERS = HERE.parent / "fmu" / "headers" / "fmi2"
STEPS = 6  # communication steps of 1 ms (10 internal steps each) per configuration

# Reports that are not PlateImpact's, each matched narrowly:
SUPPRESSIONS = """
{
   glibc-ld.so-word-wise-strncmp-over-read-of-the-$ORIGIN-rpath (valgrind false positive, not PlateImpact's)
   Memcheck:Addr8
   fun:strncmp
   fun:is_dst
}
{
   libgomp-allocates-once-in-its-constructor-and-never-frees (shipped CHOLMOD dependency, 8 bytes per load)
   Memcheck:Leak
   match-leak-kinds: definite
   fun:malloc
   obj:*/libgomp.so.1*
   ...
   fun:call_init
}
"""


@pytest.fixture(scope="module")
def valgrind():
    tool = shutil.which("valgrind")
    assert tool, "valgrind is not installed (test.sh installs it: `bash scripts/packages.sh base`)"
    return tool


@pytest.fixture(scope="module")
def unzipped_fmu(extracted_fmu):
    target = extracted_fmu
    so = target / "binaries" / "linux64" / "PlateImpact.so"
    if b"__asan_init" in so.read_bytes():
        pytest.skip("a sanitizer build of the FMU (AddressSanitizer and valgrind exclude each other)")
    return target


@pytest.fixture(scope="module")
def driver(tmp_path_factory):
    compiler = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    assert compiler, "no C compiler (cc) to build python_tests/fmu_driver.c"
    folder = tmp_path_factory.mktemp("fmu_driver")
    return compile_master(compiler, DRIVER_SOURCE, folder / "fmu_driver")


def compile_master(compiler, source, exe):
    """A C master of the FMI 2.0 headers for memcheck (-g -O1, warnings as errors), the
    suppressions beside it."""
    subprocess.run(
        [
            compiler,
            "-std=c99",
            "-D_DEFAULT_SOURCE",
            "-g",
            "-O1",
            "-Wall",
            "-Wextra",
            "-Werror",
            f"-I{FMI_HEADERS}",
            str(source),
            "-o",
            str(exe),
            "-ldl",
            "-lm",
        ],
        check=True,
        capture_output=True,
        text=True,
    )
    (exe.parent / "plateimpact.supp").write_text(SUPPRESSIONS)
    return exe


def memcheck_run(valgrind, suppressions, *command):
    """`command` under memcheck: any definite or indirect leak or invalid access exits 99."""
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}  # no sanitizer runtime
    return subprocess.run(
        [
            valgrind,
            "--leak-check=full",
            "--error-exitcode=99",
            "--errors-for-leak-kinds=definite,indirect",
            "--show-leak-kinds=definite,indirect",
            "--num-callers=30",
            "--keep-debuginfo=yes",
            f"--suppressions={suppressions}",
            *map(str, command),
        ],
        capture_output=True,
        text=True,
        timeout=600,
        env=env,
    )


def memcheck(valgrind, driver, unzipped_fmu, *options):
    return memcheck_run(valgrind, driver.parent / "plateimpact.supp", driver, *options, unzipped_fmu, STEPS)


def test_instance_lifecycle_is_clean_under_memcheck(valgrind, driver, unzipped_fmu):
    """The library stays loaded to the end (an importer session): every byte an instance, an
    FMU state or a log message allocated is freed, and nothing reads or writes out of bounds or
    branches on uninitialised memory."""
    proc = memcheck(valgrind, driver, unzipped_fmu, "--keep-loaded")
    report = proc.stderr
    assert "fmu_driver: all checks passed" in proc.stdout, proc.stdout + report[-4000:]
    assert proc.returncode == 0, f"exit code {proc.returncode}\n{report[-6000:]}"
    assert re.search(r"ERROR SUMMARY: 0 errors", report), report[-6000:]
    assert re.search(r"definitely lost: 0 bytes", report) or "All heap blocks were freed" in report, report[-6000:]
    assert "indirectly lost: 0 bytes" in report or "All heap blocks were freed" in report, report[-6000:]


def test_unloading_the_fmu_is_clean_under_memcheck(valgrind, driver, unzipped_fmu):
    """The same, and the driver unloads PlateImpact.so at the end (dlclose, as fmpy's
    freeInstance does): memory the library allocated at load time must be freed at unload —
    including the statically linked libstdc++'s emergency EH pool (fmu/core/RuntimeRelease.cpp)."""
    proc = memcheck(valgrind, driver, unzipped_fmu)
    report = proc.stderr
    assert "fmu_driver: all checks passed" in proc.stdout, proc.stdout + report[-4000:]
    assert proc.returncode == 0, f"exit code {proc.returncode}\n{report[-6000:]}"
    assert re.search(r"ERROR SUMMARY: 0 errors", report), report[-6000:]
