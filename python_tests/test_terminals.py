"""The FMI 3.0 terminals (terminalsAndIcons/terminalsAndIcons.xml): written from the binding's
terminals by the description writer, valid against the FMI 3.0 schema that fmpy ships, every
member a variable of the model description with the causality its terminal kind documents;
the FMI 2.0 FMU carries none (FMI 2.0 has no terminals)."""

import zipfile
from pathlib import Path

import fmpy
import pytest
from fmpy import read_model_description
from lxml import etree

ROOT = Path(__file__).resolve().parent.parent
FMU2 = ROOT / "build" / "PlateImpact.fmu"
FMU3 = ROOT / "build" / "fmi3" / "PlateImpact.fmu"
TERMINALS = "terminalsAndIcons/terminalsAndIcons.xml"

pytestmark = pytest.mark.skipif(not (FMU2.is_file() and FMU3.is_file()), reason="FMUs not built")

# What the kinds say (documentation/index.html of the FMI 3.0 FMU): memberName -> causality.
EXPECTED = {
    "clamp": (
        "bus",
        "org.plateimpact.TranslationalFlange",
        {
            "s": ("base_displacement", "input"),
            "v": ("base_velocity", "input"),
            "a": ("base_acceleration", "input"),
            "f": ("clamp_force", "output"),
        },
    ),
    "armature": (
        "plug",
        "org.plateimpact.TranslationalFlange",
        {
            "f": ("drive_force", "input"),
            "s": ("clamp_displacement", "output"),
            "v": ("clamp_velocity", "output"),
            "a": ("clamp_acceleration", "output"),
        },
    ),
    "line": (
        "org.plateimpact.crossed",
        "org.plateimpact.TransmissionLineEnd",
        {
            "wave_in": ("tlm_wave_in", "input"),
            "wave_out": ("tlm_wave_out", "output"),
            "impedance": ("tlm_impedance", "parameter"),
        },
    ),
}


def terminals_root():
    return etree.fromstring(zipfile.ZipFile(FMU3).read(TERMINALS))


def test_valid_against_the_fmi3_schema_fmpy_ships():
    schema = etree.XMLSchema(file=str(Path(fmpy.__file__).parent / "schema" / "fmi3" / "fmi3TerminalsAndIcons.xsd"))
    root = terminals_root()
    assert schema.validate(root), schema.error_log
    # not a formality: a member without its required variableKind is refused
    root.find("Terminals/Terminal/TerminalMemberVariable").attrib.pop("variableKind")
    assert not schema.validate(root)


def test_members_are_variables_of_the_model_with_the_documented_causality():
    variables = {v.name: v for v in read_model_description(str(FMU3)).modelVariables}
    terminals = {t.get("name"): t for t in terminals_root().iter("Terminal")}
    assert set(terminals) == set(EXPECTED)
    for name, (rule, kind, members) in EXPECTED.items():
        t = terminals[name]
        assert (t.get("matchingRule"), t.get("terminalKind")) == (rule, kind)
        got = {m.get("memberName"): m.get("variableName") for m in t.iter("TerminalMemberVariable")}
        assert got == {member: var for member, (var, _) in members.items()}
        for member, (var, causality) in members.items():
            assert variables[var].causality == causality, (name, member)
    page = zipfile.ZipFile(FMU3).read("documentation/index.html").decode()
    for kind in (
        "org.plateimpact.TranslationalFlange",
        "org.plateimpact.TransmissionLineEnd",
        "org.plateimpact.crossed",
    ):
        assert kind in page


def test_fmi2_fmu_has_none():
    names = zipfile.ZipFile(FMU2).namelist()
    assert not any(n.startswith("terminalsAndIcons/") for n in names)
    assert "org.plateimpact.TranslationalFlange" not in zipfile.ZipFile(FMU2).read("documentation/index.html").decode()
