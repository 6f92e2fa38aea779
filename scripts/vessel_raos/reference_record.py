#!/usr/bin/env python3
"""An independent synthesiser of a scenario's sea record (issue 42's spec), to check `beam-impact sea`.

Written from the spec alone (docs/sea-states.md), not from the Rust code: the spectrum (JONSWAP or
Pierson-Moskowitz in Hs/Tp form, DNV-RP-C205 3.5.5, DNV's gamma rule), the components (N equal
bins, splitmix64 seeded with `seed`: u_i then v_i per bin, w_i = w_min + (i + u_i) dw, phase
2 pi v_i, amplitude sqrt(2 S(w_i) dw)), the RAOs of our CSV interpolated linearly as complex
numbers between frequencies and headings (180-360 deg by port-starboard symmetry), the deck points'
heave w = heave - x pitch + y roll and the clamp's rotation -pitch cos psi + roll sin psi, and the
sums with their exact derivatives. Needs numpy (Python >= 3.11 for tomllib).

    python scripts/vessel_raos/reference_record.py examples/vessel-sea.toml --duration 20 --out ref.csv
    python scripts/vessel_raos/reference_record.py examples/vessel-sea.toml --check sea.csv   # vs beam-impact sea
    python scripts/vessel_raos/reference_record.py examples/vessel-sea.toml --duration 10800 --sample-interval 0.1 --stats

The CSV: `time` (the record's time, s: the run's time plus sea.time_shift), `wave_elevation` (m, at
the vessel's motion reference point), then the supports' nine motion columns named as in
examples/vessel-motion.csv (a support without a deck point has none). `--check FILE` evaluates the
record at FILE's times and prints the largest difference of each column, absolute and relative to
the column's largest value. Defaults it must choose where the spec is silent, as the sea-core's
rustdoc states them: components 1000; frequency_min/max 0.5 w_p and 5 w_p clipped to the RAO file's
frequencies; sample interval 0.005 s on the grid k dt of record times.
"""

from __future__ import annotations

import argparse
import math
import sys
import tomllib
from pathlib import Path

import numpy as np

MASK = (1 << 64) - 1
SUPPORT_COLUMNS = {
    "hinge": ["upper.hinge_heave", "upper.hinge_heave_velocity", "upper.hinge_heave_acceleration"],
    "clamp": [
        "lower.clamp_heave", "lower.clamp_heave_velocity", "lower.clamp_heave_acceleration",
        "lower.clamp_rotation", "lower.clamp_rotation_velocity", "lower.clamp_rotation_acceleration",
    ],
}
DOFS = ["surge", "sway", "heave", "roll", "pitch", "yaw"]
MIRROR = np.array([1, -1, 1, -1, 1, -1])  # H(360 - beta) = MIRROR * H(beta): sway, roll, yaw change sign


class SplitMix64:
    """splitmix64 (Steele, Lea, Flood 2014; Vigna's splitmix64.c), wrapping 64-bit arithmetic."""

    def __init__(self, seed: int):
        self.state = seed & MASK

    def next_u64(self) -> int:
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return z ^ (z >> 31)

    def uniform(self) -> float:
        return (self.next_u64() >> 11) * 2.0**-53


def dnv_gamma(hs: float, tp: float) -> float:
    """DNV-RP-C205 3.5.5.5: 5 for Tp/sqrt(Hs) <= 3.6, exp(5.75 - 1.15 Tp/sqrt(Hs)) between, 1 from 5."""
    r = tp / math.sqrt(hs)
    if r <= 3.6:
        return 5.0
    if r >= 5.0:
        return 1.0
    return math.exp(5.75 - 1.15 * r)


def spectrum(w, hs: float, tp: float, kind: str, gamma: float | None):
    """S(w), m^2 s/rad (DNV-RP-C205 3.5.5.1 and 3.5.5.4 in Hs/Tp form)."""
    w = np.asarray(w, dtype=float)
    wp = 2 * math.pi / tp
    pm = 5.0 / 16.0 * hs**2 * wp**4 * w**-5 * np.exp(-1.25 * (w / wp) ** -4)
    if kind == "pierson-moskowitz":
        return pm
    g = dnv_gamma(hs, tp) if gamma is None else gamma
    sigma = np.where(w <= wp, 0.07, 0.09)
    return (1 - 0.287 * math.log(g)) * pm * g ** np.exp(-((w - wp) ** 2) / (2 * sigma**2 * wp**2))


def components(hs, tp, kind, gamma, n, lo, hi, seed):
    """The N components: frequencies, amplitudes, phases (the spec's order of draws)."""
    rng = SplitMix64(seed)
    dw = (hi - lo) / n
    w = np.empty(n)
    phase = np.empty(n)
    for i in range(n):
        u = rng.uniform()
        v = rng.uniform()
        w[i] = lo + (i + u) * dw
        phase[i] = 2 * math.pi * v
    a = np.sqrt(2 * spectrum(w, hs, tp, kind, gamma) * dw)
    return w, a, phase, dw


def read_rao_csv(path: Path):
    """Our RAO CSV: (frequencies ascending, headings ascending, H[freq, heading, dof] complex with
    rotations in rad/m)."""
    rows = [line for line in Path(path).read_text().splitlines() if line.strip() and not line.lstrip().startswith("#")]
    names = [c.strip() for c in rows[0].split(",")]
    table = np.array([[float(c) for c in r.split(",")] for r in rows[1:]])
    col = {n: i for i, n in enumerate(names)}
    freqs = np.unique(table[:, col["frequency"]])
    heads = np.unique(table[:, col["heading"]])
    h = np.full((len(freqs), len(heads), 6), np.nan, dtype=complex)
    for r in table:
        i = int(np.searchsorted(freqs, r[col["frequency"]]))
        j = int(np.searchsorted(heads, r[col["heading"]]))
        for d, name in enumerate(DOFS):
            amp = r[col[name]] * (math.pi / 180 if d >= 3 else 1.0)
            h[i, j, d] = amp * np.exp(1j * math.radians(r[col[name + "_phase"]]))
    if np.isnan(h).any():
        raise SystemExit(f"{path}: the grid of frequencies and headings is not complete")
    return freqs, heads, h


def rao_at_heading(heads, h, beta: float):
    """H[freq, dof] at heading beta (deg): linear between the file's headings, 180-360 mirrored."""
    beta = beta % 360.0
    sign = np.ones(6)
    if heads.max() <= 180.0 and beta > 180.0:
        beta, sign = 360.0 - beta, MIRROR
    j = np.searchsorted(heads, beta)
    if j < len(heads) and heads[j] == beta:
        return h[:, j, :] * sign
    if j == 0 or j == len(heads):
        raise SystemExit(f"heading {beta} deg is outside the file's headings {heads.min()} to {heads.max()}")
    f = (beta - heads[j - 1]) / (heads[j] - heads[j - 1])
    return ((1 - f) * h[:, j - 1, :] + f * h[:, j, :]) * sign


def rao_at_frequencies(freqs, h_beta, w):
    """H[component, dof]: linear in the complex RAOs between the file's frequencies."""
    out = np.empty((len(w), 6), dtype=complex)
    for d in range(6):
        out[:, d] = np.interp(w, freqs, h_beta[:, d].real) + 1j * np.interp(w, freqs, h_beta[:, d].imag)
    return out


class Record:
    def __init__(self, scenario: Path):
        sea = tomllib.loads(Path(scenario).read_text())["sea"]
        self.sea = sea
        self.hs = float(sea["significant_wave_height"])
        self.tp = float(sea["peak_period"])
        self.kind = sea.get("spectrum", "jonswap")
        self.gamma = sea.get("peak_enhancement")
        self.heading = float(sea.get("heading", 180.0))
        self.seed = int(sea.get("seed", 1))
        self.n = int(sea.get("components", 1000))
        self.time_shift = float(sea.get("time_shift", 0.0))
        self.dt = float(sea.get("sample_interval", 0.005))
        freqs, heads, h = read_rao_csv(Path(scenario).parent / sea["raos"])
        wp = 2 * math.pi / self.tp
        self.lo = float(sea.get("frequency_min", max(0.5 * wp, freqs.min())))
        self.hi = float(sea.get("frequency_max", min(5.0 * wp, freqs.max())))
        self.w, self.a, self.phase, self.dw = components(self.hs, self.tp, self.kind, self.gamma, self.n, self.lo, self.hi, self.seed)
        six = rao_at_frequencies(freqs, rao_at_heading(heads, h, self.heading), self.w)
        psi = math.radians(float(sea.get("arrestor_direction", 180.0)))
        wave = self.a * np.exp(1j * self.phase)
        self.coefficients = {}  # column prefix -> c_i (complex, per component)
        for support, key in (("hinge", "hinge_point"), ("clamp", "clamp_point")):
            if key not in sea:
                continue
            x, y, _ = (float(v) for v in sea[key])
            rise = six[:, 2] - x * six[:, 4] + y * six[:, 3]
            self.coefficients[SUPPORT_COLUMNS[support][0]] = wave * rise
            if support == "clamp":
                self.coefficients[SUPPORT_COLUMNS[support][3]] = wave * (-six[:, 4] * math.cos(psi) + six[:, 3] * math.sin(psi))
        self.wave = wave

    def columns(self):
        cols = ["time", "wave_elevation"]
        for support in ("hinge", "clamp"):
            if SUPPORT_COLUMNS[support][0] in self.coefficients:
                cols += SUPPORT_COLUMNS[support]
        return cols

    def evaluate(self, times):
        """The columns at the record's `times` (s): sums over components in chunks of time."""
        times = np.asarray(times, dtype=float)
        out = {"time": times}
        out["wave_elevation"] = np.empty(len(times))
        series = {}
        for name in self.coefficients:
            for suffix in ("", "_velocity", "_acceleration"):
                series[name + suffix] = np.empty(len(times))
        chunk = max(1, 2_000_000 // len(self.w))
        for s in range(0, len(times), chunk):
            t = times[s:s + chunk]
            e = np.exp(1j * np.outer(t, self.w))  # (time, component)
            out["wave_elevation"][s:s + chunk] = (e @ self.wave).real
            for name, c in self.coefficients.items():
                series[name][s:s + chunk] = (e @ c).real
                series[name + "_velocity"][s:s + chunk] = (e @ (1j * self.w * c)).real
                series[name + "_acceleration"][s:s + chunk] = (e @ (-self.w**2 * c)).real
        out.update(series)
        return out

    def grid(self, start: float, end: float):
        """Record times k dt from start to end (the sea-core's grid)."""
        k0 = math.ceil(start / self.dt - 1e-9)
        k1 = math.floor(end / self.dt + 1e-9)
        return np.arange(k0, k1 + 1) * self.dt


def read_csv(path: Path):
    lines = [line for line in Path(path).read_text().splitlines() if line.strip() and not line.startswith("#")]
    names = [c.strip() for c in lines[0].split(",")]
    data = np.array([[float(c) for c in line.split(",")] for line in lines[1:]])
    return {n: data[:, i] for i, n in enumerate(names)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scenario", type=Path, help="a scenario file with a [sea] section (its RAO file: our CSV)")
    parser.add_argument("--duration", type=float, default=10.0, help="s of record from sea.time_shift (10)")
    parser.add_argument("--out", type=Path, help="write the record here (CSV)")
    parser.add_argument("--check", type=Path, help="a CSV of `beam-impact sea` to compare with, at its times")
    parser.add_argument("--offset", type=float, default=0.0,
                        help="record time = the checked file's time + OFFSET (0: its times are the record's)")
    parser.add_argument("--sample-interval", type=float, help="s between rows (default: sea.sample_interval, else 0.005)")
    parser.add_argument("--stats", action="store_true", help="print Hs = 4 sqrt(m0): the components' and the record's")
    args = parser.parse_args(argv)

    rec = Record(args.scenario)
    if args.sample_interval:
        rec.dt = args.sample_interval
    print(f"{rec.kind}, Hs {rec.hs} m, Tp {rec.tp} s, gamma {rec.gamma if rec.gamma is not None else dnv_gamma(rec.hs, rec.tp):.4g}, "
          f"heading {rec.heading} deg, seed {rec.seed}, {rec.n} components over {rec.lo:.6g} to {rec.hi:.6g} rad/s "
          f"(dw {rec.dw:.6g}), sample interval {rec.dt} s")
    if args.check:
        theirs = read_csv(args.check)
        ours = rec.evaluate(theirs["time"] + args.offset)
        print(f"{len(theirs['time'])} rows of {args.check} ({theirs['time'][0]} to {theirs['time'][-1]} s)")
        worst = 0.0
        for name in rec.columns()[1:]:
            if name not in theirs:
                print(f"  {name:36s} missing from {args.check}")
                worst = math.inf
                continue
            diff = np.max(np.abs(ours[name] - theirs[name]))
            scale = np.max(np.abs(ours[name]))
            worst = max(worst, diff / scale if scale > 0 else diff)
            print(f"  {name:36s} max |difference| {diff:.3e} (largest value {scale:.4g}: {diff / scale if scale else 0:.1e} of it)")
        print(f"largest relative difference {worst:.1e}")
    times = rec.grid(rec.time_shift, rec.time_shift + args.duration)
    if args.out or args.stats:
        rows = rec.evaluate(times)
        if args.out:
            cols = rec.columns()
            with open(args.out, "w", newline="\n") as f:
                f.write(",".join(cols) + "\n")
                for k in range(len(times)):
                    f.write(",".join(repr(float(rows[c][k])) for c in cols) + "\n")
            print(f"wrote {args.out}: {len(times)} rows")
        if args.stats:
            m0 = float(np.sum(rec.a**2) / 2)
            print(f"Hs: requested {rec.hs} m, the components' 4 sqrt(m0) {4 * math.sqrt(m0):.4f} m, "
                  f"the record's 4 std {4 * np.std(rows['wave_elevation']):.4f} m over {args.duration} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
