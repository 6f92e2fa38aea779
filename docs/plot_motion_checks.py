"""Figures of the moving-support checks (issue 17), from the CLI's runs and logs.

    python docs/plot_motion_checks.py [OUT_DIR]     (default docs/; BEAM_IMPACT_BIN: the binary)

1. `motion-slow-heave.png`: a slow hinge heave, h = 0.1 (1 - cos 2 pi 0.05 t) m, drop height 0,
   damping 0.05, the paper mesh: what the heave changes in the bridge's free-end position (the run
   against the same run on fixed supports) beside its static value h (1 - l_u / d) (the hinged
   bridge resting on the arrestor rotates rigidly about the contact point), and what it changes in
   the clamp's bending stress (statically nothing).
2. `motion-energy.png`: the energy account under a 0.5 m, 0.15 Hz hinge heave during the paper
   scenario's impact (converged method): kinetic, strain, gravity potential, the external work
   (the supports' work on the beams, booked in their frame) and the residual.

The same checks, with tolerances, are tests (tests/support_motion.rs); this draws them.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from beam_impact import load_log  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def binary() -> str:
    return os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))


def heave_csv(path: Path, duration: float, step: float, heave) -> None:
    """A hinge heave z(t) -> (z, v, a) sampled every `step` s."""
    with open(path, "w") as f:
        f.write("time,upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n")
        for n in range(int(round(duration / step)) + 1):
            t = n * step
            z, v, a = heave(t)
            f.write(f"{t!r},{z!r},{v!r},{a!r}\n")


def run(log: Path, *args: str) -> None:
    done = subprocess.run([binary(), "run", *args, "--mcap", str(log)], capture_output=True, text=True)
    if done.returncode not in (0, 1):  # 1: a result not trusted, still written
        raise SystemExit(f"beam-impact run failed: {done.stderr.strip()}")


def slow_heave(work: Path, out: Path) -> None:
    omega = 2 * math.pi * 0.05
    amplitude = 0.1
    heave_csv(work / "slow.csv", 4.0, 1e-3, lambda t: (amplitude * (1 - math.cos(omega * t)),
                                                       amplitude * omega * math.sin(omega * t),
                                                       amplitude * omega ** 2 * math.cos(omega * t)))
    # The paper's method and mesh with automatic steps.
    common = [str(ROOT / "examples" / "paper.toml"), "--set", "step_free=auto", "--set", "step_contact=auto",
              "--set", "drop_height=0", "--set", "damping_ratio=0.05", "--set", "duration=4"]
    run(work / "heaved.mcap", *common, "--motion", str(work / "slow.csv"))
    run(work / "fixed.mcap", *common)
    heaved, fixed = load_log(str(work / "heaved.mcap")).dataframe(), load_log(str(work / "fixed.mcap")).dataframe()
    t = heaved["time"].to_numpy()
    h = amplitude * (1 - np.cos(omega * t))
    # The free end's absolute position: its deflection (relative to the hinge) plus the hinge's heave.
    position = heaved["upper_tip_deflection"].to_numpy() + h
    fixed_position = np.interp(t, fixed["time"], fixed["upper_tip_deflection"])
    fixed_stress = np.interp(t, fixed["time"], fixed["lower_clamp_bending_stress"])
    static = h * (1 - 29.0 / 13.0)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    top.plot(t, position - fixed_position, label="run: heaved - fixed supports")
    top.plot(t, static, "--", label="static: h (1 - l_u / d)")
    top.set(ylabel="bridge free end, change [m]", title="slow hinge heave 0.1 m at 0.05 Hz, drop 0, damping 0.05")
    top.legend()
    bottom.plot(t, (heaved["lower_clamp_bending_stress"] - fixed_stress) / 1e6, label="run: heaved - fixed supports")
    bottom.axhline(0.0, ls="--", color="C1", label="static: 0 (statically determinate)")
    bottom.set(xlabel="time [s]", ylabel="clamp bending stress, change [MPa]")
    bottom.legend()
    fig.tight_layout()
    fig.savefig(out / "motion-slow-heave.png", dpi=110)
    late = t >= 2.0
    print(f"slow heave: after 2 s the free end's change departs from the static one by at most "
          f"{np.max(np.abs((position - fixed_position - static)[late])):.2e} m (static up to "
          f"{np.max(np.abs(static)):.3f} m); the clamp stress changes by at most "
          f"{np.max(np.abs((heaved['lower_clamp_bending_stress'] - fixed_stress)[late])) / 1e6:.3f} MPa")


def energy(work: Path, out: Path) -> None:
    omega = 2 * math.pi * 0.15
    heave_csv(work / "heave.csv", 3.0, 1e-3, lambda t: (0.5 * math.sin(omega * t), 0.5 * omega * math.cos(omega * t),
                                                       -0.5 * omega ** 2 * math.sin(omega * t)))
    run(work / "energy.mcap", "--set", "duration=3", "--motion", str(work / "heave.csv"))
    steps = load_log(str(work / "energy.mcap")).dataframe()
    t = steps["time"]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for column, label in [("energy.kinetic", "kinetic"), ("energy.strain", "strain (beams and bar)"),
                          ("energy.gravity_potential", "gravity potential"),
                          ("energy.external_work", "external work (the supports', in their frame)"),
                          ("energy.residual", "residual")]:
        ax.plot(t, steps[column] / 1e3, label=label)
    ax.set(xlabel="time [s]", ylabel="energy [kJ]", title="energy account under a 0.5 m, 0.15 Hz hinge heave")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "motion-energy.png", dpi=110)
    print(f"energy: largest |residual| {np.max(np.abs(steps['energy.residual'])):.1f} J, external work at the end "
          f"{steps['energy.external_work'].iloc[-1] / 1e3:.1f} kJ, largest strain {steps['energy.strain'].max() / 1e3:.1f} kJ")


def main(argv: list[str]) -> int:
    out = Path(argv[1]) if len(argv) > 1 else ROOT / "docs"
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        slow_heave(Path(work), out)
        energy(Path(work), out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
