"""The vessel example's figure: BeamImpact's peak stresses against the wave phase at the impact.

    python docs/plot_vessel_phase.py                     # 12 phases, 3 s each: docs/vessel-phase.png
    python docs/plot_vessel_phase.py --phases 24 --out phase.png --set wave.amplitude=1.5

Builds the vessel-motion FMU (fmu/vessel/vessel_motion.c, with gcc), then for each wave phase
at the impact (0, 360/N, ... degrees) runs the master of tests/python/vessel_master.py: the vessel
drives BeamImpact's supports, BeamImpact's reactions go back as the deck load (h = 1 ms). One more
run on fixed supports is the reference. Prints one row per phase (the peaks sigma_a, sigma_b,
tau_a, F_c, the closing speed the supports add at the impact, the verdict) and draws the peaks
with the allowables (533 MPa bending, 355 MPa shear: BeamImpact's parameters). Needs fmpy,
matplotlib and numpy, gcc, and BeamImpact.fmu (BEAM_IMPACT_FMU_DIR or --fmu-dir, default
target/fmu; `beam-impact pack` writes it).
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python"))
import vessel_master as vm  # noqa: E402


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--phases", type=int, default=12, help="wave phases at the impact over one period (12)")
    parser.add_argument("--duration", type=float, default=vm.STOP, help="simulated time per run, s (3)")
    parser.add_argument("--out", default=str(ROOT / "docs" / "vessel-phase.png"), help="the figure (PNG)")
    parser.add_argument("--fmu-dir", default=str(vm.FMU_DIR), help="holds fmi2/BeamImpact.fmu")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a VesselMotion Real parameter (e.g. wave.amplitude=1.5), repeatable")
    args = parser.parse_args(argv[1:])
    if args.phases < 1 or not args.duration > 0:
        parser.error("--phases must be >= 1 and --duration > 0")
    parameters = {}
    for item in args.set:
        name, _, value = item.partition("=")
        parameters[name.strip()] = float(value)

    beam = vm.beam_fmu(Path(args.fmu_dir))
    phases = 2 * math.pi * np.arange(args.phases) / args.phases
    with tempfile.TemporaryDirectory() as scratch:
        work = Path(scratch)
        vessel, warnings = vm.build_vessel_fmu(work / "build")
        if warnings:
            print(warnings, file=sys.stderr)
        fixed = vm.run(beam, work, "fixed", stop=args.duration)
        runs = vm.phase_sweep(beam, vessel, phases, work, parameters, stop=args.duration)

    names = vm.PEAKS  # sigma_a, sigma_b, tau_a, F_c
    p = runs[0].parameters
    s = fixed.scenario
    print(f"VesselMotion: wave amplitude {p['wave.amplitude']:g} m, period {p['wave.period']:g} s "
          f"(length {p['wave.length']:.1f} m), heave RAO {p['heave.rao']:g} at {math.degrees(p['heave.phase']):.0f} deg, "
          f"pitch RAO {p['pitch.rao']:g} at {math.degrees(p['pitch.phase']):.0f} deg; hinge at x = {p['hinge.x']:g} m, "
          f"clamp at x = {p['clamp.x']:g} m (direction {p['clamp.direction']:g}); {args.duration:g} s from the impact, "
          f"h = {vm.STEP * 1e3:g} ms")
    print(f"{'phase':>7} {'sigma_a':>9} {'sigma_b':>9} {'tau_a':>9} {'F_c':>9} {'closing':>9}  trusted  warnings")
    print(f"{'[deg]':>7} {'[MPa]':>9} {'[MPa]':>9} {'[MPa]':>9} {'[MN]':>9} {'[m/s]':>9}")

    def row(label: str, run: vm.Run, closing: float) -> None:
        sa, sb, ta, fc = (run.peaks[n] for n in names)
        warned = sum(1 for status in run.beam_statuses if status != 0)
        print(f"{label:>7} {sa / 1e6:9.1f} {sb / 1e6:9.1f} {ta / 1e6:9.1f} {fc / 1e6:9.3f} {closing:9.3f}  "
              f"{str(run.trusted):>7}  {warned:>8}")

    row("fixed", fixed, 0.0)
    for phase, run in zip(phases, runs):
        row(f"{math.degrees(phase):g}", run, vm.closing_speed(run))

    # The phase is periodic: phase 0 is drawn again at 360 degrees.
    cycle = runs + runs[:1]
    degrees = np.append(np.degrees(phases), 360.0)
    peaks = {n: np.array([run.peaks[n] for run in cycle]) for n in names}
    closing = np.array([vm.closing_speed(run) for run in cycle])
    fig, (stress, force) = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True)
    styles = {"peak.lower.clamp_bending_stress": ("C0", "$\\sigma_a$ arrestor clamp bending"),
              "peak.upper.contact_bending_stress": ("C1", "$\\sigma_b$ bridge bending at contact"),
              "peak.lower.clamp_shear_stress": ("C2", "$\\tau_a$ arrestor clamp shear")}
    for name, (color, label) in styles.items():
        stress.plot(degrees, peaks[name] / 1e6, "o-", color=color, lw=1.3, ms=4, label=label)
        stress.axhline(fixed.peaks[name] / 1e6, color=color, ls=":", lw=1)
    stress.axhline(s["lower.allowable_bending_stress"] / 1e6, color="k", ls="--", lw=1,
                   label=f"allowable bending {s['lower.allowable_bending_stress'] / 1e6:.0f} MPa")
    stress.axhline(s["lower.allowable_shear_stress"] / 1e6, color="0.45", ls="--", lw=1,
                   label=f"allowable shear {s['lower.allowable_shear_stress'] / 1e6:.0f} MPa")
    untrusted = [k for k, run in enumerate(cycle) if run.trusted is not True]
    for name in styles:
        stress.plot(degrees[untrusted], peaks[name][untrusted] / 1e6, "x", color="red", ms=8)
    top = 1.3 * max(s["lower.allowable_bending_stress"], max(peaks[n].max() for n in styles)) / 1e6
    stress.set(xlabel="wave phase at the impact [deg]", ylabel="peak stress [MPa]", ylim=(0, top),
               title="Peak stresses (dotted: fixed supports)")
    stress.legend(fontsize=7, loc="upper center", ncol=2)
    force.plot(degrees, peaks["peak.contact.force"] / 1e6, "o-", color="C3", lw=1.3, ms=4, label="peak $F_c$")
    force.axhline(fixed.peaks["peak.contact.force"] / 1e6, color="C3", ls=":", lw=1, label="fixed supports")
    force.set(xlabel="wave phase at the impact [deg]", ylabel="peak contact force [MN]", ylim=(0, None),
              title="Contact force and the supports' closing speed at the impact")
    speed = force.twinx()
    speed.plot(degrees, closing, "s--", color="0.3", lw=1, ms=3, label="closing speed the supports add")
    speed.axhline(0.0, color="0.6", lw=0.6)
    speed.set(ylabel="closing speed at t = 0 [m/s]")
    lines = force.get_legend_handles_labels()[0] + speed.get_legend_handles_labels()[0]
    force.legend(lines, [line.get_label() for line in lines], fontsize=7, loc="lower center")
    for ax in (stress, force):
        ax.grid(alpha=0.3)
        ax.set_xticks(np.arange(0, 361, 60))
        ax.set_xlim(-10, 370)
    fig.suptitle(f"BeamImpact on a vessel in a regular head sea: {2 * p['wave.amplitude']:g} m, {p['wave.period']:g} s "
                 f"wave; the phase chooses the vessel's motion at the impact ({args.duration:g} s runs"
                 f"{', red x: not trusted' if untrusted else ', all trusted'})", fontsize=10)
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
