"""Issue 45: a rigid impactor's run (`upper.kind = "mass"`, Hertz's law) replays from its log
through `beam_impact.load_log`: the stored answer holds each contact window as a sub-impact
(start, duration, peak force, restitution), the same as `run --json` prints."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import beam_impact

ROOT = Path(__file__).resolve().parents[2]


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


def test_a_sphere_on_a_beam_replays_its_sub_impacts_through_load_log(tmp_path):
    log, out = tmp_path / "sphere.mcap", tmp_path / "sphere.json"
    run = subprocess.run([binary(), "run", str(ROOT / "examples" / "lab-sphere.toml"), "--mcap", str(log),
                          "--json", str(out)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    cli = json.loads(out.read_text())
    loaded = beam_impact.load_log(str(log))
    assert loaded.complete
    assert 'kind = "mass"' in loaded.scenario_toml and 'law = "hertz"' in loaded.scenario_toml
    stored = loaded.answer["sub_impacts"]
    assert stored == cli["sub_impacts"]
    assert len(stored) == len(cli["summary"]["contact_windows"]) >= 2
    first = stored[0]
    # The stated 0.5 m/s, plus what gravity adds before the contact stage is located (g t, t of a
    # few microseconds at most: below 1e-6 m/s).
    assert abs(first["approach_speed"] - 0.5) <= 1e-6
    assert 0.0 < first["restitution"] < 1.0
    # The first strike's peak is the run's largest contact force.
    assert abs(max(s["peak_force"] for s in stored) - cli["summary"]["peaks"]["contact.force"]) \
        <= 1e-9 * cli["summary"]["peaks"]["contact.force"]
