"""The check every runner makes before a master sees an FMU: the file exists, is readable and
is an FMU (a zip archive with a modelDescription.xml). A master handed a missing or broken file
fails far from the cause (libcosim crashed in add_local_slave), so the message comes first, here."""

from __future__ import annotations

import os
import zipfile
from pathlib import Path


class FMUFileError(FileNotFoundError):
    """The FMU named is missing, unreadable or not an FMU; the message says which and what to do."""


def fmu_file(path) -> Path:
    """The resolved path of an FMU file (or of a folder holding one extracted), checked."""
    p = Path(path).resolve()
    hint = "build it with `bash run.sh` (or scripts/setup.sh), or set PLATEIMPACT_FMU"
    if p.suffix == ".fmu" and p.stem != "PlateImpact":  # a demonstration FMU: run.sh does not build it
        target = p.stem + ("Fmu3" if p.parent.name == "fmi3" else "Fmu")
        hint = f"build it with `bash scripts/setup.sh {target}` (`bash run.sh` builds PlateImpact.fmu only)"
    if not p.exists():
        raise FMUFileError(f"FMU not found: {p} ({hint})")
    if p.is_dir():
        if not (p / "modelDescription.xml").is_file():
            raise FMUFileError(f"{p} is a folder without modelDescription.xml: not an extracted FMU ({hint})")
        return p
    if not os.access(p, os.R_OK):
        raise FMUFileError(f"FMU not readable: {p} (permissions)")
    try:
        with zipfile.ZipFile(p) as archive:
            if "modelDescription.xml" not in archive.namelist():
                raise FMUFileError(f"{p} is a zip archive without modelDescription.xml: not an FMU ({hint})")
    except zipfile.BadZipFile as e:
        raise FMUFileError(f"{p} is not an FMU (not a zip archive: {e}; {hint})") from None
    return p


def require_fmu(path, prog: str) -> Path:
    """fmu_file for a command-line program: on a missing or broken FMU, one line on stderr
    (`prog: FMU not found: ... (build it with ...)`) and exit status 2 instead of a traceback."""
    import sys

    try:
        return fmu_file(path)
    except FMUFileError as e:
        print(f"{prog}: {e}", file=sys.stderr)
        raise SystemExit(2) from None


def output_dir(out, quick: bool) -> Path:
    """Where an example writes: `--out`, or for a smoke run (`--quick`) its `quick/` subfolder, so that
    a smoke run never overwrites a full run's files (one rule for every example: README, "Examples")."""
    folder = Path(out) / "quick" if quick else Path(out)
    folder.mkdir(parents=True, exist_ok=True)
    return folder
