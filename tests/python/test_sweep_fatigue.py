"""Issue 44's leftovers from Python: `beam_impact.sweep(..., fatigue=True)` and
`beam_impact.campaign(..., fatigue=True, occurrence=...)` are the CLI's `sweep --fatigue` and
`campaign --fatigue --occurrence`, not second implementations.

Goal: the sweep's fatigue columns are the CLI's JSON rows to the bit, and without `fatigue` the
table keeps its columns; the campaign's rows are the CLI's CSV rows to the bit (but `wall_time`)
and its `summary["fatigue"]` the CLI's `--json` block (the weighted damage the same float); a bad
occurrence table is a one-line ValueError; `occurrence=` without `fatigue=True` is refused; the
FMU engine refuses `fatigue=True`.

Small runs (the load-cases example's two drops; the example vessel's four cells of 2 events of
0.5 s): a few seconds on two cores.
"""

from __future__ import annotations

import json
import math
import subprocess

import pytest

import beam_impact
from test_campaign import ROOT, assert_rows_equal, binary, cli_campaign

LOAD_CASES = ROOT / "examples" / "load-cases.toml"
OCCURRENCE = ROOT / "examples" / "vessel-sea-occurrence.csv"
FATIGUE_COLUMNS = ["fatigue.damage", "fatigue.life", "fatigue.beam", "fatigue.position"]


def test_a_fatigue_sweep_is_the_clis_rows_to_the_bit(tmp_path):
    out, rows = tmp_path / "rows.csv", tmp_path / "rows.json"
    done = subprocess.run([binary(), "sweep", str(LOAD_CASES), "--vary", "drop_height=0.3,0.6", "--fatigue",
                           "--set", "fatigue.events_per_year=100", "--out", str(out), "--json", str(rows)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    cli = json.loads(rows.read_text())
    # The base scenario with the events a year set, as the CLI's --set: its TOML text.
    text = LOAD_CASES.read_text() + "\n[fatigue]\nevents_per_year = 100.0\n"
    table = beam_impact.sweep({"drop_height": [0.3, 0.6]}, scenario=text, fatigue=True, progress=False,
                              stop_time=None)
    assert list(table.columns) == list(cli[0].keys())
    at = list(table.columns).index("load_cases.utilisation")
    assert list(table.columns)[at + 1:at + 5] == FATIGUE_COLUMNS
    for k, row in enumerate(cli):
        for name in FATIGUE_COLUMNS:
            assert table[name][k] == row[name], f"row {k}, {name}: {table[name][k]!r} vs {row[name]!r}"
        assert table["fatigue.life"][k] * table["fatigue.damage"][k] * 100 == pytest.approx(1, rel=1e-12)


def test_without_fatigue_the_table_keeps_its_columns():
    table = beam_impact.sweep({"drop_height": [0.3]}, stop_time=0.05, progress=False)
    assert len(table.columns) == 63
    assert not [c for c in table.columns if c.startswith("fatigue.")]


def test_the_fmu_engine_refuses_fatigue():
    with pytest.raises(ValueError, match="fatigue=True is for the native engine"):
        beam_impact.sweep({"drop_height": [0.3]}, engine="fmu", fmu="no-such.fmu", fatigue=True)


GRID = {"sea.significant_wave_height": [1, 2], "sea.peak_period": [6, 8]}
GRID_TEXTS = ["sea.significant_wave_height=1,2", "sea.peak_period=6,8"]
SET = {"duration": 0.5, "fatigue.events_per_year": 50}
SET_TEXTS = ["duration=0.5", "fatigue.events_per_year=50"]


def test_a_fatigue_campaign_is_the_clis_rows_and_weighted_damage(tmp_path):
    args = ["--events", "2", "--seeds", "1", "--fatigue", "--occurrence", str(OCCURRENCE), "--jobs", "2"]
    for v in GRID_TEXTS:
        args += ["--vary", v]
    for s in SET_TEXTS:
        args += ["--set", s]
    header, cli_rows, document, stdout = cli_campaign(tmp_path, *args)
    result = beam_impact.campaign(str(ROOT / "examples" / "vessel-sea.toml"), events=2, seeds=1, vary=GRID, set=SET,
                                  fatigue=True, occurrence=str(OCCURRENCE), jobs=2, progress=False)
    assert_rows_equal(result.rows, header, cli_rows)
    assert result.summary["fatigue"] == document["fatigue"]
    f = result.summary["fatigue"]
    assert f["damage_per_event"] > 0 and math.isfinite(f["life_years"])
    assert "weighted over the occurrence table" in result.text
    assert result.text.split("fatigue (")[1] in stdout


@pytest.mark.parametrize("table, named", [
    ("significant_wave_height,peak_period,probability\n1,7,0.5\n", "Hs 1 m, Tp 7 s is not a cell"),
    ("significant_wave_height,peak_period,probability\n1,6,0.7\n2,8,0.7\n", "sum to 1.4"),
    ("significant_wave_height,peak_period,probability\n1,6,nan\n", "must be a finite number"),
])
def test_a_bad_occurrence_table_is_one_line(tmp_path, table, named):
    path = tmp_path / "occurrence.csv"
    path.write_text(table)
    with pytest.raises(ValueError) as e:
        beam_impact.campaign(str(ROOT / "examples" / "vessel-sea.toml"), events=2, seeds=1, vary=GRID, set=SET,
                             fatigue=True, occurrence=str(path), progress=False)
    assert named in str(e.value) and "\n" not in str(e.value)


def test_occurrence_needs_fatigue():
    with pytest.raises(ValueError, match="give fatigue=True too"):
        beam_impact.campaign(str(ROOT / "examples" / "vessel-sea.toml"), events=2, seeds=1, vary=GRID,
                             occurrence=str(OCCURRENCE), progress=False)
