"""The sea-state page's figure: a sea record beside the spectrum it came from (docs/sea-states.md).

    beam-impact sea examples/vessel-sea.toml --duration 1200 --out sea.csv
    python docs/plot_sea_state.py examples/vessel-sea.toml sea.csv           # docs/sea-state.png

Reads the record `beam-impact sea` wrote (columns `time`, `wave_elevation` and the supports' motion
columns of examples/vessel-motion.csv) and the scenario's `[sea]` values. Draws the wave elevation
and the supports' heaves over the first minutes, and the spectra: the target S(w) (JONSWAP or
Pierson-Moskowitz, DNV-RP-C205 3.5.5, in Hs/Tp form) against a Welch estimate of the elevation
(Hann windows of --window seconds, half overlapping), and each support's heave spectrum
|H_w(w)|^2 S(w) (H_w the deck point's heave RAO: heave - x pitch + y roll, from the scenario's RAO
file when it is our CSV) against the Welch estimate of its column. Prints Hs = 4 std of the record
against the requested and the components' band. Needs numpy and matplotlib (the repository's .venv).
"""

from __future__ import annotations

import argparse
import math
import sys
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts" / "vessel_raos"))
import reference_record as rr  # noqa: E402  (the spec's spectrum and RAO interpolation)


def welch(x: np.ndarray, dt: float, window_s: float):
    """One-sided power spectral density of x (units^2 s/rad) against w (rad/s): Welch's method with
    Hann windows of window_s seconds, 50 % overlap, the mean removed per segment."""
    n = int(round(window_s / dt))
    n = min(n, len(x))
    step = n // 2
    win = np.hanning(n)
    acc = np.zeros(n // 2 + 1)
    count = 0
    for s in range(0, len(x) - n + 1, step):
        seg = x[s:s + n] - np.mean(x[s:s + n])
        acc += np.abs(np.fft.rfft(seg * win)) ** 2
        count += 1
    psd_hz = acc / count * dt / np.sum(win**2)  # the periodogram |X|^2 dt / sum(win^2): units^2/Hz, two-sided
    psd_hz[1:-1] *= 2  # one-sided
    f = np.fft.rfftfreq(n, dt)
    return 2 * math.pi * f, psd_hz / (2 * math.pi), count


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scenario", type=Path, help="the scenario whose [sea] made the record")
    parser.add_argument("record", type=Path, help="the CSV of `beam-impact sea SCENARIO --duration T --out FILE`")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "sea-state.png")
    parser.add_argument("--window", type=float, default=200.0, help="Welch window, s (200: 0.031 rad/s resolution)")
    parser.add_argument("--show", type=float, default=180.0, help="seconds of record drawn (180)")
    args = parser.parse_args(argv)

    sea = tomllib.loads(args.scenario.read_text())["sea"]
    hs, tp = float(sea["significant_wave_height"]), float(sea["peak_period"])
    kind, gamma = sea.get("spectrum", "jonswap"), sea.get("peak_enhancement")
    data = rr.read_csv(args.record)
    t = data["time"]
    dt = float(np.median(np.diff(t)))
    eta = data["wave_elevation"]
    duration = t[-1] - t[0]

    w_grid = np.linspace(0.05, 3.0, 600)
    target = rr.spectrum(w_grid, hs, tp, kind, gamma)
    w_eta, s_eta, segments = welch(eta, dt, args.window)
    hs_record = 4 * np.std(eta)
    print(f"record: {len(t)} rows, {duration:.0f} s at {dt * 1e3:.3g} ms; Hs requested {hs} m, "
          f"4 std of the record {hs_record:.3f} m ({100 * (hs_record / hs - 1):+.1f} %); Welch: {segments} windows of {args.window:g} s")

    # The supports' heave spectra, when the RAO file is our CSV.
    responses = []
    rao_path = args.scenario.parent / sea["raos"]
    if rao_path.suffix.lower() == ".csv":
        freqs, heads, h = rr.read_rao_csv(rao_path)
        six = rr.rao_at_frequencies(freqs, rr.rao_at_heading(heads, h, float(sea.get("heading", 180.0))), w_grid)
        for label, key, column in (("hinge", "hinge_point", "upper.hinge_heave"), ("clamp", "clamp_point", "lower.clamp_heave")):
            if key in sea and column in data:
                x, y, _ = (float(v) for v in sea[key])
                rise = six[:, 2] - x * six[:, 4] + y * six[:, 3]
                predicted = np.abs(rise) ** 2 * target
                w_r, s_r, _ = welch(data[column], dt, args.window)
                m0 = np.trapezoid(predicted, w_grid)
                print(f"{label} heave: std of the record {np.std(data[column]):.3f} m, sqrt of the integral of |H|^2 S {math.sqrt(m0):.3f} m")
                responses.append((label, column, predicted, w_r, s_r))

    fig = plt.figure(figsize=(11, 7.5))
    grid = fig.add_gridspec(2, 2, height_ratios=[1, 1.2])
    ax = fig.add_subplot(grid[0, :])
    shown = t - t[0] <= args.show
    ax.plot(t[shown], eta[shown], color="tab:blue", lw=1.0, label="wave elevation at the reference point")
    colours = {"hinge": "tab:orange", "clamp": "tab:green"}
    for label, column, *_ in responses:
        ax.plot(t[shown], data[column][shown], color=colours[label], lw=1.0, label=f"{label} heave")
    ax.set_xlabel("record time [s]")
    ax.set_ylabel("[m]")
    ax.set_title(f"The record: Hs {hs:g} m, Tp {tp:g} s, {kind}, heading {sea.get('heading', 180.0):g} deg, seed {sea.get('seed', 1)}")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8, ncol=3)

    ax = fig.add_subplot(grid[1, 0])
    ax.plot(w_grid, target, color="black", lw=1.5, label="target S(w)")
    ax.plot(w_eta, s_eta, color="tab:blue", lw=1.0, alpha=0.8, label=f"Welch estimate of the record ({duration:.0f} s)")
    ax.set_xlim(0, 2.5)
    ax.set_xlabel("w [rad/s]")
    ax.set_ylabel("S [m$^2$ s/rad]")
    ax.set_title(f"Wave spectrum: Hs from the record {hs_record:.2f} m")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)

    ax = fig.add_subplot(grid[1, 1])
    for label, column, predicted, w_r, s_r in responses:
        ax.plot(w_grid, predicted, color=colours[label], lw=1.5, label=f"{label}: |H|$^2$ S")
        ax.plot(w_r, s_r, color=colours[label], lw=1.0, alpha=0.6, ls="--", label=f"{label}: Welch of the record")
    ax.set_xlim(0, 2.5)
    ax.set_xlabel("w [rad/s]")
    ax.set_ylabel("S [m$^2$ s/rad]")
    ax.set_title("The supports' heave spectra")
    ax.grid(alpha=0.3)
    if responses:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
