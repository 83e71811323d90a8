"""The README's Python examples run as shown: every fenced ```python block of README.md,
executed from a scratch directory in which build/ is the build under test (so the blocks'
paths, build/PlateImpact.fmu and build/fmi3/PlateImpact.fmu, are the FMUs this suite checks),
with matplotlib headless. A block that raises fails here; the first block must leave the plot
of corner_1 it promises."""

import contextlib
import io
import os
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parent.parent / "README.md"
BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def blocks():
    return BLOCK.findall(README.read_text())


def test_the_readme_has_python_examples():
    assert len(blocks()) >= 2, "README.md lost its ```python examples"


@pytest.mark.parametrize("index", range(len(blocks())), ids=lambda i: f"block{i + 1}")
def test_readme_python_block_runs(index, fmu_path, tmp_path, monkeypatch):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    build = Path(fmu_path).resolve().parent
    (tmp_path / "build").symlink_to(build, target_is_directory=True)
    (tmp_path / "out").mkdir()  # as run.sh leaves it
    monkeypatch.chdir(tmp_path)
    code = blocks()[index]
    with contextlib.redirect_stdout(io.StringIO()):
        exec(compile(code, f"README.md python block {index + 1}", "exec"), {"__name__": "__readme__"})
    import matplotlib.pyplot as plt

    plt.close("all")
    if "savefig" in code:
        saved = re.search(r'savefig\("([^"]+)"', code).group(1)
        assert os.path.getsize(tmp_path / saved) > 0
