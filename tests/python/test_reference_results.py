"""The reference results packed into each FMU, reproduced by fmpy (issue 18).

Goal: `extra/org.beam-impact.reference/BeamImpact_ref.csv` inside each FMU (every output of the
paper scenario at every millisecond, 0 to 3 s, computed at pack time through an instance of the
packed build) is what an importer gets: fmpy's `simulate_fmu` with the FMU's defaults and 1 ms
output interval returns the same numbers, bit for bit: the FMU counts time in integer
nanoseconds, so fmpy's communication points (k * 1 ms, rounded) land on the very steps of the
reference run, and the CSV's numbers are written so that they parse back exactly (repr).
"""

from __future__ import annotations

import csv
import io
import os
import zipfile
from pathlib import Path

import fmpy
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
FMU_DIR = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", str(ROOT / "target" / "fmu")))
REFERENCE = "extra/org.beam-impact.reference/BeamImpact_ref.csv"


def reference(fmu: Path) -> tuple[list[str], np.ndarray]:
    with zipfile.ZipFile(fmu) as archive:
        text = archive.read(REFERENCE).decode()
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], np.array([[float(x) for x in row] for row in rows[1:]])


@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_fmpy_reproduces_the_packed_reference_results(version, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    fmu = FMU_DIR / version / "BeamImpact.fmu"
    assert fmu.exists(), f"{fmu} not found: run `beam-impact pack` or set BEAM_IMPACT_FMU_DIR"
    names, expected = reference(fmu)
    assert names[0] == "time" and expected.shape == (3001, len(names))
    description = fmpy.read_model_description(str(fmu))
    outputs = [v.name for v in description.modelVariables if v.causality == "output"]
    assert names[1:] == outputs, "the CSV's columns are the FMU's outputs in order"
    result = fmpy.simulate_fmu(
        str(fmu), stop_time=3.0, output_interval=1e-3, start_values={"log.path": ""}, output=outputs
    )
    assert len(result) == len(expected)
    np.testing.assert_allclose(result["time"], expected[:, 0], rtol=0, atol=1e-12)
    for k, name in enumerate(outputs, start=1):
        got = np.asarray(result[name], dtype=float)
        differ = np.flatnonzero(got != expected[:, k])
        assert differ.size == 0, (
            f"{version} {name}: {differ.size} of {len(got)} values differ from the reference, first at "
            f"t = {expected[differ[0], 0]} s: {got[differ[0]]!r} against {expected[differ[0], k]!r}"
        )
