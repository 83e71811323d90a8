"""The docs pages from the studies' JSON. Each docs/templates/<page>.md is a page a person wrote
(Jinja2): prose, with its tables and quoted numbers as expressions over the JSON files named on
its first line, `{# data: speed=speed_vs_error.json laws=impact_speed_error.json #}` (JSON or CSV, files in
--data, else the saved ones in docs/). It becomes docs/<page>.md; nothing here computes a number: a value the
JSON lacks is an error (StrictUndefined), not an empty cell.

    python tools/render_docs.py                      # every page of docs/templates/
    python tools/render_docs.py performance.md       # one page
    python tools/render_docs.py --check              # exit 1 if a page is not its template + data
    python tools/render_docs.py --figures            # also redraw the figures drawn from the JSON
    python tools/render_docs.py --data /tmp/perf --out /tmp/perf performance.md   # a study's --out

Hand-written pages (FIGURE_PAGES: the README, docs/verdicts.md) quote the studies too: each number that
describes speed or error is marked `<!--= EXPRESSION -->number<!--/-->`, the expression over the JSON files their
`<!-- figures: name=file ... -->` line names (paths from the repository root). Rendering rewrites the
number from the expression, --check fails where one differs, so a figure is stated in one place (the
JSON of one study's run) and quoted, never copied.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import re
import sys
from pathlib import Path

import jinja2

DOCS = Path(__file__).resolve().parent.parent / "docs"
DATA_LINE = re.compile(r"\{#\s*data:(.*?)#\}")
REPO = DOCS.parent
FIGURE_PAGES = ["README.md", "docs/verdicts.md"]  # hand-written pages with marked figures (from the repository root)
FIGURES_LINE = re.compile(r"<!-- figures:(.*?)-->")
FIGURE = re.compile(r"<!--=\s*(.*?)\s*-->(.*?)<!--/-->", re.S)


def g(x, digits=3):
    """`digits` significant digits, scientific outside [1e-3, 1e4); — for a missing value."""
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "—"
    if x == 0:
        return "0"
    if 1e-3 <= abs(x) < 1e4:
        return f"{x:.{digits}g}"
    return f"{x:.{max(digits - 1, 1)}e}".replace("e-0", "e-").replace("e+0", "e")


def f(x, spec):
    """Python's format spec: `x | f(".2f")`; — for a missing value."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    return format(x, spec)


def cell(text):
    """Text for a table cell: pipes escaped."""
    return str(text).replace("\\|", "|").replace("|", "\\|")


def row(rows, **match):
    """The first of `rows` (dicts) whose keys have the values given: `row(laws.costs, law="flow")`."""
    found = next((r for r in rows if all(r.get(k) == v for k, v in match.items())), None)
    if found is None:
        raise jinja2.UndefinedError(f"no row with {match}")
    return found


def environment(templates):
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates)),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
    )
    env.filters.update(g=g, f=f, cell=cell, e1=lambda x: "—" if x is None else f(x, ".1e").replace("e-0", "e-"))
    # the filters as functions too: a README table's figure cannot hold a "|" (it would split the cell)
    env.globals.update(isfinite=lambda x: x is not None and math.isfinite(x), row=row, g=g, f=f)
    env.tests.update(starting=lambda text, prefix: str(text).startswith(prefix))
    return env


def data_files(template_text):
    """The `name=file` pairs of a template's data line."""
    line = DATA_LINE.search(template_text)
    return dict(item.split("=", 1) for item in line.group(1).split()) if line else {}


def find(file, data_dir):
    """A data file in `data_dir`, else the saved one in docs/."""
    path = Path(data_dir) / file
    return path if path.exists() else DOCS / file


def load(path):
    """A JSON file, or a CSV file as a list of rows (numbers as floats, nan as None)."""
    if path.suffix != ".csv":
        return json.loads(path.read_text())
    number = lambda v: None if v == "nan" else float(v) if re.fullmatch(r"[-+0-9.e]+", v) else v  # noqa: E731
    return [{k: number(v) for k, v in row.items()} for row in csv.DictReader(path.open())]


def render(page, data_dir=DOCS, templates=DOCS / "templates"):
    """The text of docs/<page> from its template and JSON."""
    source = (templates / page).read_text()
    data = {name: load(find(file, data_dir)) for name, file in data_files(source).items()}
    text = environment(templates).get_template(page).render(**data)
    names = ", ".join(data_files(source).values())
    head = f"<!-- written by tools/render_docs.py from docs/templates/{page} and {names or 'no data'}; edit those -->\n"
    return head + text.lstrip("\n")


def fill_figures(text, data_dir=None):
    """A hand-written page with each marked figure recomputed from its expression; data_dir: where
    the JSON files are instead of the paths the figures line names (a study's --out)."""
    line = FIGURES_LINE.search(text)
    if not line:
        return text
    files = dict(item.split("=", 1) for item in line.group(1).split())
    data = {
        name: load(
            Path(data_dir) / Path(file).name
            if data_dir and (Path(data_dir) / Path(file).name).exists()
            else REPO / file
        )
        for name, file in files.items()
    }
    env = environment(DOCS / "templates")

    def figure(m):
        value = env.from_string("{{ " + m.group(1) + " }}").render(**data)
        return f"<!--= {m.group(1)} -->{value}<!--/-->"

    return FIGURE.sub(figure, text)


def draw_figures(page, data_dir, out):
    """The figures of `page` that are drawn from its JSON (the others come from examples)."""
    import figures

    for name, (draw, key) in figures.FIGURES.get(page, {}).items():
        files = data_files((DOCS / "templates" / page).read_text())
        (Path(out) / "figures").mkdir(parents=True, exist_ok=True)
        draw(json.loads(find(files[key], data_dir).read_text()), Path(out) / "figures" / name)
        print(f"render_docs: drew {Path(out) / 'figures' / name}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("pages", nargs="*", help="pages of docs/templates/ (default: all)")
    ap.add_argument("--data", type=Path, default=DOCS, help="where the JSON files are (default docs/)")
    ap.add_argument("--out", type=Path, default=DOCS, help="where the pages go (default docs/)")
    ap.add_argument("--check", action="store_true", help="compare instead of writing; exit 1 on a difference")
    ap.add_argument("--figures", action="store_true", help="also redraw the figures drawn from the JSON")
    args = ap.parse_args(argv)
    pages = args.pages or sorted(p.name for p in (DOCS / "templates").glob("*.md"))
    stale = []
    for page in pages:
        text = render(page, args.data)
        target = args.out / page
        if args.check:
            if not target.exists() or target.read_text() != text:
                stale.append(page)
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text)
        print(f"render_docs: wrote {target}")
        if args.figures:
            draw_figures(page, args.data, args.out)
    for page in FIGURE_PAGES if not args.pages and args.out == DOCS else []:
        text = (REPO / page).read_text()
        filled = fill_figures(text, None if args.data == DOCS else args.data)
        if args.check:
            if filled != text:
                stale.append(page)
        elif filled != text:
            (REPO / page).write_text(filled)
            print(f"render_docs: rewrote the figures of {page}")
    if stale:
        print(f"render_docs: not their template + data: {', '.join(stale)} (run tools/render_docs.py)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
