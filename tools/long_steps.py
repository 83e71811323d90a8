"""How long a communication step may be (docs/input-accuracy.md): a slow base motion, 0.05 sin(2π·0.4 t) m
(quasi-static for the 6.1 Hz plate), passed as fmpy.simulate_fmu's input table (values only, the
default quadratic reconstruction) at communication steps from 1e-3 s to 1 s over 10 s; the energy at
the end and max |corner_1| against the h = 1e-3 s run, and whether the FMU warned of the step (it does
above T1/10, T1 the plate's first period, when an input changed over the step).

    python tools/long_steps.py [--fmu build/PlateImpact.fmu] [--json docs/long_steps.json]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from ctypes import byref
from pathlib import Path

import fmpy
import numpy as np
from fmpy.fmi1 import printLogMessage
from fmpy.fmi2 import fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
from fmpy.logging import addLoggerProxy

# fmpy's native logger proxy (fmpy/logging) holds one global logger, the last one given to
# addLoggerProxy. simulate_fmu(logger=...) sets it to a ctypes callback that dies when simulate_fmu
# returns; every later FMI 2.0 FMU of the process that logs through fmpy's default callbacks then calls
# freed memory (a segfault: test_fmi3.py's fmi2GetReal warning after test_silent_answers.py's
# simulate, in one pytest worker). After each run the proxy points again at fmpy's printing logger,
# kept alive here (a fresh struct each time: addLoggerProxy replaces the struct's logger by the proxy).
_PRINTING = fmi2CallbackLoggerTYPE(printLogMessage)


def _restore_fmpy_logger():
    callbacks = fmi2CallbackFunctions()
    callbacks.logger = _PRINTING
    addLoggerProxy(byref(callbacks))  # the proxy keeps the function pointer, _PRINTING's


STEPS = [1e-3, 4e-3, 8e-3, 0.016, 0.032, 0.064, 0.1, 0.25, 1.0]
FREQUENCY, AMPLITUDE, STOP = 0.4, 0.05, 10.0


def simulate(fmu, stop: float, h: float, frequency: float, amplitude: float, **start_values):
    """fmpy.simulate_fmu with the base amplitude·sin(2π·frequency·t) as an input table sampled every
    1e-3 s (values only, as the README's snippet); the result and the FMU's warnings of a long step."""
    t = np.linspace(0.0, stop, round(stop / 1e-3) + 1)
    signal = np.array(
        list(zip(t, amplitude * np.sin(2 * np.pi * frequency * t))),
        dtype=[("time", float), ("base_displacement", float)],
    )
    warned = []

    def logger(component, instance, status, category, message):
        if status == 1 and b"communicationStepSize" in message:
            warned.append(message.decode())

    try:
        result = fmpy.simulate_fmu(
            str(fmu),
            stop_time=stop,
            output_interval=h,
            input=signal,
            output=["corner_1", "energy"],
            start_values=start_values,
            logger=logger,
        )
    finally:
        _restore_fmpy_logger()  # not the dead callback (above)
    return result, warned


def run(fmu: Path, h: float) -> dict:
    start = time.perf_counter()
    r, warned = simulate(fmu, STOP, h, FREQUENCY, AMPLITUDE)
    return {
        "h": h,
        "energy_end": float(r["energy"][-1]),
        "corner_max": float(np.abs(r["corner_1"]).max()),
        "warned": bool(warned),
        "warning": warned[0] if warned else "",
        "wall_s": time.perf_counter() - start,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--fmu", type=Path, default=Path("build/PlateImpact.fmu"))
    parser.add_argument("--json", type=Path, default=Path("docs/long_steps.json"))
    args = parser.parse_args()
    rows = []
    for h in STEPS:
        rows.append(run(args.fmu, h))
        r = rows[-1]
        print(
            f"h = {h:g} s: energy {r['energy_end']:.4g} J, max|corner_1| {r['corner_max']:.4g} m, warned {r['warned']}",
            file=sys.stderr,
            flush=True,
        )
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    report = {"frequency": FREQUENCY, "amplitude": AMPLITUDE, "stop": STOP, "commit": commit, "rows": rows}
    args.json.write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n")
    print(f"wrote {args.json}", file=sys.stderr)


if __name__ == "__main__":
    main()
