"""The documentation points only inside the repository, and everywhere it points exists: every
relative link and image of every Markdown page (README.md, docs/, the package's schema notes)
resolves to a tracked file or folder, and a `#fragment` to a heading of the page it names; no
tracked file names an absolute path of a developer's machine."""

import re
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
# the home folders and work areas of Linux, macOS and Windows machines, and this project's worktrees
MACHINE_PATH = re.compile(r"(?<![\w.])(/work/|/home/[a-z_][\w-]*/|/Users/\w|/root/|[A-Za-z]:\\Users\\)")


def tracked():
    out = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True)
    if out.returncode != 0:
        pytest.skip("not a git checkout")
    return [REPO / p for p in out.stdout.splitlines()]


def pages():
    # docs/templates/ are rendered into docs/ (tools/render_docs.py): their links are checked there
    return [p for p in tracked() if p.suffix == ".md" and "templates" not in p.relative_to(REPO).parts[:2]]


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"`|\*\*|\[([^\]]*)\]\([^)]*\)", r"\1", heading.strip().lower())
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(page):
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)
    return {slug(m.group(1)) for m in re.finditer(r"^#{1,6}\s+(.*?)\s*#*\s*$", text, flags=re.M)}


def links(page):
    text = re.sub(r"```.*?```", "", page.read_text(), flags=re.S)  # code blocks are code, not links
    text = re.sub(r"`[^`\n]*`", "", text)
    return [m.group(1) for m in LINK.finditer(text)]


def broken_links():
    files = set(tracked())
    dirs = {p for f in files for p in f.parents}
    bad = []
    for page in pages():
        for target in links(page):
            if re.match(r"[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                continue
            path, _, fragment = target.partition("#")
            resolved = (page.parent / path).resolve() if path else page
            where = f"{page.relative_to(REPO)}: ({target})"
            if not str(resolved).startswith(str(REPO) + "/") and resolved != REPO:
                bad.append(f"{where} points outside the repository")
            elif resolved not in files and resolved not in dirs:
                bad.append(f"{where} -> {resolved.relative_to(REPO)} does not exist")
            elif fragment and resolved.suffix == ".md" and fragment not in anchors(resolved):
                bad.append(f"{where}: no heading #{fragment} in {resolved.relative_to(REPO)}")
    return bad


def test_the_checker_sees_links():
    # the readme's links are found (a regex that matched nothing would pass everything)
    found = links(REPO / "README.md")
    assert "docs/variables.md" in found and "docs/figures/plate_impact.png" in found
    assert slug("Dependencies (and why each)") == "dependencies-and-why-each"


def test_every_repository_link_resolves():
    bad = broken_links()
    assert not bad, f"{len(bad)} broken link(s):\n" + "\n".join(bad)


def test_no_absolute_machine_path():
    hits = []
    for f in tracked():
        if f.relative_to(REPO).parts[0] == "third_party" or f == Path(__file__).resolve() or not f.is_file():
            continue
        try:
            text = f.read_text()
        except UnicodeDecodeError:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            if MACHINE_PATH.search(line):
                hits.append(f"{f.relative_to(REPO)}:{n}: {line.strip()[:120]}")
    assert not hits, "absolute paths of a machine:\n" + "\n".join(hits)
