"""The docs pages written from data (docs/templates/*.md filled by tools/render_docs.py from the
studies' JSON in docs/): each committed page is its template rendered from the saved JSON, so a
number on a page is one the study measured, and editing either without the other fails here. A
value the JSON lacks is an error, never an empty cell or a number the renderer makes up."""

import json
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
