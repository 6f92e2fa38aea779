"""Issue 42: a scenario's `[sea]` in Python: `beam_impact.run` takes it as `beam-impact run` does
(the same document, to the bit: the same Rust code on the same scenario), `--set`-style fields
reach the sea's, and `beam_impact.load_log` reads a `[sea]` run's log: the sea state and the RAO
file's SHA-256 in its metadata, the record as its motion table.

Tolerances: none (both sides run the same code)."""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
from pathlib import Path

import pytest

import beam_impact

ROOT = Path(__file__).resolve().parents[2]
FIXTURE = ROOT / "tests" / "fixtures" / "sea-raos.csv"

SEA = """duration = 1.0

[sea]
significant_wave_height = 1.0
peak_period = 8.0
seed = 7
time_shift = 100.0
raos = "raos.csv"
hinge_point = [-10.0, 0.0, 8.0]
clamp_point = [15.0, 0.0, 8.0]
"""


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


@pytest.fixture
def sea_folder(tmp_path):
    (tmp_path / "raos.csv").write_bytes(FIXTURE.read_bytes())
    (tmp_path / "s.toml").write_text(SEA)
    return tmp_path


def test_run_takes_a_sea_as_the_cli_does(sea_folder):
    out = sea_folder / "cli.json"
    done = subprocess.run([binary(), "run", str(sea_folder / "s.toml"), "--no-mcap", "--json", str(out)], capture_output=True,
                          text=True, cwd=sea_folder)
    assert done.returncode in (0, 1), done.stderr
    cli = json.loads(out.read_text())
    cli.pop("wall_time_s")
    result = dict(beam_impact.run(sea_folder / "s.toml"))
    assert result.pop("wall_time_s") > 0
    assert result == cli
    assert result["scenario"]["sea"]["seed"] == 7


def test_sea_fields_are_set_by_name_and_refused_with_the_cli_s_line(sea_folder):
    a = beam_impact.run(sea_folder / "s.toml", fields={"sea.seed": 8})
    b = beam_impact.run(sea_folder / "s.toml")
    assert a["scenario"]["sea"]["seed"] == 8
    assert a["summary"]["peaks"] != b["summary"]["peaks"]
    with pytest.raises(ValueError, match=r"sea.heading must be between 0 and 360 deg, got 400"):
        beam_impact.run(sea_folder / "s.toml", fields={"sea.heading": 400})


def test_load_log_reads_a_sea_run_s_sea_state_hash_and_record(sea_folder):
    log = sea_folder / "s.mcap"
    beam_impact.run(sea_folder / "s.toml", log=log)
    (sea_folder / "raos.csv").unlink()  # the log stands alone
    data = beam_impact.load_log(log)
    assert data.metadata["sea.raos_sha256"] == hashlib.sha256(FIXTURE.read_bytes()).hexdigest()
    assert data.metadata["sea.seed"] == "7"
    assert data.metadata["sea.significant_wave_height"] == "1.0"
    assert "[sea]" in data.scenario_toml
    motion = data.motion
    assert len(motion) == 201 and motion["time"].iloc[0] == 100.0
    assert "upper.hinge_heave" in motion.columns
