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


def test_a_chattering_sphere_replays_its_truncated_sub_impacts_through_load_log(tmp_path):
    """The lab sphere made to chatter (no damping, 0.5 s, gravity 98.1 m/s^2: 139 windows): the
    log's answer keeps the first 100 windows (and the largest-force one if later) with
    `sub_impacts_total` and `sub_impacts_truncated`, the same as `run --json`."""
    text = (ROOT / "examples" / "lab-sphere.toml").read_text()
    text = text.replace("duration = 0.02", "duration = 0.5").replace("damping_ratio = 0.005", "damping_ratio = 0.0")
    text = text.replace("gravity = 9.81", "gravity = 98.1")
    scenario, log, out = tmp_path / "chatter.toml", tmp_path / "chatter.mcap", tmp_path / "chatter.json"
    scenario.write_text(text)
    run = subprocess.run([binary(), "run", str(scenario), "--mcap", str(log), "--json", str(out)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    cli = json.loads(out.read_text())
    answer = beam_impact.load_log(str(log)).answer
    assert cli["sub_impacts_total"] > 100 and cli["sub_impacts_truncated"] is True
    assert len(cli["sub_impacts"]) in (100, 101)
    for key in ("sub_impacts", "sub_impacts_total", "sub_impacts_truncated"):
        assert answer[key] == cli[key], key
