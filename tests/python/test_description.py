"""The packed model descriptions as importers read them (issue 8, items 3 and 6).

Goal, with fmpy's own reader and a real XML parser on the packed FMUs: every output depends on no
input after initialization (`dependencies=""`; an absent attribute would mean "on every input" and
put an algebraic loop into every feedback coupling), while in Initialization Mode the outputs do
depend on the inputs; every unit comes from a type definition (`declaredType`), none sits on an
FMI 3 variable (rust-fmi refuses `unit` on `Float64`); parameters hold their start values within
their declared min/max.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import pytest
from fmpy import read_model_description

ROOT = Path(__file__).resolve().parents[2]
FMU_DIR = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", str(ROOT / "target" / "fmu")))


def fmu_path(version: str) -> str:
    path = FMU_DIR / version / "BeamImpact.fmu"
    assert path.exists(), f"{path} not found: run `beam-impact pack` or set BEAM_IMPACT_FMU_DIR"
    return str(path)


@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_outputs_depend_on_no_input_after_initialization(version):
    md = read_model_description(fmu_path(version))
    inputs = {v.name for v in md.modelVariables if v.causality == "input"}
    motion = {f"{support}{suffix}" for support in ("upper.hinge_heave", "lower.clamp_heave", "lower.clamp_rotation")
              for suffix in ("", "_velocity", "_acceleration")}
    assert inputs == {"upper.tip_force", "lower.tip_force"} | motion
    assert md.outputs
    for unknown in md.outputs:
        assert unknown.dependencies == [], unknown.variable.name
    for unknown in md.initialUnknowns:
        names = {v.name for v in unknown.dependencies}
        if unknown.variable.causality == "output":
            assert inputs <= names, unknown.variable.name
        else:
            assert not inputs & names, unknown.variable.name


@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_units_come_from_type_definitions_and_starts_lie_within_min_max(version):
    md = read_model_description(fmu_path(version))
    for v in md.modelVariables:
        assert v.unit is None, f"{v.name} declares its unit itself"
        if v.type in ("Real", "Float64"):
            assert v.declaredType is not None and v.declaredType.unit, v.name
        if v.causality == "parameter" and v.type not in ("String", "Boolean"):
            start = float(v.start)
            assert v.min is not None, v.name
            assert float(v.min) <= start, v.name
            assert v.max is None or start <= float(v.max), v.name


def test_fmi3_variables_have_no_unit_attribute():
    with zipfile.ZipFile(fmu_path("fmi3")) as archive:
        root = ET.fromstring(archive.read("modelDescription.xml"))
    types = {t.get("name"): t for t in root.find("TypeDefinitions")}
    for v in root.find("ModelVariables"):
        assert "unit" not in v.attrib and "displayUnit" not in v.attrib, v.get("name")
        if v.get("declaredType") is not None:
            assert v.get("declaredType") in types, v.get("name")
    assert types["Stress"].get("unit") == "Pa" and types["Stress"].get("displayUnit") == "MPa"
