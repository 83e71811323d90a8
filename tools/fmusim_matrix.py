"""Runs PlateImpact's FMI 3 and FMI 2 FMUs through fmusim (the modelica Reference-FMUs' simulator,
built by scripts/build-fmusim.sh) and through fmpy with the same options, on the default scene,
and prints what each run measured: the issue 31 table of the reference FMI 3 master.

    .venv/bin/python tools/fmusim_matrix.py [--json out/fmusim_matrix.json]

Why: fmusim is the call sequence an FMI 3 user meets first (its event mode enters step mode again
without setting the continuous inputs), fmpy the one the project's tests use; a difference
between the two, or between a mode and the plain run, is the FMU's to explain.

The scene: base_displacement = 0.09 sin(2 pi 10 t) m (plateimpact.default_base) tabulated every
--step (1e-4 s) up to --stop-time (0.2 s) in one CSV that both masters interpolate linearly;
communication (output) interval = --step. Only base_displacement is given: base_velocity and
base_acceleration are separate inputs of other base_drive values, not its derivatives, and
fmusim cannot set FMI 2 input derivatives, so neither master sets them (the FMU reconstructs the
base inside a step by base_input_mode). fmpy runs with set_stop_time=False like fmusim.

Rows, for each FMU: each mode (plain; --early-return-allowed; --early-return-allowed
--event-mode-used) with each set of start values (defaults, i.e. base_input_mode = quadratic;
base_input_mode = linear; hold; mass = 2 with time_scheme = 2), then --record-intermediate-values
and the FMU-state round trip (--final-fmu-state-file at half the stop time, then
--initial-fmu-state-file from it to the end, against the straight run; fmpy: serialize, new
instance, deserialize). FMI 2 has neither early return, event mode nor intermediate update: both
masters ignore those options there (fmpy's simulate_fmu has no intermediate update either: this
tool instantiates fmpy's FMU3Slave with the callback itself).

Columns: energy at the stop time (last sample); its ratio to the plain run with the same start
values and master (for the round trip: to the straight plain run), and to fmpy's run with the
same options; max |corner_1| over all samples minus the obstacle gap min(obstacle_upper,
-obstacle_lower) (> 0: through an obstacle; fmusim writes 16 digits); the events (repeated sample times) and off-grid samples (early returns) fmusim
recorded. Every number is measured in this run.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import io
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
RECORDED = ("corner_1", "corner_2", "energy")
EVENT = ["--early-return-allowed", "--event-mode-used"]
MODES = {  # label: (fmusim options, fmpy simulate_fmu options)
    "plain": ([], {}),
    "early return": (["--early-return-allowed"], {"early_return_allowed": True}),
    "early return + event mode": (EVENT, {"early_return_allowed": True, "use_event_mode": True}),
}
START_SETS = {  # label: start values (a switch's item by name)
    "": {},
    "base_input_mode = linear": {"base_input_mode": "linear"},
    "base_input_mode = hold": {"base_input_mode": "hold"},
    "mass = 2, time_scheme = 2": {"mass": 2, "time_scheme": 2},
}


class Run:
    """One master's run: its samples (time and RECORDED, one row each) or why there are none."""

    def __init__(self, rows=None, error=None):
        self.rows = np.asarray(rows if rows is not None else np.empty((0, 1 + len(RECORDED))), dtype=float)
        self.error = error

    def column(self, name):
        return self.rows[:, 1 + RECORDED.index(name)]

    @property
    def ok(self):
        return self.error is None and len(self.rows) > 0

    def energy(self):
        return float(self.column("energy")[-1]) if self.ok else math.nan

    def max_corner(self):
        return float(np.max(np.abs(self.column("corner_1")))) if self.ok else math.nan

    def counts(self, step):
        """(events, off-grid samples): repeated sample times, and times off the step grid."""
        if not self.ok:
            return 0, 0
        t = self.rows[:, 0]
        events = int(np.sum(np.diff(t) == 0))
        off = int(np.sum(np.abs(t / step - np.round(t / step)) > 1e-6))
        return events, off

    @staticmethod
    def joined(first, second):
        if not (first.ok and second.ok):
            return Run(error=first.error or second.error or "no samples")
        return Run(np.vstack([first.rows, second.rows[1:]]))


# -- fmusim -------------------------------------------------------------------------------------
def run_fmusim(fmusim, fmu, input_csv, work, tag, options, start, t0, t1, step):
    out = work / f"fmusim-{tag}.csv"
    out.unlink(missing_ok=True)
    cmd = [str(fmusim), "--input-file", str(input_csv), "--output-interval", repr(step)]
    cmd += ["--start-time", repr(t0), "--stop-time", repr(t1), *options]
    for name, value in start.items():
        cmd += ["--start-value", name, str(value)]
    for name in RECORDED:
        cmd += ["--output-variable", name]
    cmd += ["--output-file", str(out), str(fmu)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=1800)
    (work / f"fmusim-{tag}.log").write_text(" ".join(cmd) + "\n" + proc.stdout + proc.stderr)
    error = None
    if proc.returncode >= 2:  # fmusim exits with the FMIStatus: 2 discard, 3 error, 4 fatal
        lines = [ln for ln in (proc.stdout + proc.stderr).splitlines() if ln.strip()]
        said = [ln for ln in lines if ln.startswith(("[Error]", "[Fatal]"))] or lines[-1:]
        error = f"fmusim status {proc.returncode}: " + (said[0] if said else "(no message)")
    rows = []
    if out.exists():
        with out.open() as f:
            reader = csv.reader(f)
            header = next(reader, [])
            index = [header.index(n) for n in ("time", *RECORDED)] if header else []
            rows = [[float(r[i]) for i in index] for r in reader if r]
    return Run(rows or None, error if rows or error else "fmusim wrote no samples")


# -- fmpy ---------------------------------------------------------------------------------------
class Fmpy:
    """fmpy's runs of one FMU (extracted once), with the FMU's log messages kept."""

    def __init__(self, fmu):
        from fmpy import extract, read_model_description

        self.md = read_model_description(str(fmu))
        self.unzip = extract(str(fmu))
        self.fmi3 = self.md.fmiVersion.startswith("3")
        self.log = []

    def _logger(self, *args):  # FMI 2: (env, name, status, category, message); FMI 3: (env, status, category, message)
        self.log.append(args[-1].decode(errors="replace") if args[-1] else "")

    def _error(self, exc):
        said = [m for m in self.log if m][-1:]
        return f"fmpy: {exc}" + (f" ({said[0]})" if said else "")

    def _simulate(self, signal, options, start, t0, t1, step, **more):
        from fmpy import simulate_fmu

        with contextlib.redirect_stdout(io.StringIO()):  # fmpy prints "missing input" for load etc.
            result = simulate_fmu(
                self.unzip,
                start_time=t0,
                stop_time=t1,
                output_interval=step,
                input=signal,
                output=list(RECORDED),
                start_values=start,
                set_stop_time=False,
                logger=self._logger,
                **options,
                **more,
            )
        return Run(np.column_stack([result["time"], *(result[n] for n in RECORDED)]))

    def run(self, signal, options, start, t0, t1, step):
        self.log.clear()
        try:
            return self._simulate(signal, options, start, t0, t1, step)
        except Exception as exc:  # the FMU's refusal or failure is a measured result
            return Run(error=self._error(exc))

    def _instance(self, **extra):
        from fmpy.simulation import instantiate_fmu

        return instantiate_fmu(self.unzip, self.md, "CoSimulation", logger=self._logger, **extra)

    def intermediate(self, signal, t0, t1, step):
        """fmpy's FMU3Slave with an intermediate-update callback that records RECORDED whenever
        the FMU allows getting them (fmusim's --record-intermediate-values)."""
        if not self.fmi3:
            return self.run(signal, {}, {}, t0, t1, step)
        self.log.clear()
        vrs = {v.name: v.valueReference for v in self.md.modelVariables}
        refs = [vrs[n] for n in RECORDED]
        extra, holder = [], {}

        def update(env, time, set_requested, get_allowed, step_finished, can_return_early, early, early_time):
            if get_allowed and "fmu" in holder:
                extra.append([time, *holder["fmu"].getFloat64(refs)])
            early[0] = False

        try:
            holder["fmu"] = fmu = self._instance(intermediate_update=update, required_intermediate_variables=refs)
        except Exception as exc:
            return Run(error=self._error(exc))
        try:
            run = self._simulate(signal, {}, {}, t0, t1, step, fmu_instance=fmu)
        except Exception as exc:
            return Run(error=self._error(exc))
        finally:
            fmu.freeInstance()
        rows = sorted([*run.rows.tolist(), *extra], key=lambda r: r[0])
        return Run(rows)

    def round_trip(self, signal, t0, tm, t1, step):
        """Straight to tm, the state serialized to bytes, then a new instance from those bytes to t1."""
        self.log.clear()
        v = "S" if self.fmi3 else "s"  # fmi3...FMUState, fmi2...FMUstate
        try:
            fmu = self._instance()
            first = self._simulate(signal, {}, {}, t0, tm, step, fmu_instance=fmu, terminate=False)
            state = getattr(fmu, f"getFMU{v}tate")()
            data = getattr(fmu, f"serializeFMU{v}tate")(state)
            getattr(fmu, f"freeFMU{v}tate")(state)
            fmu.terminate()
            fmu.freeInstance()
            fmu = self._instance()
            state = fmu.deserializeFMUState(data) if self.fmi3 else fmu.deSerializeFMUstate(data)
            getattr(fmu, f"setFMU{v}tate")(state)
            getattr(fmu, f"freeFMU{v}tate")(state)
            second = self._simulate(signal, {}, {}, tm, t1, step, fmu_instance=fmu, initialize=False)
            fmu.freeInstance()
        except Exception as exc:
            return Run(error=self._error(exc))
        return Run.joined(first, second)


# -- the matrix ---------------------------------------------------------------------------------
def resolved(md, start):
    """Start values with a switch's item names replaced by their numbers (from the description)."""
    from plateimpact.driver import switch_items

    variables = {v.name: v for v in md.modelVariables}
    out = {}
    for name, value in start.items():
        if name not in variables:
            raise SystemExit(f"fmusim_matrix: the FMU has no variable {name}")
        out[name] = switch_items(variables[name])[value] if isinstance(value, str) else value
    return out


def gap_of(md):
    start = {v.name: float(v.start) for v in md.modelVariables if v.name in ("obstacle_upper", "obstacle_lower")}
    return min(start["obstacle_upper"], -start["obstacle_lower"])


def ratio(a, b):
    return a / b if math.isfinite(a) and math.isfinite(b) and b != 0 else math.nan


def matrix(fmusim, fmu, label, signal, input_csv, work, args):
    """The rows of one FMU: both masters per option set, compared."""
    fmpy = Fmpy(fmu)
    gap = gap_of(fmpy.md)
    t1, step = args.stop_time, args.step
    tm = round(t1 / 2 / step) * step
    rows = []
    ignored = "" if fmpy.fmi3 else "FMI 2: both masters ignore the option"

    def add(options, starts, fmusim_run, fmpy_run, plain_sim, plain_py, note=""):
        events, off = fmusim_run.counts(step)
        rows.append(
            {
                "fmu": label,
                "options": options,
                "start values": starts,
                "fmusim energy [J]": fmusim_run.energy(),
                "fmusim / plain": ratio(fmusim_run.energy(), plain_sim.energy()),
                "fmusim / fmpy": ratio(fmusim_run.energy(), fmpy_run.energy()),
                "fmpy energy [J]": fmpy_run.energy(),
                "fmpy / plain": ratio(fmpy_run.energy(), plain_py.energy()),
                "fmusim max|corner_1| - gap [m]": fmusim_run.max_corner() - gap,
                "fmpy max|corner_1| - gap [m]": fmpy_run.max_corner() - gap,
                "gap [m]": gap,
                "fmusim events": events,
                "fmusim off-grid": off,
                "note": "; ".join(x for x in (note, fmusim_run.error, fmpy_run.error) if x),
            }
        )
        print(
            f"  {label} {options or 'plain'} {starts}: fmusim {fmusim_run.energy():.6g} J, fmpy {fmpy_run.energy():.6g} J",
            file=sys.stderr,
        )

    plain = {}
    for set_label, start in START_SETS.items():
        values = resolved(fmpy.md, start)
        for mode, (sim_options, py_options) in MODES.items():
            tag = f"{label}-{len(rows)}"
            sim = run_fmusim(fmusim, fmu, input_csv, work, tag, sim_options, values, 0.0, t1, step)
            py = fmpy.run(signal, py_options, values, 0.0, t1, step)
            if mode == "plain":
                plain[set_label] = (sim, py)
            add(" ".join(sim_options), set_label, sim, py, *plain[set_label], ignored if sim_options else "")

    straight_sim, straight_py = plain[""]
    sim = run_fmusim(fmusim, fmu, input_csv, work, f"{label}-iv", ["--record-intermediate-values"], {}, 0.0, t1, step)
    py = fmpy.intermediate(signal, 0.0, t1, step)
    note = ignored or (f"samples: fmusim {len(sim.rows)}, fmpy {len(py.rows)}" if sim.ok or py.ok else "")
    add("--record-intermediate-values", "", sim, py, straight_sim, straight_py, note)

    state = work / f"{label}-state.bin"
    state.unlink(missing_ok=True)
    first = run_fmusim(
        fmusim, fmu, input_csv, work, f"{label}-rt1", ["--final-fmu-state-file", str(state)], {}, 0.0, tm, step
    )
    second = run_fmusim(
        fmusim, fmu, input_csv, work, f"{label}-rt2", ["--initial-fmu-state-file", str(state)], {}, tm, t1, step
    )
    sim = Run.joined(first, second)
    py = fmpy.round_trip(signal, 0.0, tm, t1, step)
    note = f"state at {tm:g} s; max |corner_1 - straight| fmusim {deviation(sim, straight_sim):.2g} m, fmpy {deviation(py, straight_py):.2g} m"
    add(f"--final-fmu-state-file / --initial-fmu-state-file at {tm:g} s", "", sim, py, straight_sim, straight_py, note)
    return rows


def deviation(run, straight):
    """max |corner_1(run) - corner_1(straight)| at the sample times they share (after the restore)."""
    if not (run.ok and straight.ok):
        return math.nan
    a = dict(zip(np.round(run.rows[:, 0], 12), run.column("corner_1")))
    b = dict(zip(np.round(straight.rows[:, 0], 12), straight.column("corner_1")))
    return max((abs(a[t] - b[t]) for t in a.keys() & b.keys()), default=math.nan)


COLUMNS = (
    "fmu", "options", "start values", "fmusim energy [J]", "fmusim / plain", "fmusim / fmpy", "fmpy energy [J]",
    "fmpy / plain", "fmusim max|corner_1| - gap [m]", "fmpy max|corner_1| - gap [m]", "fmusim events", "fmusim off-grid", "note",
)  # fmt: skip


def markdown(rows):
    """The rows as a markdown table: energies and ratios to 4 digits, excess over the gap to 2."""

    def cell(col, value):
        if isinstance(value, float):
            return "-" if math.isnan(value) else f"{value:.2g}" if "corner" in col else f"{value:.4g}"
        return str(value).replace("|", "\\|") if value != "" else "-"

    lines = ["| " + " | ".join(c.replace("|", "\\|") for c in COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    lines += ["| " + " | ".join(cell(c, r[c]) for c in COLUMNS) + " |" for r in rows]
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fmu3", default=str(REPO / "build/fmi3/PlateImpact.fmu"), help="the FMI 3 FMU ('' to skip)")
    ap.add_argument("--fmu2", default=str(REPO / "build/PlateImpact.fmu"), help="the FMI 2 FMU ('' to skip)")
    ap.add_argument("--fmusim", default=str(REPO / ".deps/fmusim/bin/fmusim"))
    ap.add_argument("--step", type=float, default=1e-4, help="input table and communication interval, s")
    ap.add_argument("--stop-time", type=float, default=0.2)
    ap.add_argument("--json", help="also write the rows to this file")
    ap.add_argument("--workdir", help="keep the input CSV, fmusim's outputs and logs here (default: a temporary dir)")
    args = ap.parse_args(argv)

    fmusim = Path(args.fmusim)
    if not (fmusim.is_file() and fmusim.stat().st_mode & 0o111):
        raise SystemExit(
            f"fmusim_matrix: fmusim is not built ({fmusim} is missing).\n"
            "Build it with: REFERENCE_FMUS_SRC=/path/to/Reference-FMUs bash scripts/build-fmusim.sh"
        )
    fmus = [(label, Path(p)) for label, p in (("FMI 3", args.fmu3), ("FMI 2", args.fmu2)) if p]
    for label, path in fmus:
        if not path.is_file():
            raise SystemExit(f"fmusim_matrix: the {label} FMU is missing: {path} (build it: bash scripts/setup.sh)")

    from plateimpact import default_base

    n = round(args.stop_time / args.step)
    table = [(k * args.step, default_base(k * args.step)[0]) for k in range(n + 1)]
    signal = np.array(table, dtype=[("time", "f8"), ("base_displacement", "f8")])

    with tempfile.TemporaryDirectory(prefix="fmusim_matrix-") as tmp:
        work = Path(args.workdir or tmp)
        work.mkdir(parents=True, exist_ok=True)
        input_csv = work / "input.csv"
        with input_csv.open("w") as f:  # repr: shortest round trip, both masters read the same doubles
            f.write("time,base_displacement\n" + "".join(f"{t!r},{z!r}\n" for t, z in table))
        rows = []
        for label, path in fmus:
            rows += matrix(fmusim, path, label, signal, input_csv, work, args)

    version = subprocess.run([str(fmusim), "--version"], capture_output=True, text=True).stdout.strip()
    gaps = sorted({r["gap [m]"] for r in rows})
    print(
        f"{version} and fmpy, default scene to {args.stop_time:g} s, input table and communication step "
        f"{args.step:g} s; obstacle gap {', '.join(f'{g:g}' for g in gaps)} m:\n"
    )
    print(markdown(rows))
    if args.json:
        clean = [{k: None if isinstance(v, float) and math.isnan(v) else v for k, v in r.items()} for r in rows]
        Path(args.json).write_text(json.dumps(clean, indent=1) + "\n")


if __name__ == "__main__":
    main()
