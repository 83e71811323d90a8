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


@pytest.mark.parametrize("page", render_docs.FIGURE_PAGES)
def test_marked_pages_are_their_json(page):
    """Every hand-written page with marked figures (the README, docs/verdicts.md) is its JSON."""
    text = (DOCS.parent / page).read_text()
    assert len(MARKED.findall(text)) >= 9, f"{page}'s marked figures are gone (the check would be empty)"
    assert render_docs.fill_figures(text) == text, f"{page}'s figures are not their JSON: run tools/render_docs.py"


def section(text, heading, end):
    """The text from `heading` to `end` (exclusive), with the marked figures taken out."""
    part = text[text.index(heading) :]
    return MARKED.sub("", part[: part.index(end)])


def test_the_performance_table_is_one_run_of_instance_setup(tmp_path):
    """Issue 56: the README's "Performance" table gave the setup times (0.60 s, 0.014 s) and the
    Dask map's (8.5 s against 52.5 s, 10.0 s against 33.8 s) by hand, from runs nobody could
    repeat. Each is now a figure over docs/instance_setup.json (tools/instance_setup.py, one run):
    no unmarked time or share is left in the table, and a new measurement changes it."""
    text = README.read_text()
    table = section(text, "## Performance", "**The discretization cache.**")
    assert not re.findall(r"\d[\d.]*\s*(?:s\b|%)", table), "a time or share in the Performance table is not marked"
    data = json.loads((DOCS / "instance_setup.json").read_text())
    data["first_cpu_s"] = 98.765
    data["map"]["cache_off"]["wall_s"] = 4321.0
    (tmp_path / "instance_setup.json").write_text(json.dumps(data))
    filled = render_docs.fill_figures(text, tmp_path)
    assert "-->98.77<!--/--> s CPU" in filled and "-->4321.0<!--/--> s" in filled


def test_verdicts_quote_the_port_cost_and_the_speed_report(tmp_path):
    """Issue 56: docs/verdicts.md said the port's outputs cost 0.98x and 1.10x of a pre-port step
    while docs/port_cost.json, the run performance.md renders, measured 1.05x against a run that
    does not read them; its headline step (9.2 us, 0.34 of the floor), its `modes`, baseline and
    convergence figures and its table of the elements' speed were older than speed_vs_error.json's.
    They are figures over the JSON now (the elements' table is performance.md's)."""
    text = (DOCS / "verdicts.md").read_text()
    port = section(text, "- Cost (`tools/port_cost.py`", "\n- ")
    assert not re.findall(r"\d[\d.]*×(?!\s*\d)", port), "an unmarked ratio in the port's cost"
    measured = r"(?<![≥≤] )(?<![≥≤])\b\d[\d.]*(?:e-?\d+)?\s*(?:µs|×(?!\s*\d)|J\b|s wall)"  # not a goal's bound
    speed = section(text, "## Performance", "## Inputs")
    assert not re.findall(measured, speed), "an unmarked speed or error figure in the Performance section"
    elements = section(text, "Speed at matched accuracy", "On the *same*")
    assert not re.findall(measured, elements) and "|" not in elements, "a hand-typed speed table of the elements"
    data = json.loads((DOCS / "port_cost.json").read_text())
    data["read_over_not_read"] = 7.5
    (tmp_path / "port_cost.json").write_text(json.dumps(data))
    assert "-->7.50<!--/-->×" in render_docs.fill_figures(text, tmp_path)


def test_the_resources_table_is_one_run_of_resource_scaling(tmp_path):
    """Issue 56: performance.md's "Resources" table and its findings (0.87–1.04, 2–4×, the largest
    meshes under 10 s) were pasted from an older run of scripts/resource_scaling.py and no file
    kept. The template now holds no measured row or ratio: they come from docs/resource_scaling.json
    (one run), and a new measurement changes the page."""
    template = (DOCS / "templates" / "performance.md").read_text()
    resources = template[template.index("## Resources") : template.index("\n## ", template.index("## Resources"))]
    bare = re.sub(r"\{\{.*?\}\}|\{%.*?%\}", "", resources, flags=re.S)
    assert not re.search(r"^\| (argyris|fvs) \|", bare, re.M), "a hand-typed row in the Resources table"
    assert not re.findall(r"\d\.\d+\s*[–-]\s*\d\.\d+|\d[\d.]*\s*(?:ms|GB)\b", bare), "a hand-typed finding"
    data = json.loads((DOCS / "resource_scaling.json").read_text())
    measured = next(r for r in data["rows"] if "rss_mb" in r)
    measured["rss_mb"] = 4321.0
    data["comparisons"]["memory_ratio"]["sparse"]["max"] = 7.77
    (tmp_path / "resource_scaling.json").write_text(json.dumps(data))
    text = render_docs.render("performance.md", tmp_path)
    assert "| 4321 |" in text and "–7.77 (" in text


def test_the_fine_mesh_table_is_one_run_of_fine_mesh_setup(tmp_path):
    """Issue 70: "Fine meshes on a few modes" held hand-typed measurements; its table and
    ratios now come from docs/fine_mesh_setup.json (tools/fine_mesh_setup.py), and a new
    measurement changes the page."""
    template = (DOCS / "templates" / "performance.md").read_text()
    start = template.index("## Fine meshes on a few modes")
    section = template[start : template.index("\n## ", start)]
    bare = re.sub(r"\{\{.*?\}\}|\{%.*?%\}", "", section, flags=re.S)
    assert not re.search(r"^\| \d+ × \d+ \|", bare, re.M), "a hand-typed row in the fine-mesh table"
    assert not re.findall(r"\d+(?:\.\d+)? ?(?:s|MB) ?/ ?\d", bare), "a hand-typed measurement"
    data = json.loads((DOCS / "fine_mesh_setup.json").read_text())
    data["rows"][0]["setup_cpu_s"] = 98.76
    data["cpu_over_estimate"]["max"] = 7.77
    (tmp_path / "fine_mesh_setup.json").write_text(json.dumps(data))
    text = render_docs.render("performance.md", tmp_path)
    assert "| 98.76 |" in text and "–7.77," in text


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
