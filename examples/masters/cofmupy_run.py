"""Run a CoFmuPy configuration (cofmupy_default_scene.json, cofmupy_release.json) with PlateImpact.fmu:
CoFmuPy 1.0.0 with the one fix it needs for this FMU (docs/masters.md, "CoFmuPy").

CoFmuPy's FMI 2.0 handler reads every output with fmi2GetReal and sets every start value with
fmi2SetReal, whatever the variable's type: the plate's first step fails on the Integer output
contact_vertices, and an Integer or Boolean parameter (nx, obstacle_upper_enabled) cannot be set.
`type_aware()` replaces the handler's getter, setter and step by ones that call get/set Real, Integer
or Boolean as the model description declares (the FMU itself is unchanged).

CoFmuPy pins fmpy 0.3.20 (with fmpy 0.3.32 its master fails on the model description's step size),
so it lives in a venv of its own, from the repository root after `bash run.sh`:

    python3 -m venv .deps/cofmupy && .deps/cofmupy/bin/pip install cofmupy==1.0.0
    .deps/cofmupy/bin/python examples/masters/cofmupy_run.py examples/masters/cofmupy_release.json 1e-3 0.3

The default scene reads its base from a CSV (columns t, base_displacement) the configuration names:
write it first (`--write-base` does, at CoFmuPy's own communication times, see below):

    .deps/cofmupy/bin/python examples/masters/cofmupy_run.py examples/masters/cofmupy_default_scene.json \
        1e-4 1.0 --write-base out/cofmupy/base_displacement.csv

(CONFIG STEP STOP repeated: several runs in one process.)
The storage named in the configuration gets every step's outputs (CoFmuPy empties its folder
first: give it a folder of its own); `--out DIR` also writes CoFmuPy's own table (DIR/<config>.csv), whose time
column is each step's start time (the outputs are those at the step's end).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from cofmupy import Coordinator
from cofmupy.wrappers import Fmu2Handler

# FMI 2.0 getter and setter per variable type (an Enumeration is read and set as an Integer).
KIND = {"Real": "Real", "Integer": "Integer", "Enumeration": "Integer", "Boolean": "Boolean"}


def _set_variable(self, name, value):
    var = self.var_name2attr[name]
    getattr(self.fmu, "set" + KIND[var.type])([var.valueReference], value)


def _get_variable(self, name):
    var = self.var_name2attr[name]
    return getattr(self.fmu, "get" + KIND[var.type])([var.valueReference])


def _step(self, current_time, step_size, input_dict):
    for name, value in input_dict.items():
        self._set_variable(name, value)
    self.fmu.doStep(currentCommunicationPoint=current_time, communicationStepSize=step_size)
    return {name: self.get_variable(name) for name in self.output_var_names}


def type_aware():
    """CoFmuPy's FMI 2.0 handler made type-aware (get/set by the variable's declared type)."""
    Fmu2Handler._set_variable = _set_variable
    Fmu2Handler.get_variable = _get_variable
    Fmu2Handler.step = _step


def cofmupy_times(step, count):
    """CoFmuPy's communication times: it adds the step to its clock (t += h), so after n steps
    its time is not n*h in the last bits; a CSV sampled at these times is read at its own points."""
    times = [0.0]
    for _ in range(count):
        times.append(times[-1] + step)
    return times


def write_base(path, step, count):
    """The default scene's base 0.09 sin(2 pi 10 t) at t = k*step, written at CoFmuPy's times."""
    path.parent.mkdir(parents=True, exist_ok=True)
    rows = [
        f"{t!r},{0.09 * math.sin(2 * math.pi * 10 * (k * step))!r}" for k, t in enumerate(cofmupy_times(step, count))
    ]
    path.write_text("t,base_displacement\n" + "\n".join(rows) + "\n")


def run(config, step, stop, out=None):
    """Start CoFmuPy on one configuration and take round(stop/step) steps of `step`."""
    count = round(stop / step)
    coordinator = Coordinator()
    coordinator.start(str(config))
    for _ in range(count):  # not run_simulation: its `while t < stop` may take one step more
        coordinator.do_step(step, save_data=True)
    if out:
        out.mkdir(parents=True, exist_ok=True)
        coordinator.save_results(str(out / f"{Path(config).stem}.csv"))
    print(f"cofmupy_run: {config}: {count} steps of {step} s, CoFmuPy's clock at {coordinator.master.current_time!r} s")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "runs",
        nargs="+",
        metavar="CONFIG STEP STOP",
        help="a CoFmuPy JSON configuration, its step and stop time (s); repeat for more runs in one process",
    )
    parser.add_argument(
        "--write-base", type=Path, help="first write the default scene's base CSV here (the first run's step and stop)"
    )
    parser.add_argument(
        "--out", type=Path, help="also write CoFmuPy's result table of each run here (DIR/<config>.csv)"
    )
    args = parser.parse_args()
    if len(args.runs) % 3:
        parser.error("give CONFIG STEP STOP, as many times as runs")
    runs = [(Path(c), float(h), float(t)) for c, h, t in zip(*[iter(args.runs)] * 3)]
    if args.write_base:
        write_base(args.write_base, runs[0][1], round(runs[0][2] / runs[0][1]))
    type_aware()
    for config, step, stop in runs:
        run(config, step, stop, args.out)


if __name__ == "__main__":
    main()
