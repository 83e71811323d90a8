"""The package `plateimpact` declares every third-party module it imports (python/pyproject.toml):
a user who installs it with pip gets what it needs, nothing found by accident in the venv."""

import ast
import sys
from pathlib import Path

import tomllib

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "python" / "plateimpact"
# import name -> distribution name, where they differ
DISTRIBUTION = {"distributed": "dask"}


def imported_modules():
    out = {}
    for path in sorted(PACKAGE.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names = [node.module]
            else:
                continue
            for name in names:
                out.setdefault(name.split(".")[0], path.name)
    return out


def declared():
    project = tomllib.loads((ROOT / "python" / "pyproject.toml").read_text())["project"]
    specs = list(project["dependencies"])
    for extra in project.get("optional-dependencies", {}).values():
        specs += extra
    names = set()
    for spec in specs:
        name = spec.split(";")[0]
        for sep in "[<>=!~ ":
            name = name.split(sep)[0]
        names.add(name.strip().lower())
    return names


def test_every_third_party_import_is_declared():
    have = declared()
    missing = {
        f"{DISTRIBUTION.get(module, module)} (imported by {where})"
        for module, where in imported_modules().items()
        if module not in sys.stdlib_module_names
        and module != "plateimpact"
        and DISTRIBUTION.get(module, module).lower() not in have
    }
    assert not missing, f"imported but not declared in python/pyproject.toml: {sorted(missing)}"
