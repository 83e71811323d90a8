"""The validator's answers on a user's mistakes (issue 40): an unknown --experiment, a source-only
FMU, --master fmusim without fmusim are each one clear line and exit status 2, before anything is
replayed; a crashed fmusim is reported with its signal and the likely cause; the FMU's own page
sends the state experiment to a fmusim that restores states."""

import signal
import zipfile
from pathlib import Path

import pytest

from plateimpact import validate

ROOT = Path(__file__).resolve().parent.parent
SOURCE_FMU = ROOT / "build" / "dist" / "PlateImpact-source.fmu"


def run(argv, capsys):
    code = validate.main([str(a) for a in argv])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_unknown_experiment_is_an_error(fmu_path, capsys):
    code, out, err = run([fmu_path, "--master", "fmpy", "--experiment", "smok"], capsys)
    assert code == 2, (code, out, err)
    assert "no experiment smok" in err and "smoke" in err and "forced_state" in err, err
    assert "passed" not in out


def test_source_only_fmu_says_build_it_first(capsys):
    if not SOURCE_FMU.is_file():
        pytest.skip("source FMU not built")
    code, out, err = run([SOURCE_FMU, "--master", "fmpy"], capsys)
    assert code == 2, (code, out, err)
    assert "only sources: build it first" in err and "cmake -S" in err, err
    assert "FAIL" not in out


def test_source_only_fmu_folder_says_build_it_first(tmp_path, capsys):
    if not SOURCE_FMU.is_file():
        pytest.skip("source FMU not built")
    with zipfile.ZipFile(SOURCE_FMU) as z:
        z.extractall(tmp_path / "fmu")
    code, _, err = run([tmp_path / "fmu", "--master", "fmpy"], capsys)
    assert code == 2 and "build it first" in err, err


def test_master_fmusim_without_fmusim(fmu_path, monkeypatch, capsys):
    monkeypatch.setattr(validate, "find_fmusim", lambda: None)
    code, out, err = run([fmu_path, "--master", "fmusim"], capsys)
    assert code == 2, (code, out, err)
    assert "fmusim not found" in err and "--master fmpy" in err, err
    assert "fmpy only" not in out + err and "PASS" not in out and "FAIL" not in out


def test_fmusim_crash_names_signal_and_cause(fmu_path, tmp_path, monkeypatch, capsys):
    fake = tmp_path / "fmusim"
    fake.write_text("#!/bin/sh\nkill -SEGV $$\n")
    fake.chmod(0o755)
    monkeypatch.setenv("FMUSIM", str(fake))
    code, out, _ = run([fmu_path, "--master", "fmusim", "--experiment", "forced_state"], capsys)
    assert code == 1
    line = next(x for x in out.splitlines() if x.startswith("FAIL forced_state"))
    assert "SIGSEGV" in line and "FreeFMUState" in line and "scripts/build-fmusim.sh" in line, line
    code, out, _ = run([fmu_path, "--master", "fmusim", "--experiment", "smoke"], capsys)
    line = next(x for x in out.splitlines() if x.startswith("FAIL smoke"))
    assert "SIGSEGV" in line and "--master fmpy" in line and "FreeFMUState" not in line, line


def test_fmusim_failure_texts():
    exp = validate.Experiment("e", "validation", 0, 1, 0.1, {}, None, Path("r.csv"), {}, None)
    assert validate.fmusim_failure(3, "bad option\n", exp) == "fmusim exited with 3: bad option"
    assert validate.fmusim_failure(-signal.SIGKILL, "", exp).startswith("fmusim crashed (SIGKILL)")


def test_fmu_page_points_at_a_fmusim_that_restores_states(fmu_path):
    with zipfile.ZipFile(fmu_path) as z:
        html = z.read("documentation/fmi-ls-ref.html").decode()
    section = html[html.index("The serialized state") :]
    section = section[: section.index("<h2>", 10)]
    assert "--initial-fmu-state-file" in section
    assert "patched" in section and "https://github.com/modelica/fmusim" in section, section[-800:]
