"""The fatigue of a run read back from its log by `beam_impact.load_log` (issue 44, item 3).

Goal: `run --json`'s `fatigue` block, `beam-impact report LOG --fatigue` and `load_log(LOG).fatigue`
are one computation on one history (the log's `fatigue.json`, the turning points of every step of
the printed run): the same numbers, compared exactly (JSON with round-trip precision); on a beam of
sections (the three-section gangway) the section changes are hot spots; `beam_impact.run`'s
document carries the same block. A log without stress stations (written before them) has `fatigue`
None and says why.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

import beam_impact
from beam_impact import load_log

ROOT = Path(__file__).resolve().parents[2]
OLD = ROOT / "tests" / "fixtures" / "log-before-stations.mcap"


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


@pytest.fixture(scope="module", params=["paper.toml", "three-section-gangway.toml"])
def fatigue_run(request, tmp_path_factory):
    directory = tmp_path_factory.mktemp("fatigue")
    log, summary = directory / "run.mcap", directory / "run.json"
    scenario = ROOT / "examples" / request.param
    subprocess.run(
        [binary(), "run", str(scenario), "--set", "duration=0.5", "--set", "fatigue.events_per_year=2000",
         "--mcap", str(log), "--json", str(summary)],
        check=True,
        capture_output=True,
    )
    return request.param, log, json.loads(summary.read_text())["fatigue"]


def test_load_log_replays_the_runs_fatigue(fatigue_run):
    name, log, block = fatigue_run
    replayed = load_log(log)
    assert replayed.fatigue_note == ""
    assert replayed.fatigue == block
    assert block["source"] == "every step"
    assert block["life_years"] > 0
    names = {h["name"] for h in block["hot_spots"]}
    assert {"clamp", "contact", "largest stress"} <= names
    if name == "three-section-gangway.toml":
        assert "section change" in names


def test_report_prints_the_runs_fatigue(fatigue_run):
    _, log, block = fatigue_run
    out = subprocess.run([binary(), "report", str(log), "--fatigue"], check=True, capture_output=True, text=True).stdout
    for beam in ("lower", "upper"):
        assert rust_exp(block["worst"][beam]["damage"]) in out


def rust_exp(x: float) -> str:
    """x as Rust's `{:.4e}` writes it (3.8225e-5, 1.2000e2: no sign or padding on the exponent)."""
    mantissa, exponent = f"{x:.4e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def test_the_python_run_document_carries_the_fatigue_block():
    doc = beam_impact.run(ROOT / "examples" / "paper.toml", duration=0.2, check_sensitivity=False)
    assert doc["fatigue"]["curve"] == "D"
    assert doc["fatigue"]["worst"]["upper"]["damage"] > 0


def test_a_log_without_stations_has_no_fatigue():
    log = load_log(OLD)
    assert log.fatigue is None
    assert "no stress history" in log.fatigue_note
