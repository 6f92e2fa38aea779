"""Issue 45: a run of the struck beam on two supports (the deck beam example: pinned-pinned,
struck at midspan) replays from its log through `beam_impact.load_log` (the Rust reader): the
scenario with its supports and contact position, the steps, the arrestor's contact-point
deflection at its peak, and the contact bar's force, as the run's JSON has them."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import numpy as np

import beam_impact

ROOT = Path(__file__).resolve().parents[2]


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


def test_a_deck_beam_run_replays_through_load_log(tmp_path):
    log, out = tmp_path / "deck.mcap", tmp_path / "deck.json"
    run = subprocess.run([binary(), "run", str(ROOT / "examples" / "deck-beam-supports.toml"),
                          "--mcap", str(log), "--json", str(out)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    loaded = beam_impact.load_log(str(log))
    assert loaded.complete
    assert 'supports = "pinned-pinned"' in loaded.scenario_toml and "contact_position = 6.0" in loaded.scenario_toml
    peaks = json.loads(out.read_text())["summary"]["peaks"]
    steps = loaded.steps
    # The log's dense output holds the exact state at each peak (docs/logs.md): its largest
    # |deflection| and |contact force| are the run's peaks to the recorded digits.
    deflection = np.max(np.abs(steps["lower_tip_deflection"]))
    force = np.max(np.abs(steps["contact_force"]))
    assert abs(deflection / peaks["lower_tip_deflection"] - 1) < 1e-9, (deflection, peaks)
    assert abs(force / peaks["contact_force"] - 1) < 1e-9, (force, peaks)
    # A pin carries no moment: the first support's bending stress stays 0 at every step.
    assert np.all(steps["lower_clamp_bending_stress"] == 0.0)
    # The far support's reactions are in the log (issue 45): at t = 0 the beam rests on its two
    # pins, each carrying half its weight (to round-off: 1e-9), the far pin carries no moment,
    # and the last step's force is the run's final one (the JSON's, to its printed digits).
    far_force, far_moment = steps["lower.far_reaction_force"], steps["lower.far_reaction_moment"]
    assert np.array_equal(far_force, steps["lower_far_reaction_force"])
    weight = 10124.0 * 9.81  # the example's lower.mass (kg) times the default gravity (m/s^2)
    assert abs(far_force[0] / (weight / 2) - 1) < 1e-9, far_force[0]
    assert np.all(far_moment == 0.0)
    assert np.any(far_force != far_force[0]), "the bridge's impact moves the far reaction"
