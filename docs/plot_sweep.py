"""The sweep figure of docs/cli.md: peak arrestor clamp stress over drop height, one line per damping ratio.

    beam-impact sweep --vary drop_height=0.1:2:100 --vary damping_ratio=0.005:0.05:10 --out sweep.csv
    python docs/plot_sweep.py sweep.csv docs/sweep-arrestor-stress.png

Needs matplotlib (`pip install "./python[plot]"`). Untrusted runs (their energy balance misses by
more than the scenario's tolerance) are drawn as crosses; failed scenarios are left out.
"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(__doc__)
        return 2
    rows = pd.read_csv(argv[1], keep_default_na=False, na_values=[""])
    rows = rows[rows["error"].astype("string").fillna("") == ""]
    fig, (stress, deflection) = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True)
    ratios = sorted(rows["damping_ratio"].unique())
    colors = plt.cm.viridis([k / max(1, len(ratios) - 1) for k in range(len(ratios))])
    for ratio, color in zip(ratios, colors):
        r = rows[rows["damping_ratio"] == ratio].sort_values("drop_height")
        label = f"{ratio:g}"
        stress.plot(r["drop_height"], r["peak.lower.clamp_bending_stress"] / 1e6, color=color, lw=1.3, label=label)
        deflection.plot(r["drop_height"], r["peak.lower.tip_deflection"], color=color, lw=1.3, label=label)
        bad = r[r["quality.trusted"].astype(str).str.lower() != "true"]
        stress.plot(bad["drop_height"], bad["peak.lower.clamp_bending_stress"] / 1e6, "x", color="red", ms=5)
        deflection.plot(bad["drop_height"], bad["peak.lower.tip_deflection"], "x", color="red", ms=5)
    first = rows[rows["damping_ratio"] == ratios[0]].sort_values("drop_height")
    stress.plot(first["drop_height"], first["energy_method.clamp_bending_stress"] / 1e6, "k--", lw=1,
                label="energy approach")
    deflection.plot(first["drop_height"], first["energy_method.tip_deflection"], "k--", lw=1,
                    label="energy approach")
    stress.set(xlabel="drop height h [m]", ylabel="peak clamp bending stress $\\sigma_{din,a}$ [MPa]",
               title="Arrestor clamp stress (peak over 3 s)")
    deflection.set(xlabel="drop height h [m]", ylabel="peak arrestor end deflection $w_{din,a}$ [m]",
                   title="Arrestor end deflection (peak over 3 s)")
    for ax in (stress, deflection):
        ax.grid(alpha=0.3)
    stress.legend(title="damping ratio", fontsize=7, title_fontsize=8, ncol=2)
    untrusted = int((rows["quality.trusted"].astype(str).str.lower() != "true").sum())
    verdict = f"{untrusted} not trusted (red x)" if untrusted else "all trusted by their energy balance"
    fig.suptitle(f"beam-impact sweep: {len(rows)} scenarios, paper scenario (mesh and steps), 3 s each, {verdict}",
                 fontsize=10)
    fig.savefig(argv[2], dpi=110)
    print(f"wrote {argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
