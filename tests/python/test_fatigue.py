"""Issue 44 item 3: `beam-impact fatigue --json` against two independent rainflow counters on the
same histories: PyPI `rainflow` (ASTM E1049-85 with half cycles, as ours: the same list of
cycles) and `fatpack` (the four-point method: its closed cycles, and its residue, whose
neighbouring ranges are half cycles: the same count per range and mean, see `histogram`).
Cycles equal exactly (range, mean and count are differences, sums and halves of the same
doubles); damage to 1e-9 relative, from the packages' cycles on the same DNV-RP-C203 curve
computed here (N = 10^(log a - m log10 S), S in MPa; the 1e-9 covers pow/log10 of different libms,
a few ulps per cycle).
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

rainflow = pytest.importorskip("rainflow")
fatpack = pytest.importorskip("fatpack")

ROOT = Path(__file__).resolve().parents[2]


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


def histories() -> dict[str, np.ndarray]:
    """Structured and random histories, Pa."""
    rng = np.random.default_rng(44)
    t = np.linspace(0.0, 10.0, 2001)
    out = {
        "astm_fig6": np.array([-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]) * 1e7,
        "sine_with_noise": 80e6 * np.sin(2 * np.pi * 0.7 * t) + 5e6 * rng.standard_normal(t.size),
        "decaying_impact": 150e6 * np.exp(-0.3 * t) * np.sin(2 * np.pi * 2.1 * t) + 20e6,
        "plateaus": np.repeat(rng.integers(-5, 6, 300).astype(float) * 1e7, 3),
        "random_walk": np.cumsum(rng.standard_normal(3000)) * 3e6,
        "uniform": rng.uniform(-200e6, 200e6, 1500),
        "diverging_then_converging": np.array([(-1) ** i * (i if i < 50 else 100 - i) for i in range(101)]) * 2e6,
        "monotone": np.linspace(-1e8, 1e8, 50),
        "constant": np.full(20, 3e7),
    }
    for k in range(5):
        out[f"random_{k}"] = rng.normal(0.0, 60e6, 400 + 200 * k)
    return out


def write_csv(path: Path, columns: dict[str, np.ndarray]) -> None:
    n = max(len(v) for v in columns.values())
    names = list(columns)
    lines = ["time," + ",".join(names)]
    for i in range(n):
        cells = [repr(float(i) * 1e-3)]
        for name in names:
            v = columns[name]
            cells.append(repr(float(v[min(i, len(v) - 1)])))
        lines.append(",".join(cells))
    path.write_text("\n".join(lines) + "\n")


def padded(columns: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Each column as the CSV holds it (shorter ones repeat their last value: a plateau)."""
    n = max(len(v) for v in columns.values())
    return {k: np.concatenate([v, np.full(n - len(v), v[-1])]) for k, v in columns.items()}


def curve_n(curve: dict, s_pa: float) -> float:
    """Cycles to failure on the command's curve (its JSON parameters), S in Pa."""
    s = s_pa * 1e-6
    if s == 0.0:
        return float("inf")
    if curve["n_switch"] is not None:
        switch = 10.0 ** ((curve["log_a1"] - np.log10(curve["n_switch"])) / curve["m1"])
        if s < switch:
            return 10.0 ** (curve["log_a2"] - curve["m2"] * np.log10(s))
    return 10.0 ** (curve["log_a1"] - curve["m1"] * np.log10(s))


def damage(cycles, curve: dict, factor: float, dff: float) -> float:
    return dff * sum(count / curve_n(curve, rng * factor) for rng, _, count in cycles)


def key(cycles):
    """Cycles as a sorted list, zero ranges dropped (`rainflow` counts a constant history's one
    range-0 half cycle; we count no cycle)."""
    return sorted((r, m, c) for r, m, c in cycles if r != 0.0)


def histogram(cycles):
    """Total count per (range, mean), zero ranges dropped. Where neighbouring ranges tie, ASTM's
    start-point rule counts two half cycles a-b, b-a where the four-point method closes one full
    cycle b-a: the same range and mean, the same count, the same damage."""
    totals: dict[tuple[float, float], float] = {}
    for r, m, c in cycles:
        if r != 0.0:
            totals[(r, m)] = totals.get((r, m), 0.0) + c
    return totals


def rainflow_cycles(y: np.ndarray):
    return [(float(r), float(m), float(c)) for r, m, c, _, _ in rainflow.extract_cycles(y)]


def fatpack_cycles(y: np.ndarray):
    # fatpack.find_reversals bins the signal (k levels); the exact reversals come from rainflow's
    # extractor, and fatpack's four-point counter closes the cycles.
    reversals = np.array([float(v) for _, v in rainflow.reversals(y)])
    if reversals.size < 2:
        return []
    closed, residue = fatpack.find_rainflow_cycles(reversals)
    out = [(abs(float(b) - float(a)), 0.5 * (float(a) + float(b)), 1.0) for a, b in np.asarray(closed).reshape(-1, 2)]
    residue = [float(v) for v in residue]
    out += [(abs(b - a), 0.5 * (a + b), 0.5) for a, b in zip(residue, residue[1:])]
    return out


@pytest.mark.parametrize("curve_name,scf,thickness,dff", [
    ("D", 1.0, None, 1.0),
    ("F-seawater-cp", 1.7, 0.04, 3.0),
    ("W3-free-corrosion", 1.0, 0.03, 2.0),
    ("C-2024", 1.2, None, 1.0),
])
def test_cycles_and_damage_equal_rainflow_and_fatpack(tmp_path, curve_name, scf, thickness, dff):
    columns = histories()
    csv = tmp_path / "history.csv"
    write_csv(csv, columns)
    args = [binary(), "fatigue", str(csv), "--curve", curve_name, "--scf", str(scf), "--dff", str(dff),
            "--json", str(tmp_path / "out.json")]
    if thickness is not None:
        args += ["--thickness", str(thickness)]
    subprocess.run(args, check=True, capture_output=True)
    doc = json.loads((tmp_path / "out.json").read_text())
    curve = doc["curve"]
    factor = scf * (max(thickness or 0.0, curve["reference_thickness_m"]) / curve["reference_thickness_m"]) ** \
        curve["thickness_exponent"]
    worst = 0.0
    for column, y in zip(doc["columns"], padded(columns).values()):
        ours = [(c["range"], c["mean"], c["count"]) for c in column["cycles"]]
        by_rainflow = rainflow_cycles(y)
        by_fatpack = fatpack_cycles(y)
        assert key(ours) == key(by_rainflow), column["name"]
        assert histogram(ours) == histogram(by_fatpack), column["name"]
        for theirs in (by_rainflow, by_fatpack):
            expected = damage(theirs, curve, factor, dff)
            if expected == 0.0:
                assert column["damage"] == 0.0, column["name"]
                continue
            rel = abs(column["damage"] / expected - 1.0)
            worst = max(worst, rel)
            assert rel <= 1e-9, (column["name"], column["damage"], expected)
    print(f"{curve_name}: largest relative damage difference against rainflow/fatpack {worst:.3e}")


def test_astm_example_cycles_as_the_standard_table(tmp_path):
    csv = tmp_path / "astm.csv"
    write_csv(csv, {"sigma": np.array([-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0])})
    out = subprocess.run([binary(), "fatigue", str(csv), "--curve", "D", "--json", "-"], check=True,
                         capture_output=True, text=True)
    cycles = json.loads(out.stdout)["columns"][0]["cycles"]
    totals: dict[float, float] = {}
    for c in cycles:
        totals[c["range"]] = totals.get(c["range"], 0.0) + c["count"]
    assert totals == {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}
