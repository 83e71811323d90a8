"""The table of variables of docs/variables.md is the FMU's: written from the model description
(which the build writes from the FMU's own table of variables) by `python -m plateimpact.interface`.
A parameter added to the table and not to the page — or a default changed — fails here. The
README, the user's page, names the main variables and links the page: each variable it names in
code is one of the FMU's."""

import re
from pathlib import Path

from fmpy import read_model_description

from plateimpact.interface import block, current_block

REPO = Path(__file__).resolve().parent.parent
README = REPO / "README.md"
VARIABLES = REPO / "docs" / "variables.md"


def test_variables_table_is_the_fmus(fmu_path):
    expected = block(fmu_path)
    assert current_block(VARIABLES.read_text()) == expected, (
        "docs/variables.md's table differs from the FMU's; rewrite it with "
        "`.venv/bin/python -m plateimpact.interface build/PlateImpact.fmu docs/variables.md`"
    )
    assert "`base_input_mode`" in expected and "`corner_1`" in expected  # the table is not empty


def test_readme_links_the_table_and_names_only_the_fmus_variables(fmu_path):
    text = README.read_text()
    assert "docs/variables.md" in text
    names = {v.name for v in read_model_description(str(fmu_path)).modelVariables}
    section = text[text.index("## Main inputs and outputs") :]
    section = section[: section.index("\n## ", 3)]
    rows = [line for line in section.splitlines() if line.startswith("|")]
    named = {name for line in rows for name in re.findall(r"`([a-z][a-z0-9_]*)`", line)}
    assert named, "the README's main variables table is empty"
    assert named <= names, named - names


def test_the_real_time_row_says_whose_latency_it_is_with_the_c_step_beside():
    """The README's real-time recipe quoted step latencies measured through the Python driver as if they were
    the FMU's (issue 71): it says so, with the C step's own (fmi2DoStep from a C master, tools/step_latency.py's
    c_cpu columns) beside them, each a marker over docs/step_latency.json, the C step the smaller."""
    row = next(line for line in README.read_text().splitlines() if line.startswith("| a real-time master"))
    assert "through the Python driver" in row and "the C step alone" in row, row
    quoted = dict(re.findall(r'law="conserving m=20"\)\.(\w+), "\.0f"\) -->(\d+)<!--/-->', row))
    assert {"cpu_max_us", "c_cpu_max_us", "cpu_median_us", "c_cpu_median_us"} <= set(quoted), quoted
    assert int(quoted["c_cpu_max_us"]) < int(quoted["cpu_max_us"]), quoted
    assert int(quoted["c_cpu_median_us"]) < int(quoted["cpu_median_us"]), quoted
