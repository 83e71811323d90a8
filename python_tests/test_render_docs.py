"""The docs pages written from data (docs/templates/*.md filled by tools/render_docs.py from the
studies' JSON in docs/): each committed page is its template rendered from the saved JSON, so a
number on a page is one the study measured, and editing either without the other fails here. A
value the JSON lacks is an error, never an empty cell or a number the renderer makes up."""

import json
import re
import shutil
from pathlib import Path

import jinja2
import pytest
import render_docs

DOCS = Path(__file__).resolve().parent.parent / "docs"
PAGES = sorted(p.name for p in (DOCS / "templates").glob("*.md"))


def test_there_are_templates():
    assert "performance.md" in PAGES


@pytest.mark.parametrize("page", PAGES)
def test_page_is_its_template_and_data(page):
    assert (DOCS / page).read_text() == render_docs.render(page), (
        f"docs/{page} is not docs/templates/{page} filled from its JSON: run `python tools/render_docs.py {page}`"
    )


def test_a_missing_value_is_an_error_not_a_blank(tmp_path):
    data = json.loads((DOCS / "speed_vs_error.json").read_text())
    del data["baseline"]["ratio_free"]
    (tmp_path / "speed_vs_error.json").write_text(json.dumps(data))
    shutil.copy(DOCS / "impact_speed_error.json", tmp_path)
    with pytest.raises(jinja2.UndefinedError):
        render_docs.render("performance.md", tmp_path)


def test_a_new_law_brings_its_rows(tmp_path):
    """The after-impact tables are data-driven: a law added to the JSON appears in each of them."""
    laws = json.loads((DOCS / "impact_speed_error.json").read_text())
    row = dict(laws["errors"][0], law="new scheme")
    laws["errors"].append(row)
    laws["costs"].append(dict(laws["costs"][0], law="new scheme"))
    laws["verdicts"].append(dict(laws["verdicts"][0], law="new scheme"))
    (tmp_path / "impact_speed_error.json").write_text(json.dumps(laws))
    text = render_docs.render("performance.md", tmp_path)
    assert text.count("new scheme") == 3


# -- the README quotes the studies: each figure marked with its expression (tools/render_docs.py) ---
README = DOCS.parent / "README.md"
MARKED = render_docs.FIGURE


def test_readme_figures_are_their_json():
    """Issue 56: the README said the conserving law's worst step "is about 3× its median" while the
    studies' tables said 88× and 6.4×. Each speed or error figure of the README is now its expression
    over the JSON of one study's run; editing either alone fails here."""
    text = README.read_text()
    assert len(MARKED.findall(text)) >= 9, "the README's marked figures are gone (the check would be empty)"
    assert render_docs.fill_figures(text) == text, "README.md's figures are not their JSON: run tools/render_docs.py"


def test_a_changed_measurement_changes_the_readme(tmp_path):
    data = json.loads((DOCS / "step_latency.json").read_text())
    for r in data["rows"]:
        r["cpu_max_us"] = 123456.0
    (tmp_path / "step_latency.json").write_text(json.dumps(data))
    text = README.read_text()
    filled = render_docs.fill_figures(text, tmp_path)
    assert filled != text and "-->123456<!--/-->" in filled


def test_the_law_table_states_no_unmarked_figure():
    """In "Which impact law to pick" every cost and error a law achieves is a marked figure (µs, ×,
    m in e-notation): nothing copied by hand from a study's page."""
    text = README.read_text()
    table = text[text.index("## Which impact law to pick") :]
    table = table[: table.index("\n\n", table.index("|---"))]
    bare = MARKED.sub("", table)
    bare = "\n".join(line.split("|", 2)[-1] for line in bare.splitlines())  # "you need" asks, it measures nothing
    copied = re.findall(r"\d[\d.]*(?:e-?\d+)?\s*(?:µs|×(?!\s*\d))|\d(?:\.\d+)?e-\d+ m", bare)
    assert not copied, copied


def test_the_flow_laws_cost_is_stated_once():
    """Issue 56: docs/performance.md gave the flow law's CPU against the conserving law as 3.3× and 4.6×
    (the per-step table of impact_speed_error.json, measured before contact rows and the new error
    estimate), 2.09× (a bullet) and 1.67× / 2.07× (the tolerance study). The tolerance study's table,
    which times the flow law with and without a tolerance against the conserving law in one run, is
    now the one statement: the other study times no flow row, and the page and the README quote it."""
    laws = json.loads((DOCS / "impact_speed_error.json").read_text())
    assert not [r for r in laws["costs"] if r["law"].startswith("flow")], "a second statement of the flow law's cost"
    assert "cpu_ratio" not in laws["goals"]["release_dt_1e-5"]
