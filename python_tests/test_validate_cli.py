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


STAND_IN = """#!/bin/sh
# A stand-in fmusim: records its command line, answers --version as {version!r}, and plays the part
# the test gives it (fmusim 0.8's validate prints problems as `error:` lines and exits 0).
echo "$@" >> "{log}"
case "$1" in
  --version) [ -n "{version}" ] && echo "fmusim {version}" && exit 0; echo "unknown option --version" >&2; exit 1;;
  validate) printf '    Validating ZIP archive\\n{validate_stderr}' >&2; exit 0;;
esac
echo "error: stand-in does not simulate" >&2
exit 1
"""


def stand_in(tmp_path, monkeypatch, version, validate_stderr=""):
    fake, log = tmp_path / "fmusim", tmp_path / "calls.txt"
    fake.write_text(STAND_IN.format(version=version, log=log, validate_stderr=validate_stderr))
    fake.chmod(0o755)
    monkeypatch.setenv("FMUSIM", str(fake))
    return log


def test_current_fmusim_command_lines(fmu_path, tmp_path, monkeypatch, capsys):
    """fmusim 0.8 (the standalone one): `fmusim validate FMU` once, then `fmusim simulate` with
    `--start-value NAME=VALUE` per experiment; a clean validate passes."""
    log = stand_in(tmp_path, monkeypatch, "0.8.0")
    code, out, _ = run([fmu_path, "--master", "fmusim", "--experiment", "fvs"], capsys)
    calls = log.read_text().splitlines()
    assert calls[0] == "--version" and calls[1] == f"validate {fmu_path}", calls
    simulate = calls[2].split()
    assert simulate[0] == "simulate" and "--interface-type" in simulate, calls[2]
    assert "element=2" in simulate and "nx=20" in simulate, calls[2]  # NAME=VALUE, one argument
    assert simulate[-1] == str(fmu_path)
    assert "PASS fmusim-validate" in out, out
    assert code == 1 and "FAIL fvs" in out and "error: stand-in does not simulate" in out, out


def test_current_fmusim_validate_error_lines_fail(fmu_path, tmp_path, monkeypatch, capsys):
    """fmusim 0.8's validate exits 0 while printing ZIP or schema problems as `error:` lines (in
    colour on a terminal): the validator reads them as failures."""
    log = stand_in(tmp_path, monkeypatch, "0.8.0", validate_stderr="\\033[1;91merror\\033[0m: Unexpected file x.txt\\n")
    code, out, _ = run([fmu_path, "--master", "fmusim", "--experiment", "smoke"], capsys)
    assert "validate" in log.read_text()
    line = next(x for x in out.splitlines() if x.startswith("FAIL fmusim-validate"))
    assert "1 error line(s): error: Unexpected file x.txt" in line, line
    assert code == 1


def test_legacy_fmusim_command_lines(fmu_path, tmp_path, monkeypatch, capsys):
    """Reference-FMUs' fmusim v0.0.39 (no --version): one command line, `--start-value NAME VALUE`,
    no validate."""
    log = stand_in(tmp_path, monkeypatch, "")
    code, out, _ = run([fmu_path, "--master", "fmusim", "--experiment", "fvs"], capsys)
    calls = log.read_text().splitlines()
    assert calls[0] == "--version" and len(calls) == 2, calls
    simulate = calls[1].split()
    assert simulate[0] == "--interface-type" and not any(c.split()[0] == "validate" for c in calls), calls
    k = simulate.index("element")
    assert simulate[k - 1] == "--start-value" and simulate[k + 1] == "2", calls[1]
    assert "fmusim-validate" not in out and code == 1


def test_current_fmusim_end_to_end(fmu_path):
    """The real fmusim 0.8 where it is found: its validate is clean and it replays the smoke and
    state experiments within their tolerances."""
    fmusim = validate.find_fmusim()
    if fmusim is None or not validate.is_current(validate.fmusim_version(fmusim)):
        pytest.skip("no fmusim >= 0.8 found ($FMUSIM, PATH, .deps/fmusim/bin/fmusim)")
    _, _, results = validate.validate(fmu_path, ("fmusim",), ["smoke", "forced_state"], log=lambda _: None)
    assert [r.experiment for r in results] == ["fmusim-validate", "smoke", "forced_state"]
    assert all(r.passed for r in results), [validate.format_result(r) for r in results if not r.passed]
