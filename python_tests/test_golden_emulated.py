"""The golden output on other CPUs with no Python under emulation: python_tests/golden_driver.c
(a plain C FMI 2.0 master, compiled here with the host's C compiler) runs the golden's default
scene on build/PlateImpact.fmu with the golden file's own inputs, under qemu-x86_64 with
`-cpu Nehalem` (SSE4.2, no AVX, no FMA) and `-cpu Haswell` (AVX2, FMA), over the first 0.06 s
(QEMU_WINDOW of test_golden.py, past the first impacts); every output bit for bit against
python_tests/golden/default_scene_0.1s.csv. Only the driver, the FMU and the C runtime run
emulated: a Python or numpy wheel built for newer instructions than the emulated CPU's
would die with SIGILL at import before the FMU is loaded. The driver also runs natively
over the whole 0.1 s (the driver itself checked against the golden)."""

import csv
import shutil
import subprocess
import zipfile
from pathlib import Path

import fmpy
import pytest

HERE = Path(__file__).resolve().parent
GOLDEN = HERE / "golden" / "default_scene_0.1s.csv"
INPUTS = ("base", "base_d1", "base_d2")
STEP, STEPS, QEMU_WINDOW = 1e-4, 1000, 600


@pytest.fixture(scope="module")
def setup(fmu_path, tmp_path_factory):
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.skip("no C compiler")
    work = tmp_path_factory.mktemp("golden_c")
    driver = work / "golden_driver"
    out = subprocess.run(
        [
            cc,
            "-O2",
            "-I",
            str(HERE.parent / "fmu" / "headers" / "fmi2"),
            str(HERE / "golden_driver.c"),
            "-o",
            str(driver),
            "-ldl",
        ],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stderr
    with zipfile.ZipFile(fmu_path) as z:
        z.extractall(work / "fmu")
    md = fmpy.read_model_description(str(fmu_path))
    vr = {v.name: v for v in md.modelVariables}
    with GOLDEN.open() as f:
        rows = list(csv.DictReader(f))
    names = [n for n in rows[0] if n != "time" and n not in INPUTS]
    reals = [n for n in names if vr[n].type == "Real"]
    ints = [n for n in names if vr[n].type == "Integer"]
    stdin = "".join(" ".join(r[c] for c in INPUTS) + "\n" for r in rows[:STEPS])
    args = [
        str(driver),
        str(work / "fmu"),
        md.guid,
        None,
        repr(STEP),
        str(vr["base_displacement"].valueReference),
        str(vr["load"].valueReference),
        ",".join(str(vr[n].valueReference) for n in reals),
        ",".join(str(vr[n].valueReference) for n in ints),
    ]
    return args, stdin, rows, reals, ints


def mismatches(output, rows, reals, ints, steps):
    lines = output.splitlines()
    assert len(lines) == steps + 1, f"{len(lines)} rows for {steps} steps"
    found = []
    for line, want in zip(lines, rows):
        fields = line.split()
        got = {"time": float.fromhex(fields[0])}
        got.update((n, float.fromhex(x)) for n, x in zip(reals, fields[1 : 1 + len(reals)]))
        got.update((n, int(x)) for n, x in zip(ints, fields[1 + len(reals) :]))
        for name in ("time", *reals, *ints):
            if got[name] != float(want[name]):
                found.append(f"{name} at t = {want['time']}: {got[name]!r} != golden {want[name]}")
    return found


def run(setup, steps, prefix=()):
    args, stdin, rows, reals, ints = setup
    args = list(args)
    args[3] = str(steps)
    out = subprocess.run([*prefix, *args], input=stdin, capture_output=True, text=True, timeout=900)
    assert out.returncode == 0, out.stderr[-2000:]
    return mismatches(out.stdout, rows, reals, ints, steps)


def test_c_driver_reproduces_the_golden_natively(setup):
    found = run(setup, STEPS)
    assert not found, f"{len(found)} differences, first: {found[:3]}"


@pytest.mark.parametrize("cpu", ["Nehalem", "Haswell"])
def test_golden_on_emulated_cpu_without_python(setup, cpu):
    qemu = shutil.which("qemu-x86_64")
    if qemu is None:
        pytest.fail("qemu-x86_64 not found: test.sh installs qemu-user before the suite")
    found = run(setup, QEMU_WINDOW, prefix=(qemu, "-cpu", cpu))
    assert not found, f"under qemu -cpu {cpu}: {len(found)} differences, first: {found[:3]}"
