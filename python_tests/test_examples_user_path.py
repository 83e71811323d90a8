"""The examples on a new user's path (issue 40): a missing FMU is one line on stderr and a
non-zero exit, not a traceback or a cluster's worker errors; no example writes into a tracked
folder by default; `--quick`'s help names every setting it changes; the README's snippets write
only where git ignores. demos/system_model.py is not covered."""

import ast
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
SCRIPTS = [
    "examples/animate.py",
    "examples/default_scene.py",
    "examples/frequency_response.py",
    "examples/input_accuracy.py",
    "examples/paper_scenes.py",
    "demos/shaker.py",
    "examples/sine_sweep.py",
]


def git(*args):
    return subprocess.run(["git", *args], cwd=REPO, capture_output=True, text=True)


def main_function(script):
    tree = ast.parse((REPO / script).read_text())
    return next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "main")


def options(script):
    """{option: (default, help)} of the example's argparse calls."""
    out = {}
    for node in ast.walk(main_function(script)):
        if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "add_argument" and node.args:
            first = node.args[0]
            if isinstance(first, ast.Constant) and str(first.value).startswith("--"):
                kw = {k.arg: k.value for k in node.keywords}
                default = kw.get("default")
                help_ = kw.get("help")
                out[first.value] = (
                    default.value if isinstance(default, ast.Constant) else None,
                    help_.value if isinstance(help_, ast.Constant) else "",
                )
    return out


def quick_changes(script):
    """The option names `if args.quick:` assigns (args.x = ... or a, b = ...)."""
    changed = set()
    for node in ast.walk(main_function(script)):
        if isinstance(node, ast.If) and ast.unparse(node.test) in ("args.quick", "q"):
            for stmt in ast.walk(ast.Module(body=node.body, type_ignores=[])):
                if isinstance(stmt, ast.Assign):
                    for target in stmt.targets:
                        for t in ast.walk(target):
                            if isinstance(t, ast.Attribute) and ast.unparse(t.value) == "args":
                                changed.add(t.attr)
    return changed


@pytest.mark.parametrize("script", SCRIPTS)
def test_missing_fmu_is_one_line_and_a_failure(script, tmp_path):
    missing = tmp_path / "no" / "PlateImpact.fmu"
    cmd = [sys.executable, str(REPO / script), "--quick", "--fmu", str(missing), "--out", str(tmp_path / "o")]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert r.returncode != 0, f"{script} exited 0 without its FMU"
    err = r.stderr.strip().splitlines()
    assert len(err) == 1 and "Traceback" not in r.stderr, f"{script}: {r.stderr[-1500:]}"
    assert "not found" in err[0] and Path(script).stem in err[0], err[0]
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())


@pytest.mark.parametrize("script", SCRIPTS)
def test_default_output_folder_is_not_tracked(script):
    default, _ = options(script)["--out"]
    assert default, f"{script}: --out has no default"
    tracked = git("ls-files", "--", default).stdout.strip()
    assert not tracked, f"{script} writes into {default}/ by default, which holds tracked files"
    assert git("check-ignore", "-q", f"{default}/x.png").returncode == 0, f"{script}: {default}/ is not ignored"


@pytest.mark.parametrize("script", SCRIPTS)
def test_quick_help_names_what_it_changes(script):
    opts = options(script)
    _, help_ = opts["--quick"]
    for name in sorted(quick_changes(script)):
        option = "--" + name.replace("_", "-")
        words = {name, name.replace("_", " "), option, name.replace("_", "-")}
        assert option not in opts or any(w in help_ for w in words), (
            f"{script}: --quick changes {option} but its help does not say so: {help_!r}"
        )


def test_quick_changes_are_seen():
    # the AST reader finds what --quick sets (a reader that found nothing would pass everything)
    assert {"amplitude", "f_start", "nx"} <= quick_changes("examples/sine_sweep.py")


def test_readme_snippets_write_only_ignored_files():
    text = (REPO / "README.md").read_text()
    blocks = re.findall(r"^```python\n(.*?)^```", text, re.S | re.M)
    written = [p for b in blocks for p in re.findall(r'(?:savefig|to_csv|open)\(\s*"([^"]+)"', b)]
    assert written, "the README's snippets write nothing (the check would be empty)"
    for path in written:
        assert git("check-ignore", "-q", path).returncode == 0, (
            f"README snippet writes {path}, which git does not ignore"
        )


def test_shaker_quick_compares_envelopes_and_plots_data(fmu_path, tmp_path):
    """--quick's 1 s run has its first impact near 0.3 s, inside the sweep's 0.5 s ramp-in: its
    envelope windows are the quick ones, so the line's deviation from the monolithic reference is
    a number (it printed `envelope nan%`) and every curve of the figure has points (it drew
    single points, invisible)."""
    import importlib.util

    pytest.importorskip("libcosimpy.CosimExecution")
    spec = importlib.util.spec_from_file_location("shaker_quick", REPO / "demos" / "shaker.py")
    shaker = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(shaker)
    shaker.ENVELOPE.update(shaker.QUICK_ENVELOPE)  # what main does for --quick
    q = shaker.QUICK
    paths = shaker.fmus(fmu_path)
    reference = shaker.simulate(paths, "monolithic", q["mass"], 1e-4, q["duration"], q["gap"])
    line = shaker.simulate(paths, "tlm", q["mass"], 1e-4, q["duration"], q["gap"])
    assert reference["finished"] and line["finished"] and 0.1 < line["first_impact"] < 0.5, line
    shaker.compare(line, reference)
    assert np.isfinite(line["envelope_deviation"]), line
    assert "nan" not in shaker.summary(line)
    drawn = shaker.figure([reference, line], tmp_path / "shaker.png")
    assert drawn and all(n >= 5 for _, n in drawn), drawn


def test_paper_scene_titles_count_the_mesh_they_ran():
    """A title's element count comes from the mesh of the run (--quick runs 7×2 and 10×3 cells,
    it said "140 elements"): no figure text of paper_scenes.py writes a count as a literal."""
    import importlib.util

    source = (EXAMPLES / "paper_scenes.py").read_text()
    literal = [
        ast.unparse(n)
        for n in ast.walk(ast.parse(source))
        if isinstance(n, (ast.Constant, ast.JoinedStr))
        and re.search(r"\d\s*elements", ast.unparse(n))
        and not (isinstance(n, ast.Constant) and "\n" in str(n.value))  # the docstring
    ]
    assert not literal, literal
    spec = importlib.util.spec_from_file_location("paper_scenes_titles", EXAMPLES / "paper_scenes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.mesh_text({"argyris": (7, 2), "fvs": (10, 3)}) == "Argyris 28 (7×2), FVS 30 (10×3) elements"
    assert module.mesh_text(module.MESHES) == "Argyris 140 (14×5), FVS 140 (20×7) elements"


@pytest.mark.parametrize("script", [*SCRIPTS, "examples/stress_sweep.py", "demos/system_model.py"])
def test_quick_writes_into_its_own_folder(script):
    """Issue 56: `--quick` runs of five examples overwrote the full runs' files. One rule for every
    example (README, "Examples"): a smoke run writes into <out>/quick/ — each main takes its folder
    from plateimpact.fmufile.output_dir(args.out, args.quick)."""
    calls = [
        ast.unparse(n)
        for n in ast.walk(main_function(script))
        if isinstance(n, ast.Call) and ast.unparse(n.func) == "output_dir"
    ]
    assert calls == ["output_dir(args.out, args.quick)"], f"{script}: {calls or 'no output_dir call'}"
