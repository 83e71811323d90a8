"""The checkout a tool reads and writes, given on its command line: --repo (default: the current
directory) holds build/ and docs/; --fmu defaults to $PLATEIMPACT_FMU, else <repo>/build/PlateImpact.fmu."""

from __future__ import annotations

import os
from pathlib import Path


def add_checkout_arguments(parser):
    parser.add_argument("--repo", type=Path, default=Path("."), help="the PlateImpact checkout (default: .)")
    parser.add_argument("--fmu", help="the FMU (default: $PLATEIMPACT_FMU, else <repo>/build/PlateImpact.fmu)")


def fmu_path(args):
    return args.fmu or os.environ.get("PLATEIMPACT_FMU") or str(args.repo / "build" / "PlateImpact.fmu")
