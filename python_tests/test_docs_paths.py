"""Every repository path a doc names exists. The links are test_docs_links.py's; this file reads the
prose and the code spans: a path that starts with one of the repository's top folders
(`solver/fe/Mesh.cpp`, `fmu/binding/PlateVariables.{h,cpp}`, `solver/schemes/FlowScheme*`) must name
a tracked file or folder (braces expanded, `*` a glob), and a bare source file name (`PlateModel.cpp`)
must be the name of a tracked file. Generated paths (build/, out/, .venv/) start with no top folder
of the repository and are not checked; docs/templates/ are checked through the pages they render."""

import fnmatch
import re
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
# Bare names a doc may give that are no file of this repository: a system header.
NOT_OURS = {"xxhash.h"}
SOURCE_NAME = re.compile(r"(?<![\w./-])([A-Za-z_][\w-]*\.(?:cpp|h|py|sh|cmake))(?![\w/])")


def tracked():
    out = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True)
    if out.returncode != 0:
        pytest.skip("not a git checkout")
    return out.stdout.splitlines()


def pages(files):
    return [f for f in files if f.endswith(".md") and not f.startswith("third_party/") and "/templates/" not in f]


def path_pattern(files):
    """A repository path: one of the tracked top folders, a slash, then path characters."""
    tops = sorted({f.split("/")[0] for f in files if "/" in f and not f.startswith(".")})
    return re.compile(r"(?<![\w./-])((?:%s)/[\w.*{},/-]*[\w*}/])" % "|".join(map(re.escape, tops)))


def expand(path):
    """`a/{b,c}.h` -> a/b.h, a/c.h (nested braces too)."""
    m = re.search(r"\{([^{}]*)\}", path)
    if not m:
        return [path]
    return [x for alt in m.group(1).split(",") for x in expand(path[: m.start()] + alt + path[m.end() :])]


def exists(path, files, dirs):
    path = path.rstrip("/")
    if path in files or path in dirs:
        return True
    return "*" in path and any(fnmatch.fnmatch(f, path) or fnmatch.fnmatch(f, path + "/*") for f in files)


def missing_paths(texts, files):
    """(where, path) for every named path that does not exist; texts: {page: text}."""
    dirs = {str(p) for f in files for p in Path(f).parents}
    names = {Path(f).name for f in files}
    pattern = path_pattern(files)
    bad = []
    for page, text in texts.items():
        for n, line in enumerate(text.splitlines(), 1):
            for m in pattern.finditer(line):
                for path in expand(m.group(1)):
                    path = path.rstrip(".,:;")
                    if not exists(path, files, dirs):
                        bad.append(f"{page}:{n}: {path}")
            for m in SOURCE_NAME.finditer(line):
                if m.group(1) not in names and m.group(1) not in NOT_OURS:
                    bad.append(f"{page}:{n}: {m.group(1)} (no tracked file has this name)")
    return bad


def test_the_checker_sees_a_moved_file():
    # the paths theory.md named before the solver was split into folders: all three are found
    files = tracked()
    text = "the mesh (`solver/Mesh.cpp`), the law in solver/ImpactLaw.cpp; ModalPlate.cpp is fine"
    bad = missing_paths({"x.md": text}, files)
    assert bad == ["x.md:1: solver/Mesh.cpp", "x.md:1: solver/ImpactLaw.cpp"], bad
    assert missing_paths({"x.md": "fmu/binding/PlateVariables.{h,cpp}, solver/schemes/Flow*"}, files) == []
    assert missing_paths({"x.md": "fmu/binding/PlateVariables.{h,hpp}"}, files) == [
        "x.md:1: fmu/binding/PlateVariables.hpp"
    ]
    assert missing_paths({"x.md": "see Mesh2.cpp"}, files) == ["x.md:1: Mesh2.cpp (no tracked file has this name)"]


def test_every_path_a_doc_names_exists():
    files = tracked()
    texts = {page: (REPO / page).read_text() for page in pages(files)}
    bad = missing_paths(texts, files)
    assert not bad, f"{len(bad)} path(s) named in the docs that do not exist:\n" + "\n".join(bad)
