"""Measures how far other masters and platforms land from the references an FMU carries
(FMI-LS-REF), as a table of deviation / tolerance per experiment and output: the evidence the
tolerances of tools/write_references.py are checked against (issue 33).

    FMUSIM=path/to/fmusim python tools/reference_spreads.py build/PlateImpact.fmu [--master fmpy fmusim]

Prints, per experiment and master, the largest deviation/tolerance ratio and the output it
belongs to, and the largest deviation of every output, with its tolerance.
"""

from __future__ import annotations

import argparse

from plateimpact import validate


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("fmu")
    ap.add_argument("--master", nargs="*", default=["fmpy", "fmusim"])
    args = ap.parse_args(argv)
    sums, skipped, results = validate.validate(args.fmu, tuple(args.master), log=lambda s: None)
    for what, why in skipped:
        print(f"skipped {what}: {why}")
    worst = 0.0
    for r in results:
        if r.error:
            print(f"{r.experiment:12s} {r.master:7s} ERROR {r.error}")
            continue
        s = max(r.signals, key=lambda s: s.deviation / s.tolerance)
        worst = max(worst, s.deviation / s.tolerance)
        print(
            f"{r.experiment:12s} {r.master:7s} {'PASS' if r.passed else 'FAIL'}  max deviation/tolerance "
            f"{s.deviation / s.tolerance:.2e} ({s.name}: {s.deviation:.2e} of {s.tolerance:.2e})"
        )
        print("    " + ", ".join(f"{x.name} {x.deviation:.1e}" for x in r.signals))
    print(f"largest deviation/tolerance: {worst:.2e}; checksums ok: {all(ok for _, ok, _ in sums)}")


if __name__ == "__main__":
    main()
