"""What the docs and the FMU's own reference experiments say agrees with what they carry: each
experiment's description names the mesh its parameters set and, for the smoke test, the first
impact its reference shows; the README explains §5.2 where it first uses it; the state
experiment claims bit-for-bit replays only for this project's own replay (another master lands
within the tolerance, not on the same bits)."""

import re
import zipfile
from pathlib import Path

import numpy as np

from plateimpact.references import EXPERIMENTS, LS_DIR

REPO = Path(__file__).resolve().parent.parent


def test_descriptions_name_the_mesh_they_run():
    for exp in EXPERIMENTS:
        meshes = re.findall(r"(\d+)x(\d+) (?:Argyris|FVS) cells", exp.description)
        nx, ny = exp.parameters.get("nx", 14), exp.parameters.get("ny", 5)
        assert all((int(a), int(b)) == (nx, ny) for a, b in meshes), (exp.name, meshes, nx, ny)


def test_smoke_first_impact_is_the_references(fmu_path):
    smoke = next(e for e in EXPERIMENTS if e.name == "smoke")
    stated = float(re.search(r"first impact near ([0-9.]+) s", smoke.description).group(1))
    with zipfile.ZipFile(fmu_path) as z:
        lines = z.read(f"{LS_DIR}/smoke_ref.csv").decode().splitlines()
    names = [n.strip('"') for n in lines[0].split(",")]
    table = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    impulse = np.abs(table[:, names.index("contact_impulse_lower")]) + np.abs(
        table[:, names.index("contact_impulse_upper")]
    )
    first = table[np.argmax(impulse > 0), 0]
    assert impulse.any() and abs(first - stated) <= 2e-4, (
        f"smoke says first impact near {stated} s, its reference {first} s"
    )


def test_readme_explains_section_5_2_at_first_use():
    text = (REPO / "README.md").read_text()
    at = text.index("§5.2")
    assert "free vibration" in text[max(0, at - 100) : at + 200], text[at - 100 : at + 200]


def test_state_experiment_qualifies_bit_for_bit(fmu_path):
    with zipfile.ZipFile(fmu_path) as z:
        html = z.read("documentation/fmi-ls-ref.html").decode()
    sentences = [s for s in re.split(r"(?<=\.)\s", html) if "bit for bit" in s and "replay" in s]
    assert sentences, "fmi-ls-ref.html no longer says how the state replay compares"
    for s in sentences:
        assert "another master" in s and "tolerance" in s, s
