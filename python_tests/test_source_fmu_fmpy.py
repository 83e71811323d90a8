"""The source FMU as fmpy's build_platform_binary (0.3.32) reads it: only the first SourceFileSet
(its files, definitions and language) and no IncludeDirectory, only sources/ (and fmpy's FMI
headers) on the include path. That set must hold every file the binary needs (the C and the C++
sources), and every include of a header the FMU carries must resolve the way the compiler
looks for it there: beside the including file, else under sources/ — headers included from
headers too (Eigen's own relative includes excepted). Checked without compiling (a second or so); the builds themselves, fmpy's and the
smoke experiment on the result, are scripts/check-source-fmu-builders.sh (minutes)."""

import re
import zipfile
from pathlib import Path, PurePosixPath

import pytest
from lxml import etree

ROOT = Path(__file__).resolve().parent.parent
SOURCE_FMU = ROOT / "build" / "dist" / "PlateImpact-source.fmu"
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
# fmpy's FMI headers: its c-code/ folder comes first on its include path. A header the FMU does not
# carry at all is the toolchain's (or inside an #if for another platform) and not checked.
FMPY_HEADERS = {"fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h", "fmi3Functions.h"}
FMPY_HEADERS |= {"fmi3FunctionTypes.h", "fmi3PlatformTypes.h"}

pytestmark = pytest.mark.skipif(not SOURCE_FMU.is_file(), reason="source FMU not built")


def first_set(z):
    root = etree.fromstring(z.read("sources/buildDescription.xml"))
    return root.find("BuildConfiguration").find("SourceFileSet")


def test_first_set_holds_every_source():
    with zipfile.ZipFile(SOURCE_FMU) as z:
        names = set(z.namelist())
        listed = {f.get("name") for f in first_set(z).iter("SourceFile")}
    plain = {
        n[len("sources/") :]
        for n in names
        if re.fullmatch(r"sources/suitesparse/.*/(cholmod_\w+|amd_\w+|colamd|SuiteSparse_config)\.c", n)
        or re.fullmatch(r"sources/plateimpact/(solver|fmu)/\w+\.cpp", n)
    }
    assert plain and plain <= listed, sorted(plain - listed)[:10]
    assert any(f.endswith(".c") for f in listed) and any(f.endswith(".cpp") for f in listed)


def test_every_include_resolves_from_sources():
    with zipfile.ZipFile(SOURCE_FMU) as z:
        names = set(z.namelist())
        todo = [f"sources/{f.get('name')}" for f in first_set(z).iter("SourceFile")]
        texts = {}
        unresolved, seen = [], set()
        while todo:
            path = todo.pop()
            if path in seen:
                continue
            seen.add(path)
            if path not in texts:
                texts[path] = z.read(path).decode("utf-8", "replace")
            for target in INCLUDE.findall(texts[path]):
                beside = str(PurePosixPath(path).parent / target)
                beside = _normalize(beside)
                found = next((c for c in (beside, _normalize(f"sources/{target}")) if c in names), None)
                if found:
                    if not found.startswith("sources/eigen3/"):  # Eigen's own includes are relative, some inside #if
                        todo.append(found)
                elif target not in FMPY_HEADERS and any(n.endswith(f"/{target}") for n in names):
                    unresolved.append(f"{path}: {target}")  # a header the FMU carries, not found
    assert len(seen) > 150, len(seen)  # the walk went through the headers
    assert not unresolved, f"{len(unresolved)} include(s) fmpy's build cannot find, e.g. " + "; ".join(unresolved[:5])


def _normalize(p):
    parts = []
    for part in p.split("/"):
        if part == "..":
            if parts:
                parts.pop()
        elif part != ".":
            parts.append(part)
    return "/".join(parts)
