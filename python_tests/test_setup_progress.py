"""`bash run.sh` says what it does while it builds (issue 56: it printed nothing for two minutes):
scripts/setup.sh names each of its four stages on one line, `setup: [k/4] ...`, and turns make's
`[ 42%]` lines into a progress count, one line each time the count passes a tenth. Run here on
make-like output (a real build is test.sh's and run.sh's to make, not the suite's)."""

import re
import subprocess
from pathlib import Path

SETUP = Path(__file__).resolve().parent.parent / "scripts" / "setup.sh"


def test_setup_names_four_stages_in_order():
    text = SETUP.read_text()
    stages = [int(k) for k in re.findall(r"^stage (\d) ", text, re.M)]
    assert stages == [1, 2, 3, 4], stages
    assert re.search(r'^stage\(\) \{ echo "setup: \[\$1/4\] \$2"; \}', text, re.M)


def test_build_progress_is_a_count():
    program = re.search(r"awk '(.*?)'\n", SETUP.read_text(), re.S).group(1)
    make = "".join(f"[{p:3d}%] Building CXX object x{p}.o\nwarning: something\n" for p in [*range(0, 100, 3), 100])
    r = subprocess.run(["awk", program], input=make, capture_output=True, text=True, check=True)
    counts = [int(m) for m in re.findall(r"^setup:\s+built\s+(\d+)%$", r.stdout, re.M)]
    assert counts == [12, 21, 30, 42, 51, 60, 72, 81, 90, 100], r.stdout


def test_first_run_times_each_stage_line_setup_and_run_print():
    """tools/first_run.py times `bash run.sh` from one stage line to the next: the lines it looks
    for are the ones setup.sh and run.sh print (renaming a stage cannot leave it timing nothing)."""
    import first_run

    setup = SETUP.read_text()
    names = re.findall(r'^stage (\d) "([^"]*)"', setup, re.M)
    printed = [f"setup: [{k}/4] {name}" for k, name in names]
    run = re.search(r'^echo "(run\.sh: simulating [^"]*)"', (SETUP.parent.parent / "run.sh").read_text(), re.M)
    printed.append(run.group(1))
    assert len(printed) == 5 and all(first_run.STAGE.match(line) for line in printed), printed
    lines = [(0.5, "noise"), *((10.0 * (i + 1), line) for i, line in enumerate(printed)), (55.0, "setup: built 40%")]
    rows = first_run.stages(lines, total=80.0)
    assert [r["stage"] for r in rows] == ["(before the first stage line)", *printed]
    assert [r["s"] for r in rows] == [10.0, 10.0, 10.0, 10.0, 10.0, 30.0]
