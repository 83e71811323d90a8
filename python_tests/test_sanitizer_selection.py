"""What the sanitizer stage leaves out names what covers it (issue 54): every test of a `sanitizer`
file marked `repeats_paths` names, as the marker's arguments, tests that the stage runs (the
tests marked `sanitizer` but not `repeats_paths`, as scripts/sanitizer-stage.sh selects them) or
a libFuzzer harness of fuzz/ (the fuzz stage runs it in the same ASan + UBSan build). A name that
is no such test — a typo, a renamed or moved test, a parameter that went — fails here."""

import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
SELECTION = "sanitizer and not repeats_paths"


def collect(*args):
    """The node ids pytest collects from python_tests/ with these arguments, and its output."""
    out = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider", *args],
        cwd=HERE,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "PLATEIMPACT_LIST_REPEATS_PATHS": "1"},
    )
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    return out.stdout.splitlines()


def test_every_test_left_out_of_the_sanitizer_stage_names_what_covers_it():
    # One collection (issue 54: two took 10 s): the node ids pytest lists are the stage's, as
    # scripts/sanitizer-stage.sh selects them; conftest.py's pytest_collection_modifyitems runs
    # before pytest's -m deselects (tryfirst) and prints "repeats_paths <node id> -> <covering> ..."
    # for every test of a sanitizer file left out.
    lines = collect("-m", SELECTION, ".")
    stage = {line for line in lines if "::" in line and not line.startswith("repeats_paths ")}
    notes = [line.split(" ", 1)[1] for line in lines if line.startswith("repeats_paths ")]
    assert stage, lines[-20:]
    assert len(notes) >= 40, notes  # the stability cases, the conformance configurations, the studies
    left_out = {note.split(" -> ")[0] for note in notes}
    assert not left_out & stage, left_out & stage  # what is left out is not in the stage
    problems = []
    for note in notes:
        test, covering = note.split(" -> ")
        names = covering.split()
        if not names:
            problems.append(f"{test}: names nothing")
        for name in names:
            harness = name.startswith("fuzz/") and name.endswith(".cpp") and (REPO / name).is_file()
            if not harness and name not in stage:
                problems.append(f"{test}: {name} is no test of the sanitizer stage")
            if name == test:
                problems.append(f"{test}: names itself")
    assert not problems, "\n".join(problems)
