"""Writes the reference experiments of python/plateimpact/references.py (FMI-LS-REF) from the FMU
itself, at build time (fmu/cmake/References.cmake): each experiment's parameters, stimuli and
reference result with the tolerance of every compared output, the manifest and
documentation/fmi-ls-ref.html, then adds them to the FMUs.

How a reference and its tolerances are made (`generate`):
  1. the reference: the experiment replayed through fmpy's simulate_fmu on the FMI 2.0 FMU as
     built — exactly what a generic master does (inputs from the CSV at the communication points,
     no input derivatives: base_input_mode and load_input_mode extrapolate them inside the step);
  2. the spread: the same experiment (a) on the FMI 3.0 FMU (another binary, another master
     path), (b) with rounding-level noise on every stimulus sample (relative 2^-50 of the
     input's scale, two seeds; on the release scene, which has no time-varying input, on the
     initial load): what another compiler, CPU or libm changes in the last bits, grown through
     the experiment's impacts;
  3. the tolerance of each output: SAFETY x the largest deviation of (a) and (b) from the
     reference, at least FLOOR x the output's scale (max |reference|) and never below TINY.
What FLOOR covers, measured (never bit-identity):
  - masters: fmusim against fmpy on these experiments, at most 4e-16 of an output's scale (its
    CSV's last digit) and 7.3e-7 of a tolerance (tools/reference_spreads.py);
  - platforms: win64 against linux64 bit for bit on the same input bits (python_tests/
    test_win64.py); aarch64 against x86-64 on the default scene for 0.1 s at most 4.5e-8
    (corner_1) and 1.1e-7 (energy) of the output's scale (the C masters of python_tests/
    test_aarch64.py, main of 2026-11-25; 1.3e-8 and 3.0e-8 before issue 31; the cause: Eigen's NEON FMA), which the
    rounding-level noise of (b) does not reach (3e-10 on the smoke test): FLOOR = 1e-5 is 88 x
    that largest platform spread;
  - CPUs: the one CPU-dependent path (the modal kernel's x86-64-v3 clone, solver/plate/Kernels.h) runs
    only with modes > 0, which no experiment uses.


    python tools/write_references.py build/PlateImpact.fmu OUT_DIR --fmi3 build/fmi3/PlateImpact.fmu
"""

from __future__ import annotations

import argparse
import hashlib
import html
import json
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from plateimpact.references import (
    CHECKSUM_ANNOTATION,
    DOCUMENT,
    EXPERIMENT_TYPE,
    EXPERIMENTS,
    LS_DIR,
    MANIFEST,
    NOISE,
    SSV_NS,
    STATES,
    StateExperiment,
    deviation,
    read_csv,
    serialized_state,
    simulate,
    stimuli_table,
    uninterrupted_from,
)

LS_VERSION = "1.0.0-beta.1"
LS_DESCRIPTION = "Layered Standard providing information on related files included in an FMU."
SAFETY = 10.0  # tolerance = SAFETY x the largest measured spread ...
FLOOR = 1e-5  # ... at least FLOOR x the output's scale (88 x the largest platform spread measured) ...
TINY = 1e-15  # ... and never below TINY (in the output's unit)
SEEDS = (1, 2)


def sha3(path) -> str:
    return hashlib.sha3_256(Path(path).read_bytes()).hexdigest()


def fmt(x) -> str:
    """A float written so that reading it back gives the same double."""
    return repr(float(x))


def write_csv(path, table: np.ndarray):
    names = table.dtype.names
    lines = [",".join(f'"{n}"' for n in names)]
    lines += [",".join(fmt(row[n]) for n in names) for row in table]
    Path(path).write_text("\n".join(lines) + "\n")


def ssv_text(name, parameters: dict, types: dict) -> str:
    """An SSP 1.0 parameter set; `types` maps each parameter to its FMI type (Real, Integer,
    Enumeration, Boolean; an FMI 3.0 Int32/Float64 counts as Integer/Real)."""
    rows = []
    for key, value in parameters.items():
        kind = types[key]
        if kind == "Boolean":
            rows.append(f'<ssv:Boolean value="{"true" if value else "false"}"/>')
        elif kind in ("Integer", "Enumeration", "Int32"):
            rows.append(f'<ssv:Integer value="{int(value)}"/>')
        else:
            rows.append(f'<ssv:Real value="{fmt(value)}"/>')
    params = "\n".join(f"    <ssv:Parameter name={quoteattr(k)}>{r}</ssv:Parameter>" for k, r in zip(parameters, rows))
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<ssv:ParameterSet xmlns:ssv="{SSV_NS}" version="1.0" name={quoteattr(name)}>\n'
        "  <ssv:Parameters>\n" + (params + "\n" if params else "") + "  </ssv:Parameters>\n"
        "</ssv:ParameterSet>\n"
    )


def variable_types(fmu) -> dict:
    from fmpy import read_model_description

    return {v.name: v for v in read_model_description(str(fmu)).modelVariables}


def generate(fmu2, fmu3, out_dir, log=print) -> dict:
    """Writes the experiments, the manifest and documentation/fmi-ls-ref.html into out_dir (the
    FMU's root: out_dir/extra/..., out_dir/documentation/...). Returns the spreads measured."""
    out = Path(out_dir)
    ls = out / LS_DIR
    ls.mkdir(parents=True, exist_ok=True)
    (out / "documentation").mkdir(parents=True, exist_ok=True)
    variables = variable_types(fmu2)
    report = {}
    related = []
    for exp in EXPERIMENTS:
        params = dict(exp.parameters)
        stim = stimuli_table(exp)
        ref = simulate(fmu2, 0.0, exp.stop, exp.step, params, stim, exp.outputs)
        runs = {}
        if fmu3:
            runs["fmi3"] = simulate(fmu3, 0.0, exp.stop, exp.step, params, stim, exp.outputs)
        for seed in SEEDS:
            if exp.stimuli:
                runs[f"noise{seed}"] = simulate(
                    fmu2, 0.0, exp.stop, exp.step, params, stimuli_table(exp, seed), exp.outputs
                )
            else:
                p = dict(params)
                x = float(p[exp.perturb])
                p[exp.perturb] = x * (1.0 + (-1) ** seed * NOISE)
                runs[f"noise{seed}"] = simulate(fmu2, 0.0, exp.stop, exp.step, p, stim, exp.outputs)
        signals = {}
        for name in exp.outputs:
            scale = float(np.max(np.abs(ref[name])))
            spreads = {k: deviation(r, ref, name) for k, r in runs.items()}
            spread = max(spreads.values(), default=0.0)
            tol = max(SAFETY * spread, FLOOR * scale, TINY)
            signals[name] = {"tolerance": tol, "scale": scale, "spread": spreads}
        report[exp.name] = signals
        log(
            f"{exp.name}: "
            + ", ".join(
                f"{n} tol {s['tolerance']:.2e} (spread {max(s['spread'].values(), default=0):.1e}, scale {s['scale']:.2e})"
                for n, s in signals.items()
            )
        )

        files = write_experiment(ls, exp, params, stim, ref, signals, variables)
        related += files
    for st in STATES:
        related += write_state_experiment(ls, st, fmu2, fmu3, report, log)
    write_documentation(out / DOCUMENT, report)
    related.append(
        (
            "../../" + DOCUMENT,
            "document",
            "text/html",
            "What the reference experiments are, how they were made, how to replay them",
            None,
        )
    )
    write_manifest(out, related)
    return report


def write_experiment(ls: Path, exp, params, stim, ref, signals, variables):
    types = {k: (variables[k].type if k in variables else "Real") for k in params}
    (ls / f"{exp.name}.ssv").write_text(ssv_text(exp.name, params, types))
    files = [
        (
            f"{exp.name}.ssv",
            "parameter",
            "application/x-ssp-parameter-set",
            f"Parameters of experiment {exp.name}",
            exp.name,
        )
    ]
    stimuli_xml = ""
    if stim is not None:
        write_csv(ls / f"{exp.name}_in.csv", stim)
        stimuli_xml = f'  <Stimuli source="{exp.name}_in.csv"/>\n'
        files.append(
            (
                f"{exp.name}_in.csv",
                "other",
                "text/csv",
                f"Stimuli of experiment {exp.name} (the FMU's inputs at every communication point)",
                exp.name,
            )
        )
    cols = {"time": ref["time"]} | {n: ref[n] for n in exp.outputs}
    write_csv(ls / f"{exp.name}_ref.csv", np.rec.fromarrays(list(cols.values()), names=list(cols)))
    files.append((f"{exp.name}_ref.csv", "result", "text/csv", f"Reference result of experiment {exp.name}", exp.name))
    sig = "\n".join(
        f'    <Signal name="{n}" absoluteTolerance="{s["tolerance"]:.3e}" measuredSpread="{max(s["spread"].values(), default=0.0):.3e}"/>'
        for n, s in signals.items()
    )
    text = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<Experiment name="{exp.name}" startTime="0" stopTime="{fmt(exp.stop)}" stepSize="{fmt(exp.step)}"\n'
        f"    description={quoteattr(exp.description)}>\n"
        f'  <Parameters source="{exp.name}.ssv"/>\n'
        + stimuli_xml
        + f'  <References source="{exp.name}_ref.csv">\n{sig}\n  </References>\n'
        "</Experiment>\n"
    )
    (ls / f"{exp.name}.xml").write_text(text)
    files.insert(0, (f"{exp.name}.xml", f"experiment/{exp.role}", EXPERIMENT_TYPE, exp.description, exp.name))
    return files


def write_state_experiment(ls: Path, st: StateExperiment, fmu2, fmu3, report, log):
    """The state of experiment st.base at st.at (FMI 2.0 and 3.0 must write the same bytes), its
    continuation restored through fmpy as the reference (bit for bit where it was written), and
    the continuation's deviation from the uninterrupted run checked against st.base's tolerances."""
    exp = next(e for e in EXPERIMENTS if e.name == st.base)
    state = serialized_state(fmu2, exp, st.at)
    if fmu3 and serialized_state(fmu3, exp, st.at) != state:
        raise RuntimeError(f"{st.name}: the FMI 2.0 and FMI 3.0 FMUs serialize different states")
    state_file = f"{st.name}.fmustate"
    (ls / state_file).write_bytes(state)
    stim = stimuli_table(exp)
    cont = simulate(fmu2, st.at, exp.stop, exp.step, {}, stim, exp.outputs, fmu_state=state)
    uninterrupted = read_csv(ls / f"{exp.name}_ref.csv")
    signals = {}
    for name in exp.outputs:
        base = report[exp.name][name]
        d = deviation(uninterrupted_from(uninterrupted, st.at), cont, name)
        if not d <= base["tolerance"]:
            raise RuntimeError(
                f"{st.name}: {name} continues {d:.3e} from the uninterrupted run (tolerance {base['tolerance']:.3e})"
            )
        signals[name] = {"tolerance": base["tolerance"], "scale": base["scale"], "spread": {"uninterrupted": d}}
    report[st.name] = signals
    log(
        f"{st.name}: continuation vs uninterrupted "
        + ", ".join(f"{n} {s['spread']['uninterrupted']:.1e}" for n, s in signals.items())
    )
    cols = {"time": cont["time"]} | {n: cont[n] for n in exp.outputs}
    write_csv(ls / f"{st.name}_ref.csv", np.rec.fromarrays(list(cols.values()), names=list(cols)))
    sig = "\n".join(
        f'    <Signal name="{n}" absoluteTolerance="{s["tolerance"]:.3e}" measuredSpread="{s["spread"]["uninterrupted"]:.3e}"/>'
        for n, s in signals.items()
    )
    description = (
        f"The state of experiment {exp.name} at t = {st.at:g} s, serialized ({state_file}, written on "
        f"{' / '.join(st.platforms)}), restored in a new instance and run on to {exp.stop:g} s"
    )
    text = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<Experiment name="{st.name}" startTime="{fmt(st.at)}" stopTime="{fmt(exp.stop)}" stepSize="{fmt(exp.step)}"\n'
        f"    description={quoteattr(description)}>\n"
        f'  <InitialState source="{state_file}"/>\n'
        f'  <Stimuli source="{exp.name}_in.csv"/>\n'
        f'  <References source="{st.name}_ref.csv">\n{sig}\n  </References>\n'
        "</Experiment>\n"
    )
    (ls / f"{st.name}.xml").write_text(text)
    files = [(f"{st.name}.xml", "experiment/validation", EXPERIMENT_TYPE, description, st.name)]
    for platform in st.platforms:
        files.append(
            (
                state_file,
                f"serialized-state/{platform}",
                "application/octet-stream",
                f"Serialized FMU state of {exp.name} at t = {st.at:g} s ({platform})",
                st.name,
            )
        )
    files.append((f"{st.name}_ref.csv", "result", "text/csv", f"Reference result of experiment {st.name}", st.name))
    return files


def write_manifest(out: Path, related):
    ls = out / LS_DIR
    rows = []
    for source, role, mime, description, label in related:
        digest = sha3((ls / source).resolve())
        label_xml = f'\n    <Label name="experiment:{label}"/>' if label else ""
        rows.append(
            f"  <Related type={quoteattr(mime)} source={quoteattr(source)} role={quoteattr(role)} description={quoteattr(description)}>"
            f"{label_xml}\n"
            f'    <Annotations>\n      <Annotation type="{CHECKSUM_ANNOTATION}"><Checksum algorithm="SHA3-256" value="{digest}"/></Annotation>\n    </Annotations>\n'
            "  </Related>"
        )
    text = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        "<fmiReferences\n"
        '    xmlns:fmi-ls="http://fmi-standard.org/fmi-ls-manifest"\n'
        '    fmi-ls:fmi-ls-name="org.fmi-standard.fmi-ls-ref"\n'
        f'    fmi-ls:fmi-ls-version="{LS_VERSION}"\n'
        f'    fmi-ls:fmi-ls-description="{LS_DESCRIPTION}">\n' + "\n".join(rows) + "\n</fmiReferences>\n"
    )
    (out / MANIFEST).write_text(text)


def write_documentation(path: Path, report: dict):
    rows = []
    for exp in EXPERIMENTS:
        sig = report[exp.name]
        tols = "<br>".join(
            f"{html.escape(n)}: {s['tolerance']:.2e} (spread {max(s['spread'].values(), default=0.0):.1e}, scale {s['scale']:.2e})"
            for n, s in sig.items()
        )
        params = ", ".join(f"{k} = {v}" for k, v in exp.parameters.items()) or "(defaults)"
        stim = ", ".join(exp.stimuli) or "none"
        rows.append(
            f"<tr><td>{exp.name}</td><td>experiment/{exp.role}</td><td>{html.escape(exp.description)}</td>"
            f"<td>{html.escape(params)}</td><td>{stim}</td><td>{tols}</td></tr>"
        )
    text = f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>PlateImpact: reference experiments (FMI-LS-REF)</title></head>
<body>
<h1>Reference experiments (FMI-LS-REF {LS_VERSION})</h1>
<p>This FMU carries its own reference experiments in <code>{LS_DIR}/</code>, listed by role in
<code>fmi-ls-manifest.xml</code> (each file with its SHA3-256 checksum as an annotation of type
<code>{CHECKSUM_ANNOTATION}</code>). The FMI 2.0 and FMI 3.0 FMUs carry the same files.</p>
<p>Each experiment is one <code>&lt;name&gt;.xml</code> (role <code>experiment/smoke-test</code> or
<code>experiment/validation</code>, type <code>{EXPERIMENT_TYPE}</code>): start time, stop time and
communication step, its parameters (<code>&lt;name&gt;.ssv</code>, SSP 1.0; every other variable keeps its
start value), its stimuli (<code>&lt;name&gt;_in.csv</code>: the inputs at every communication point; a
master applies them at the communication points and gives no input derivatives, the FMU extrapolates
them inside a step as base_input_mode / load_input_mode say) and its reference result
(<code>&lt;name&gt;_ref.csv</code>) with an absolute tolerance per output. An output passes when
max over the reference's times of |result - reference| is within its tolerance.</p>
<h2>How the references and tolerances were made</h2>
<p>At build time, from this FMU: the reference is the experiment replayed through fmpy (simulate_fmu) on
the FMI 2.0 FMU. The spread is the largest deviation from it of (a) the FMI 3.0 FMU (another binary,
another master path) and (b) the experiment with rounding-level noise ({NOISE:.1e} of the input's scale)
on every stimulus sample (two seeds; on the release scene, on the initial load): what another
compiler, CPU or libm changes in the last bits, grown through the impacts of the experiment.
The tolerance is {SAFETY:g} x that spread, at least {FLOOR:g} x the output's scale (max |reference|).
That floor comes from measurements: fmusim against fmpy differs by at most 4e-16 of an output's scale;
the win64 binary under Wine computes the same bits as linux64 from the same inputs; the aarch64 binary
(under qemu) parts from x86-64 in the last bits and the impacts grow that to 4.5e-8 (corner_1) and
1.1e-7 (energy) of the scale over 0.1 s of the default scene: the floor is 88 times that.
Impacts make a vibro-impact plate sensitive to such bits: expect agreement within the tolerance,
never bit for bit, on another master, platform or CPU.</p>
<h2>How to replay them</h2>
<pre>pip install fmpy lxml
python -m plateimpact.validate PlateImpact.fmu        # the plateimpact package of the repository</pre>
<p>or with any master: set the SSV's parameters, feed the stimuli CSV, run from startTime to stopTime
at stepSize and compare the outputs named in the experiment's References with the reference CSV.</p>
<h2>The serialized state</h2>
<p>{"".join(f"<code>{st.name}.fmustate</code> is the state of experiment {st.base} at t = {st.at:g} s, serialized through fmiXSerializeFMUState (FMI 2.0 and FMI 3.0 write the same bytes); experiment <code>{st.name}</code> restores it in a new instance (fmiXDeSerializeFMUState and fmiXSetFMUState right after instantiation, no initialization: the parameters are the state's) and runs on to {next(e for e in EXPERIMENTS if e.name == st.base).stop:g} s with the stimuli of {st.base}. Its reference is that continuation as restored where the state was written (so this project's fmpy-based replay on that platform is bit for bit; another master restores and steps it with its own time grid and lands within the tolerances, not on the same bits: fmusim 6e-7 to 9e-7 N on the clamp outputs); at build time it was checked against the uninterrupted run of {st.base} within that experiment's tolerances (largest deviation {max(v['spread']['uninterrupted'] / v['tolerance'] for v in report[st.name].values()):.1e} of the tolerance). The manifest lists the file once per platform it was written on (role serialized-state/&lt;platform&gt;); a binary of the same CPU architecture on another system continues it (x86_64-windows: the same bits), one of another architecture refuses it at fmiXDeSerializeFMUState, naming both platforms (the state's header records the platform that wrote it). " for st in STATES)}
With fmusim, one that restores states: Reference-FMUs fmusim v0.0.39 crashes there (SIGSEGV: its
fmusim/FMIUtil.c hands FreeFMUState the state instead of its address); use v0.0.39 with that one call
patched (the repository's scripts/build-fmusim.sh patches it) or the standalone fmusim 0.8 or newer
(https://github.com/modelica/fmusim, <code>fmusim simulate ...</code>):
<code>fmusim --initial-fmu-state-file {STATES[0].name}.fmustate --start-time {STATES[0].at:g} ...</code>.</p>
<h2>The experiments</h2>
<table border="1" cellpadding="3">
<tr><th>name</th><th>role</th><th>what</th><th>parameters</th><th>stimuli</th><th>tolerance per output</th></tr>
{chr(10).join(rows)}
</table>
</body></html>
"""
    path.write_text(text)


def add_tree(tree, target):
    """Adds the generated files (tree/extra/..., tree/documentation/fmi-ls-ref.html) to an FMU:
    a .fmu file is rewritten with them (entries of the same name replaced), a directory (an
    extracted FMU, a packaging stage) gets them copied in."""
    import shutil
    import zipfile

    tree, target = Path(tree), Path(target)
    files = sorted(p for p in tree.rglob("*") if p.is_file())
    names = {p.relative_to(tree).as_posix(): p for p in files}
    if target.is_dir():
        for name, p in names.items():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(p, target / name)
        return
    tmp = target.with_name(target.name + ".tmp")
    with zipfile.ZipFile(target) as src, zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as dst:
        for item in src.infolist():
            if item.filename not in names:
                dst.writestr(item, src.read(item.filename))
        for name, p in names.items():
            dst.write(p, name)
    tmp.replace(target)


def main(argv=None):
    ap = argparse.ArgumentParser(description="Generate the FMI-LS-REF reference experiments from the FMU itself")
    ap.add_argument("fmu2", help="the FMI 2.0 FMU (file or extracted directory): the reference")
    ap.add_argument("--fmi3", help="the FMI 3.0 FMU (file or directory): one of the spreads")
    ap.add_argument("out", help="output directory (the FMU's root: extra/ and documentation/ are written into it)")
    ap.add_argument("--report", help="write the measured spreads and tolerances as JSON here")
    ap.add_argument("--add-to", nargs="*", default=[], help="FMUs (.fmu files or directories) to add the files to")
    args = ap.parse_args(argv)
    report = generate(args.fmu2, args.fmi3, args.out)
    if args.report:
        Path(args.report).write_text(json.dumps(report, indent=1))
    for target in args.add_to:
        add_tree(args.out, target)


if __name__ == "__main__":
    main()
