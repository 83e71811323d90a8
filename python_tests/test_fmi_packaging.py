"""The binary of PlateImpact.fmu runs where SuiteSparse is not installed: it needs only glibc
and the libraries shipped in binaries/linux64, finds them through RPATH=$ORIGIN, links
libstdc++/libgcc statically and exports nothing but the fmi2* functions."""

import os
import re
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest

# glibc's libraries: present on every Linux target, never shipped.
GLIBC = re.compile(
    r"^(ld-linux.*|linux-vdso.*|libc|libm|libmvec|libpthread|libdl|librt|libutil|libresolv|"
    r"libanl|libnsl)\.so(\.[0-9]+)*$"
)

FMI2_FUNCTIONS = """
fmi2GetTypesPlatform fmi2GetVersion fmi2SetDebugLogging fmi2Instantiate fmi2FreeInstance
fmi2SetupExperiment fmi2EnterInitializationMode fmi2ExitInitializationMode fmi2Terminate fmi2Reset
fmi2GetReal fmi2GetInteger fmi2GetBoolean fmi2GetString fmi2SetReal fmi2SetInteger fmi2SetBoolean
fmi2SetString fmi2GetFMUstate fmi2SetFMUstate fmi2FreeFMUstate fmi2SerializedFMUstateSize
fmi2SerializeFMUstate fmi2DeSerializeFMUstate fmi2GetDirectionalDerivative fmi2EnterEventMode
fmi2NewDiscreteStates fmi2EnterContinuousTimeMode fmi2CompletedIntegratorStep fmi2SetTime
fmi2SetContinuousStates fmi2GetDerivatives fmi2GetEventIndicators fmi2GetContinuousStates
fmi2GetNominalsOfContinuousStates fmi2SetRealInputDerivatives fmi2GetRealOutputDerivatives
fmi2DoStep fmi2CancelStep fmi2GetStatus fmi2GetRealStatus fmi2GetIntegerStatus
fmi2GetBooleanStatus fmi2GetStringStatus
""".split()


def run(*command):
    tool = shutil.which(command[0])
    if tool is None:
        pytest.skip(f"{command[0]} not installed")
    return subprocess.run([tool, *command[1:]], capture_output=True, text=True, check=True).stdout


@pytest.fixture(scope="module")
def binaries(fmu_path, tmp_path_factory):
    assert fmu_path.is_file(), f"FMU not built: {fmu_path} (build it or set PLATEIMPACT_FMU)"
    target = tmp_path_factory.mktemp("fmu_binaries")
    with zipfile.ZipFile(fmu_path) as archive:
        names = archive.namelist()
        archive.extractall(target)
    assert "modelDescription.xml" in names
    folder = target / "binaries" / "linux64"
    assert (folder / "PlateImpact.so").is_file()
    return folder


def dynamic_section(path):
    text = run("readelf", "-d", str(path))
    needed = re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", text)
    rpath = re.findall(r"\(RPATH\)\s+Library rpath: \[([^\]]*)\]", text)
    runpath = re.findall(r"\(RUNPATH\)\s+Library runpath: \[([^\]]*)\]", text)
    return needed, rpath, runpath


def test_archive_holds_only_the_fmu_files(fmu_path):
    with zipfile.ZipFile(fmu_path) as archive:
        files = [n for n in archive.namelist() if not n.endswith("/")]
    assert "modelDescription.xml" in files
    assert "binaries/linux64/PlateImpact.so" in files
    # extra/org.fmi-standard.fmi-ls-ref/: the reference experiments (python_tests/test_references.py)
    allowed = ("binaries/linux64/", "documentation/", "extra/org.fmi-standard.fmi-ls-ref/")
    assert all(f == "modelDescription.xml" or f.startswith(allowed) for f in files), files
    # FMI 2.0 §2.4: documentation/index.html; the licences of what the binary links statically
    assert "documentation/index.html" in files
    assert "documentation/licenses/CHOLMOD-Core-Cholesky.txt" in files


def test_needed_libraries_are_glibc_or_shipped_and_rpath_is_origin(binaries):
    needed, rpath, runpath = dynamic_section(binaries / "PlateImpact.so")
    shipped = {p.name for p in binaries.iterdir()}
    assert needed
    for name in needed:
        assert GLIBC.match(name) or name in shipped, f"{name} is neither glibc nor in binaries/linux64"
    assert not any(n.startswith(("libstdc++", "libgcc_s")) for n in needed), needed  # linked statically
    assert rpath and "$ORIGIN" in rpath[0].split(":"), rpath
    assert runpath == [], "DT_RUNPATH would not apply to the dependencies of the dependencies"


def test_the_fmu_ships_no_shared_library_but_its_own(binaries):
    # CHOLMOD's simplicial factor is linked in statically (third_party/): binaries/linux64 holds
    # PlateImpact.so alone, and it needs nothing outside glibc
    assert {p.name for p in binaries.iterdir()} == {"PlateImpact.so"}
    needed, _, _ = dynamic_section(binaries / "PlateImpact.so")
    assert all(GLIBC.match(name) for name in needed), needed


def test_only_fmi2_symbols_are_exported(binaries):
    text = run("nm", "-D", "--defined-only", str(binaries / "PlateImpact.so"))
    symbols = [line.split()[-1] for line in text.splitlines() if line.strip()]
    assert [s for s in symbols if not s.startswith("fmi2")] == []
    assert set(FMI2_FUNCTIONS) <= set(symbols), set(FMI2_FUNCTIONS) - set(symbols)


def test_ldd_resolves_everything_into_the_fmu_or_glibc(binaries):
    # a clean environment: no LD_LIBRARY_PATH that could hide a missing library
    env = {k: v for k, v in os.environ.items() if k != "LD_LIBRARY_PATH"}
    text = subprocess.run(
        [shutil.which("ldd") or pytest.skip("ldd not installed"), str(binaries / "PlateImpact.so")],
        capture_output=True,
        text=True,
        check=True,
        env=env,
    ).stdout
    assert "not found" not in text, text
    folder = binaries.resolve()
    resolved = re.findall(r"^\s*(\S+) => (\S+) \(0x", text, re.MULTILINE)
    assert resolved
    for name, path in resolved:
        if GLIBC.match(name):
            continue
        assert Path(path).resolve().parent == folder, f"{name} resolves to {path}, outside the FMU"


REPO = Path(__file__).resolve().parent.parent


def platforms(fmu):
    with zipfile.ZipFile(fmu) as z:
        return {n.split("/")[1] for n in z.namelist() if n.startswith("binaries/") and n.count("/") >= 2}


def test_one_packaging_step_ships_every_platform_built_in_either_order():
    """scripts/package-dist.sh (the end of both cross scripts) assembles the distributed FMUs from
    every platform binary that exists: run again last (as the win64 script does when it runs after
    the aarch64 one), the FMI 3.0 FMU keeps aarch64-linux beside x86_64-windows, and the licence
    texts of the GCC runtime are the native compiler's, never a cross toolchain's."""
    cross = {
        "x86_64-windows": REPO / "build-win64" / "fmu" / "fmi3" / "PlateImpact.dll",
        # compiled from the source FMU's sources/ (scripts/build-aarch64.sh)
        "aarch64-linux": REPO / "build-aarch64" / "source-fmu" / "binaries" / "aarch64-linux" / "PlateImpact.so",
    }
    built = {name for name, path in cross.items() if path.is_file()}
    if not built:
        pytest.skip("no cross build here (test.sh's win64 and aarch64 stages make them)")
    subprocess.run(["bash", str(REPO / "scripts" / "package-dist.sh")], check=True, capture_output=True)
    fmi3 = platforms(REPO / "build" / "dist" / "fmi3" / "PlateImpact.fmu")
    assert fmi3 == {"x86_64-linux"} | built
    if "x86_64-windows" in built:
        assert platforms(REPO / "build" / "dist" / "PlateImpact.fmu") == {"linux64", "win64"}


def test_gcc_runtime_licence_is_that_of_the_linked_libstdcxx(fmu_path):
    """The GCC runtime's licence text is the copyright file of the Debian package that owns the
    libstdc++ g++ links (whatever cross toolchains were installed, and when)."""
    library = subprocess.run(["g++", "-print-file-name=libstdc++.a"], capture_output=True, text=True, check=True)
    owner = subprocess.run(
        ["dpkg-query", "--search", os.path.realpath(library.stdout.strip())], capture_output=True, text=True, check=True
    )
    package = re.match(r"([^:,]+)", owner.stdout).group(1)
    want = Path(f"/usr/share/doc/{package}/copyright").read_bytes()
    with zipfile.ZipFile(fmu_path) as z:
        assert z.read("documentation/licenses/GCC-runtime.txt") == want
