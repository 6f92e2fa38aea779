"""Issue 28: runs that use the new scenario fields (a stated impact speed, gravity 0, the contact at
the bridge's free end, a rigid support, a contact rate, a clearance, a power law with Hunt-Crossley
damping) replay from their logs through `beam_impact.load_log` (the Rust reader), and the FMU
simulates them from Python with the CLI's peaks."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import beam_impact

ROOT = Path(__file__).resolve().parents[2]


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


@pytest.mark.parametrize("settings", [
    [],
    ["--set", "contact.clearance=0.0005"],
    ["--set", "contact.law=power", "--set", "contact.stiffness=2e7", "--set", "contact.damping=0.2"],
])
def test_a_run_of_the_new_fields_replays_through_load_log(tmp_path, settings):
    log, out = tmp_path / "s.mcap", tmp_path / "s.json"
    run = subprocess.run([binary(), "run", str(ROOT / "examples" / "sdnl32-rigid-spring.toml"), *settings,
                          "--mcap", str(log), "--json", str(out)], capture_output=True, text=True, timeout=300)
    assert run.returncode in (0, 3), run.stderr
    loaded = beam_impact.load_log(str(log))
    assert loaded.complete
    assert 'kind = "rigid"' in loaded.scenario_toml and "impact_angular_velocity = 3.8" in loaded.scenario_toml
    steps = loaded.steps
    cli = json.loads(out.read_text())
    # The log's steps hold the run's contact force peak (the CLI's summary: the running peak, with
    # the converged method's extrema inside the steps), and forces up to it.
    peak = cli["summary"]["peaks"]["contact.force"]
    assert abs(steps["peaks.contact_force"][-1] - peak) <= 1e-9 * peak
    assert 0.99 * peak <= np.abs(steps["contact_force"]).max() <= peak
    assert cli["impact"]["angular_velocity"] == 3.8


def test_the_fmu_simulates_a_rigid_support_struck_at_a_stated_speed_as_the_cli_does(tmp_path):
    fmu_dir = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", ROOT / "target" / "fmu"))
    fmu = fmu_dir / "fmi2" / "BeamImpact.fmu"
    if not fmu.exists():
        pytest.skip(f"{fmu} not packed (run `beam-impact pack`)")
    out = tmp_path / "s.json"
    run = subprocess.run([binary(), "run", str(ROOT / "examples" / "sdnl32-rigid-spring.toml"), "--set", "method=paper",
                          "--no-mcap", "--json", str(out)], capture_output=True, text=True, timeout=300)
    assert run.returncode in (0, 3), run.stderr
    cli = json.loads(out.read_text())
    result = beam_impact.simulate(str(fmu), {
        "method": 1, "impact_angular_velocity": 3.8, "drop_height": 0.0, "gravity": 0.0, "contact_position": 0.783,
        "damping_ratio": 0.01, "upper.length": 0.783, "upper.mass": 0.3683232, "upper.elastic_modulus": 6.7e10,
        "upper.second_moment": 3.2013333333333333e-9, "upper.section_modulus": 4.573333333333333e-7,
        "lower.kind": 1, "contact.stiffness": 18000.0,
    }, stop_time=0.012)
    force = cli["summary"]["peaks"]["contact.force"]
    assert abs(result["peak.contact.force"] - force) <= 1e-9 * force, (result["peak.contact.force"], force)
