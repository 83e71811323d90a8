"""The FMU's interface as a user reads it: the table of variables of docs/variables.md, written
from the model description (which the build writes from the FMU's own table of variables), so
that the page cannot drift from the binary. python_tests/test_readme.py checks the page against it.

    python -m plateimpact.interface build/PlateImpact.fmu docs/variables.md   # rewrite the table in place
"""

from __future__ import annotations

import sys
from pathlib import Path

from fmpy import read_model_description

from .driver import switch_items

BEGIN = "<!-- variables: written by `python -m plateimpact.interface`; do not edit by hand -->"
END = "<!-- variables: end -->"


def start_text(v):
    """A variable's start value as docs/variables.md shows it (a switch's item by name and number)."""
    if v.causality == "output" or v.start is None:
        return ""
    names = {value: name for name, value in switch_items(v).items()}
    if names:
        return f"{v.start} (`{names.get(int(v.start), '?')}`)"
    if v.type == "Boolean":
        return str(v.start).lower()
    return str(v.start)


def range_text(v):
    """The allowed range the model description declares (min/max), as docs/variables.md shows it."""
    low, high = getattr(v, "min", None), getattr(v, "max", None)
    if low is None and high is None:
        return ""
    return f"{low if low is not None else ''} … {high if high is not None else ''}"


def variables_table(fmu) -> str:
    """The Markdown table of every variable: name, causality, type, start, range, unit, description."""
    md = read_model_description(str(fmu))
    rows = [
        "| name | causality | type | default | range | unit | meaning |",
        "|---|---|---|---|---|---|---|",
    ]
    for v in md.modelVariables:
        kind = v.type
        description = (v.description or "").replace("|", "\\|")
        rows.append(
            f"| `{v.name}` | {v.causality} | {kind} | {start_text(v)} | {range_text(v)} | {v.unit or ''} | {description} |"
        )
    return "\n".join(rows)


def block(fmu) -> str:
    return f"{BEGIN}\n{variables_table(fmu)}\n{END}"


def current_block(text: str) -> str:
    """The table block of a page's text (between the markers)."""
    begin, end = text.index(BEGIN), text.index(END)
    return text[begin : end + len(END)]


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    fmu, page = argv
    path = Path(page)
    text = path.read_text()
    path.write_text(text.replace(current_block(text), block(fmu)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
