"""The README's table of variables is the FMU's: written from the model description (which the
build writes from the FMU's own table of variables) by `python -m plateimpact.interface`. A
parameter added to the table and not to the README — or a default changed — fails here."""

from pathlib import Path

from plateimpact.interface import block, current_block

README = Path(__file__).resolve().parent.parent / "README.md"


def test_readme_variables_table_is_the_fmus(fmu_path):
    expected = block(fmu_path)
    assert current_block(README.read_text()) == expected, (
        "README's variables table differs from the FMU's; rewrite it with "
        "`.venv/bin/python -m plateimpact.interface build/PlateImpact.fmu README.md`"
    )
    assert "`base_input_mode`" in expected and "`corner_1`" in expected  # the table is not empty
