"""docs/plot_motion_checks.py (issue 17's check figures) runs from the CLI's runs and logs, draws its
two PNGs, and what it prints holds: after 2 s the slow heave's change of the bridge's free-end
position is its static value to within 2 % of the largest static value, the clamp stress changes
by under 2 % of its 170 MPa static value, and the energy residual under the 0.5 m heave stays
within 1 % of the largest strain energy (the run's trust bound)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_motion_check_figures(tmp_path):
    env = dict(os.environ)
    env.setdefault("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    done = subprocess.run([sys.executable, str(ROOT / "docs" / "plot_motion_checks.py"), str(tmp_path)],
                          capture_output=True, text=True, timeout=600, env=env)
    assert done.returncode == 0, done.stderr
    for name in ("motion-slow-heave.png", "motion-energy.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", name
    out = done.stdout
    m = re.search(r"by at most ([0-9.e+-]+) m \(static up to ([0-9.e+-]+) m\); the clamp stress changes by at most "
                  r"([0-9.e+-]+) MPa", out)
    assert m, out
    departure, static, stress = map(float, m.groups())
    assert static > 0.05 and departure < 0.02 * static, out
    assert stress < 0.02 * 170.0, out
    m = re.search(r"largest \|residual\| ([0-9.e+-]+) J, external work at the end ([0-9.e+-]+) kJ, largest strain "
                  r"([0-9.e+-]+) kJ", out)
    assert m, out
    residual, work, strain = map(float, m.groups())
    assert abs(work) > 0.1 and residual < 0.01 * strain * 1e3, out
