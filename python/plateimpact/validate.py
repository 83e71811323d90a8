"""Validate an FMU against the reference experiments it carries (FMI-LS-REF).

    python -m plateimpact.validate PlateImpact.fmu [--master fmpy|fmusim|all] [--experiment NAME]
    plateimpact-validate PlateImpact.fmu

Reads extra/org.fmi-standard.fmi-ls-ref/fmi-ls-manifest.xml of any FMU (FMI 2.0 or 3.0),
checks each listed file's SHA3-256 checksum where the manifest gives one, and replays every
experiment it can run (role experiment..., type application/x-plateimpact-experiment+xml: see
documentation/fmi-ls-ref.html of the FMU) through fmpy, and through fmusim when it is found
(on the PATH, at $FMUSIM, or at .deps/fmusim/bin/fmusim of the repository): the standalone
fmusim (>= 0.8, https://github.com/modelica/fmusim: `fmusim simulate ...`, and `fmusim validate`
of the FMU file, whose `error:` lines fail the validation although it exits 0 on some of them) or
Reference-FMUs' fmusim v0.0.39 (its one command line), told apart by `fmusim --version`. Prints pass/fail per
output with its deviation and tolerance; exit status 0 when everything passed, 1 when something
failed, 2 when the FMU cannot be validated: missing, no manifest, no binary for this platform
(a source-only FMU: build it first), an unknown --experiment, or --master fmusim without fmusim.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import zipfile
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

import numpy as np

from .references import CHECKSUM_ANNOTATION, EXPERIMENT_TYPE, MANIFEST, deviation, read_csv, read_ssv, typed


class ValidationError(Exception):
    """The FMU cannot be validated at all (missing, not an FMU, no manifest, broken manifest)."""


@dataclass
class Related:
    source: str  # as written in the manifest
    path: str  # inside the FMU archive
    role: str
    type: str
    description: str
    checksum: str | None  # SHA3-256, hex


@dataclass
class SignalResult:
    name: str
    deviation: float
    tolerance: float

    @property
    def passed(self):
        return bool(np.isfinite(self.deviation) and self.deviation <= self.tolerance)


@dataclass
class ExperimentResult:
    experiment: str
    master: str
    role: str
    signals: list = field(default_factory=list)
    error: str | None = None

    @property
    def passed(self):
        return self.error is None and all(s.passed for s in self.signals)


def read_manifest(fmu: Path):
    """The manifest's Related entries of an FMU (a .fmu file or an extracted directory)."""
    from lxml import etree

    if not fmu.exists():
        raise ValidationError(f"FMU not found: {fmu}")
    try:
        text = _read(fmu, MANIFEST)
    except KeyError:
        raise ValidationError(f"{fmu} carries no FMI-LS-REF manifest ({MANIFEST})") from None
    except zipfile.BadZipFile:
        raise ValidationError(f"{fmu} is not an FMU (not a ZIP archive)") from None
    try:
        root = etree.fromstring(text)
    except etree.XMLSyntaxError as e:
        raise ValidationError(f"{MANIFEST} of {fmu} is not well-formed XML: {e}") from None
    base = PurePosixPath(MANIFEST).parent
    out = []
    for r in root.findall("Related"):
        source = r.get("source")
        checksum = None
        for a in r.findall("Annotations/Annotation"):
            if a.get("type") == CHECKSUM_ANNOTATION:
                c = a.find("Checksum")
                if c is not None and c.get("algorithm", "").upper() == "SHA3-256":
                    checksum = c.get("value")
        out.append(
            Related(
                source,
                _normalize(base / source) if "://" not in source else source,
                r.get("role"),
                r.get("type", "application/octet-stream"),
                r.get("description", ""),
                checksum,
            )
        )
    return out


def _normalize(p: PurePosixPath) -> str:
    parts = []
    for part in p.parts:
        if part == "..":
            if parts:
                parts.pop()
        elif part != ".":
            parts.append(part)
    return "/".join(parts)


def _read(fmu: Path, member: str) -> bytes:
    if fmu.is_dir():
        path = fmu / member
        if not path.is_file():
            raise KeyError(member)
        return path.read_bytes()
    with zipfile.ZipFile(fmu) as z:
        return z.read(member)


def check_checksums(fmu: Path, related):
    """[(path, ok, message)] for every entry with a checksum."""
    out = []
    for r in related:
        if r.checksum is None:
            continue
        try:
            digest = hashlib.sha3_256(_read(fmu, r.path)).hexdigest()
        except KeyError:
            out.append((r.path, False, "listed in the manifest but missing from the FMU"))
            continue
        ok = digest == r.checksum.lower()
        out.append((r.path, ok, "SHA3-256 ok" if ok else f"SHA3-256 {digest} != manifest's {r.checksum}"))
    return out


@dataclass
class Experiment:
    name: str
    role: str
    start: float
    stop: float
    step: float
    parameters: dict  # name -> (ssv type, text)
    stimuli: Path | None
    reference: Path
    tolerances: dict  # output -> absolute tolerance
    state: Path | None = None  # a serialized FMU state to start from instead of initializing


def load_experiments(fmu: Path, related, workdir: Path):
    """The runnable experiments (their files extracted to workdir) and the skipped entries."""
    from lxml import etree

    runnable, skipped = [], []
    for r in related:
        if not (r.role or "").startswith("experiment"):
            continue
        if r.type != EXPERIMENT_TYPE:
            skipped.append((r.path, f"experiment of type {r.type}: not a format this validator runs"))
            continue
        root = etree.fromstring(_read(fmu, r.path))
        base = PurePosixPath(r.path).parent

        def extract(source):
            member = _normalize(base / source)
            target = workdir / member.replace("/", "__")
            target.write_bytes(_read(fmu, member))
            return target

        params = {}
        for p in root.findall("Parameters"):
            params.update(read_ssv(extract(p.get("source"))))
        stim = root.find("Stimuli")
        refs = root.find("References")
        init = root.find("InitialState")
        runnable.append(
            Experiment(
                root.get("name"),
                r.role,
                float(root.get("startTime", "0")),
                float(root.get("stopTime")),
                float(root.get("stepSize")),
                params,
                extract(stim.get("source")) if stim is not None else None,
                extract(refs.get("source")),
                {s.get("name"): float(s.get("absoluteTolerance")) for s in refs.findall("Signal")},
                extract(init.get("source")) if init is not None else None,
            )
        )
    return runnable, skipped


def platform_binaries(fmu: Path, md) -> tuple[list, bool]:
    """(the binaries/ folders the FMU has, whether one is this platform's)."""
    import fmpy

    if fmu.is_dir():
        folders = sorted(p.name for p in (fmu / "binaries").iterdir()) if (fmu / "binaries").is_dir() else []
    else:
        with zipfile.ZipFile(fmu) as z:
            folders = sorted({n.split("/")[1] for n in z.namelist() if n.startswith("binaries/") and n.count("/") >= 2})
    here = fmpy.platform if md.fmiVersion.startswith("2") else fmpy.platform_tuple
    return folders, here in folders


def check_runnable(fmu: Path, md):
    """A ValidationError when the FMU has no binary for this platform (a source-only FMU says how to build it)."""
    import fmpy

    folders, ok = platform_binaries(fmu, md)
    if ok:
        return
    here = fmpy.platform if md.fmiVersion.startswith("2") else fmpy.platform_tuple
    try:
        has_sources = bool(_read(fmu, "sources/buildDescription.xml"))
    except (KeyError, zipfile.BadZipFile):
        has_sources = False
    if has_sources:
        raise ValidationError(
            f"{fmu} has no binary for {here}, only sources: build it first (unzip it to DIR, "
            f"`cmake -S DIR/sources -B build && cmake --build build`, then validate DIR; or "
            f"fmpy.build.build_platform_binary(DIR))"
        )
    raise ValidationError(f"{fmu} has no binary for {here} (it has: {', '.join(folders) or 'none'})")


FMUSIM_HINT = (
    "a fmusim on the PATH, at $FMUSIM or at .deps/fmusim/bin/fmusim (the standalone fmusim >= 0.8, "
    "https://github.com/modelica/fmusim, or scripts/build-fmusim.sh's Reference-FMUs v0.0.39 with its "
    "FreeFMUState fix); or --master fmpy"
)

# The first fmusim with subcommands (simulate, validate): the standalone one, modelica/fmusim 0.8.
CURRENT_FMUSIM = (0, 8)


def fmusim_version(fmusim: str):
    """(major, minor, patch) that `fmusim --version` prints ("fmusim 0.8.0"), or None when it prints
    no version (Reference-FMUs' v0.0.39 has no --version and is taken for what it is)."""
    try:
        proc = subprocess.run([fmusim, "--version"], capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired):
        return None
    match = re.search(r"fmusim\s+v?(\d+)\.(\d+)\.(\d+)", proc.stdout + proc.stderr)
    return tuple(int(x) for x in match.groups()) if match and proc.returncode == 0 else None


def is_current(version) -> bool:
    """Whether a fmusim of that version speaks the standalone fmusim's command lines."""
    return version is not None and version[:2] >= CURRENT_FMUSIM


def fmusim_errors(stderr: str):
    """The `error:` lines of a fmusim's stderr (colours stripped): fmusim 0.8's `validate` prints its
    ZIP, schema and buildDescription problems so and still exits 0."""
    plain = re.sub(r"\x1b\[[0-9;]*m", "", stderr)
    return [line.strip() for line in plain.splitlines() if line.strip().startswith("error:")]


def run_fmusim_validate(fmusim: str, fmu: Path) -> ExperimentResult:
    """`fmusim validate FMU` (fmusim >= 0.8): its checks of the archive, the model and the build
    description, as one result: failed on a non-zero exit or any `error:` line."""
    res = ExperimentResult("fmusim-validate", "fmusim", "the FMU file: ZIP, schemas, structure")
    proc = subprocess.run([fmusim, "validate", str(fmu)], capture_output=True, text=True, timeout=600)
    errors = fmusim_errors(proc.stderr)
    if proc.returncode != 0 or errors:
        res.error = f"fmusim validate exited with {proc.returncode}" + (
            f"; {len(errors)} error line(s): " + " | ".join(errors) if errors else f": {proc.stderr.strip()[-300:]}"
        )
    return res


def find_fmusim():
    for candidate in (
        os.environ.get("FMUSIM"),
        shutil.which("fmusim"),
        str(Path(__file__).resolve().parents[2] / ".deps/fmusim/bin/fmusim"),
    ):
        if candidate and Path(candidate).is_file() and os.access(candidate, os.X_OK):
            return candidate
    return None


def run_fmpy(fmu: Path, exp: Experiment, variables):
    from .references import simulate

    start_values = {k: typed(v, kind, variables.get(k)) for k, (kind, v) in exp.parameters.items()}
    stimuli = read_csv(exp.stimuli) if exp.stimuli else None
    state = exp.state.read_bytes() if exp.state else None
    return simulate(fmu, exp.start, exp.stop, exp.step, start_values, stimuli, list(exp.tolerances), fmu_state=state)


def probe_arrays(exp: Experiment, variables) -> bool:
    """The experiment names the FMI 2.0 FMU's scalar probes and the FMU has them as arrays (FMI 3.0)."""
    from .references import uses_probes

    return "probe_x" in variables and uses_probes(exp.parameters, exp.tolerances)


def start_values_as_arrays(exp: Experiment, variables) -> list:
    """(name, fmusim literal) of the experiment's start values, the scalar probes as the FMI 3.0 FMU's
    structural parameter probe_count (fmusim sets it in Configuration Mode) and arrays probe_x, probe_y
    (space-separated values, as fmusim 0.8 reads arrays); none of them when a state is restored."""
    from .references import SCALAR_PROBE

    plain = {k: kv for k, kv in exp.parameters.items() if k != "probe_count" and not SCALAR_PROBE.match(k)}
    pairs = [(k, literal(typed(v, kind, variables.get(k)))) for k, (kind, v) in plain.items()]
    if exp.state:  # the state carries the count and the places; Configuration Mode is before it
        return pairs
    count = int(float(exp.parameters.get("probe_count", ("Integer", "0"))[1]))
    pairs.insert(0, ("probe_count", str(count)))
    for axis in ("_x", "_y"):
        places = [float(exp.parameters.get(f"probe_{k + 1}{axis}", ("Real", "0"))[1]) for k in range(count)]
        pairs.append((f"probe{axis}", " ".join(repr(x) for x in places)))
    return pairs


def literal(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value) if isinstance(value, float) else str(value)


def fmusim_command(fmusim: str, current: bool, fmu: Path, exp: Experiment, variables, out: Path):
    """The command line that replays `exp`: `fmusim simulate ... --start-value NAME=VALUE` for the
    standalone fmusim (current), `fmusim ... --start-value NAME VALUE` for v0.0.39. The scalar probes
    of an FMI 2.0 experiment on the FMI 3.0 FMU: its probe_count and arrays (start_values_as_arrays)."""
    from .references import ARRAY_OF, SCALAR_PROBE

    arrays = probe_arrays(exp, variables)
    cmd = [fmusim, "simulate"] if current else [fmusim]
    cmd += ["--interface-type", "cs", "--start-time", repr(exp.start), "--stop-time", repr(exp.stop)]
    cmd += ["--output-interval", repr(exp.step), "--output-file", str(out)]
    if arrays:
        pairs = start_values_as_arrays(exp, variables)
    else:
        pairs = [(k, literal(typed(v, kind, variables.get(k)))) for k, (kind, v) in exp.parameters.items()]
    for k, value in pairs:
        cmd += ["--start-value", f"{k}={value}"] if current else ["--start-value", k, value]
    if exp.state:
        cmd += ["--initial-fmu-state-file", str(exp.state)]
    if exp.stimuli:
        cmd += ["--input-file", str(exp.stimuli)]
    outputs = list(exp.tolerances)
    if arrays:
        scalars = [n for n in outputs if not SCALAR_PROBE.match(n)]
        kinds = {ARRAY_OF[SCALAR_PROBE.match(n).group(2)] for n in outputs if SCALAR_PROBE.match(n)}
        outputs = scalars + sorted(kinds)
    for name in outputs:
        cmd += ["--output-variable", name]
    cmd.append(str(fmu))
    return cmd


def read_fmusim_arrays(path: Path, exp: Experiment):
    """fmusim 0.8's CSV with array columns (their values space-separated in one field), the arrays
    probe, probe_velocity, probe_acceleration read back as the experiment's probe_<k>... columns."""
    import csv as csvmodule

    from .references import ARRAY_OF, SCALAR_PROBE

    with open(path, newline="") as f:
        rows = list(csvmodule.reader(f))
    header, body = rows[0], [r for r in rows[1:] if r]
    columns = {name: [[float(x) for x in r[i].split()] for r in body] for i, name in enumerate(header)}
    out = {"time": np.array([c[0] for c in columns["time"]])}
    for name in exp.tolerances:
        m = SCALAR_PROBE.match(name)
        source = ARRAY_OF[m.group(2)] if m else name
        k = int(m.group(1)) - 1 if m else 0
        out[name] = np.array([c[k] for c in columns[source]])
    return np.rec.fromarrays(list(out.values()), names=list(out))


def run_fmusim(fmusim: str, fmu: Path, exp: Experiment, variables, workdir: Path, current: bool):
    out = workdir / f"{exp.name}_fmusim.csv"
    proc = subprocess.run(
        fmusim_command(fmusim, current, fmu, exp, variables, out), capture_output=True, text=True, timeout=600
    )
    errors = fmusim_errors(proc.stderr) if current else []
    if proc.returncode != 0 or errors:
        raise RuntimeError(fmusim_failure(proc.returncode, proc.stderr or proc.stdout, exp))
    return read_fmusim_arrays(out, exp) if probe_arrays(exp, variables) else read_csv(out)


def fmusim_failure(returncode: int, output: str, exp: Experiment) -> str:
    """What a failed fmusim run means: its exit status or the signal that killed it, the likely cause, its last output."""
    tail = output.strip()[-300:]
    if returncode >= 0:
        return f"fmusim exited with {returncode}: {tail}"
    try:
        name = signal.Signals(-returncode).name
    except ValueError:
        name = f"signal {-returncode}"
    text = f"fmusim crashed ({name})"
    if exp.state is not None and -returncode in (signal.SIGSEGV, signal.SIGABRT, signal.SIGBUS):
        text += (
            " restoring the FMU state: Reference-FMUs fmusim v0.0.39 passes the state instead of its address "
            "to FreeFMUState (fmusim/FMIUtil.c) and crashes there; use a fmusim that restores states: "
            "v0.0.39 with that call patched (scripts/build-fmusim.sh) or the standalone fmusim >= 0.8 "
            "(https://github.com/modelica/fmusim)"
        )
    else:
        text += ": a crash of the master or of the FMU; rerun with fmpy (--master fmpy) to tell which"
    return text + (f"; its last output: {tail}" if tail else "")


def validate(fmu, masters=("fmpy", "fmusim"), only=None, log=print):
    """Checks and replays; returns (checksum results, skipped, [ExperimentResult])."""
    from fmpy import read_model_description

    fmu = Path(fmu)
    related = read_manifest(fmu)
    sums = check_checksums(fmu, related)
    md = read_model_description(str(fmu))
    variables = {v.name: v for v in md.modelVariables}
    check_runnable(fmu, md)
    fmusim = find_fmusim() if "fmusim" in masters else None
    if masters == ("fmusim",) and fmusim is None:
        raise ValidationError(f"--master fmusim: fmusim not found; {FMUSIM_HINT}")
    results = []
    with tempfile.TemporaryDirectory(prefix="plateimpact-validate-") as tmp:
        work = Path(tmp)
        experiments, skipped = load_experiments(fmu, related, work)
        unknown = sorted(set(only or ()) - {e.name for e in experiments})
        if unknown:
            raise ValidationError(
                f"no experiment {', '.join(unknown)} in {fmu}; it carries: {', '.join(e.name for e in experiments)}"
            )
        if "fmusim" in masters and fmusim is None:
            skipped.append(("fmusim", f"not found: replayed through fmpy only (for fmusim too: {FMUSIM_HINT})"))
        current = fmusim is not None and is_current(fmusim_version(fmusim))
        if current and fmu.is_file():
            results.append(run_fmusim_validate(fmusim, fmu))
            log(format_result(results[-1]))
        elif current:
            skipped.append(("fmusim validate", f"{fmu} is a folder; fmusim validate checks FMU files (.fmu)"))
        for exp in experiments:
            if only and exp.name not in only:
                continue
            reference = read_csv(exp.reference)
            runners = []
            if "fmpy" in masters:
                runners.append(("fmpy", lambda e=exp: run_fmpy(fmu, e, variables)))
            if fmusim:
                runners.append(("fmusim", lambda e=exp: run_fmusim(fmusim, fmu, e, variables, work, current)))
            for master, run in runners:
                res = ExperimentResult(exp.name, master, exp.role)
                try:
                    result = run()
                    for name, tol in exp.tolerances.items():
                        res.signals.append(SignalResult(name, deviation(result, reference, name), tol))
                except Exception as e:  # a crash of the FMU or the master fails this experiment
                    res.error = f"{type(e).__name__}: {e}"
                results.append(res)
                log(format_result(res))
    return sums, skipped, results


def format_result(res: ExperimentResult) -> str:
    head = f"{'PASS' if res.passed else 'FAIL'} {res.experiment} ({res.role}, {res.master})"
    if res.error:
        return f"{head}: {res.error}"
    lines = [head]
    for s in res.signals:
        lines.append(
            f"  {'ok  ' if s.passed else 'FAIL'} {s.name:<24} deviation {s.deviation:.3e}  tolerance {s.tolerance:.3e}"
        )
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="plateimpact-validate", description="Replay the reference experiments an FMU carries (FMI-LS-REF)"
    )
    ap.add_argument("fmu", help="the FMU (.fmu file or extracted directory)")
    ap.add_argument("--master", choices=("fmpy", "fmusim", "all"), default="all")
    ap.add_argument("--experiment", action="append", help="only this experiment (repeatable)")
    args = ap.parse_args(argv)
    masters = ("fmpy", "fmusim") if args.master == "all" else (args.master,)
    try:
        sums, skipped, results = validate(args.fmu, masters, args.experiment)
    except ValidationError as e:
        print(f"plateimpact-validate: {e}", file=sys.stderr)
        return 2
    for path, ok, message in sums:
        if not ok:
            print(f"FAIL checksum {path}: {message}")
    for what, why in skipped:
        print(f"skipped {what}: {why}")
    bad_sums = sum(1 for _, ok, _ in sums if not ok)
    failed = sum(1 for r in results if not r.passed)
    print(
        f"{len(results) - failed} passed, {failed} failed ({len(sums) - bad_sums} of {len(sums)} checksums ok, "
        f"{len(results)} experiment runs)"
    )
    return 0 if failed == 0 and bad_sums == 0 and results else 1


if __name__ == "__main__":
    sys.exit(main())
