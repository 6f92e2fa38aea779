"""The `beam_impact` Python package (issue 10): sweeps of the FMU as Dask tasks, against the CLI.

Goal: `beam_impact.sweep` on a 2-worker LocalCluster gives, row for row and in the same grid
order, the peaks and energy-approach values of `beam-impact sweep` of the same grid, by both
engines (issue 31's one rule: the FMU's, and the default, the Rust solver itself); a scenario
the FMU refuses is a row with the FMU's message and the sweep goes on; the local scheduler gives
the cluster's very numbers; the SPEC syntax gives the CLI's grid to the bit; `simulate` returns the
peaks and histories and logs only when asked; `load_log` reads a complete log and a killed run's.

Tolerances: the issue asks for 0.5 %; the FMU at one communication step over the run takes the
CLI's very internal steps (docs/fmu.md, "Co-simulation grid"), so the peaks are compared to 1e-9
relative (round-off), like tests/python/test_fmu.py; the native engine runs the CLI sweep's own
code for a row, so it meets the same bound (it gives the same bits). Both sides use automatic time steps: a scenario
file without steps on the CLI, the FMU's default 0 (`beam-impact sweep` without a file would run
the paper's 5e-5 / 2.5e-5 s pair).
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import beam_impact
from beam_impact.grid import parse_vary

ROOT = Path(__file__).resolve().parents[2]
FMU_DIR = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", str(ROOT / "target" / "fmu")))
# One name per quantity: the FMU's output names, as the CLI's sweep columns.
PEAKS = [
    "peak.lower.tip_deflection",
    "peak.lower.clamp_bending_stress",
    "peak.lower.clamp_shear_stress",
    "peak.upper.contact_bending_stress",
    "peak.contact.force",
]
CHECKS = ["quality.discretisation_error", "quality.sensitivity_spread", "utilisation.lower.clamp_bending_stress",
          "utilisation.lower.clamp_shear_stress", "utilisation.upper.contact_bending_stress"]
VERDICTS = ["design.pass", "quality.trusted"]
# The former names, duplicates until 0.2.0.
FORMER = {"lower_tip_deflection": PEAKS[0], "lower_clamp_bending_stress": PEAKS[1],
          "lower_clamp_shear_stress": PEAKS[2], "upper_contact_bending_stress": PEAKS[3], "contact_force": PEAKS[4],
          "discretisation_error": CHECKS[0], "sensitivity_spread": CHECKS[1],
          "utilisation.lower_clamp_bending_stress": CHECKS[2], "utilisation.lower_clamp_shear_stress": CHECKS[3],
          "utilisation.upper_contact_bending_stress": CHECKS[4], "design_pass": VERDICTS[0], "trusted": VERDICTS[1]}
#: The stress envelope's outputs (issue 30) the FMU gives and `simulate` returns.
ENVELOPE = [f"{kind}.{beam}.{stress}_stress" for kind in ("peak", "peak_position", "utilisation")
            for beam in ("upper", "lower") for stress in ("bending", "shear")]
METHOD = [f"energy_method.{n}" for n in ["tip_deflection", "force", "clamp_bending_stress", "clamp_shear_stress",
                                         "strain_energy"]]
# Two drop heights x two damping ratios x a contact point inside and one beyond the 29 m bridge.
VARY = ["drop_height=0.3:1.2:2", "damping_ratio=0.02,0.05", "contact_position=13,40"]


def fmu_path(version: str = "fmi2") -> str:
    path = FMU_DIR / version / "BeamImpact.fmu"
    assert path.exists(), f"{path} not found: run `beam-impact pack` or set BEAM_IMPACT_FMU_DIR"
    return str(path)


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


@pytest.fixture(scope="module")
def cluster():
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as c:
        with Client(c) as client:
            yield client


@pytest.fixture(scope="module")
def cli_rows(tmp_path_factory):
    directory = tmp_path_factory.mktemp("cli")
    scenario, out = directory / "auto.toml", directory / "rows.csv"
    scenario.write_text("# the defaults, automatic time steps (the FMU's default)\n")
    args = [binary(), "sweep", str(scenario), "--out", str(out)]
    for v in VARY:
        args += ["--vary", v]
    subprocess.run(args, check=True, capture_output=True)
    rows = pd.read_csv(out, keep_default_na=False, na_values=[""])
    rows["error"] = rows["error"].fillna("")
    return rows


@pytest.fixture(scope="module")
def cluster_rows(cluster):
    return beam_impact.sweep(parse_vary(VARY), client=cluster, fmu=fmu_path(), progress=False, check_sensitivity=True)


@pytest.fixture(scope="module")
def native_rows():
    """The default engine: the Rust solver itself (no FMU), on the local threads."""
    return beam_impact.sweep(parse_vary(VARY), progress=False, check_sensitivity=True)


@pytest.fixture(scope="module")
def native_cluster_rows(cluster):
    return beam_impact.sweep(parse_vary(VARY), client=cluster, engine="native", progress=False,
                             check_sensitivity=True)


#: The check figures: differences of nearly equal peaks, compared to 1e-9 absolute (each peak
#: agrees to 1e-9 relative).
FIGURES = {"quality.discretisation_error", "quality.sensitivity_spread", "discretisation_error", "sensitivity_spread"}
BOOLEANS = {"design.pass", "quality.trusted", "design_pass", "trusted"}
#: The CLI's sweep columns the FMU has no output for (docs/python.md, `sweep`'s docstring).
FMU_LACKS = [*(f"peak_time.{p.removeprefix('peak.')}" for p in PEAKS),
             *(f"energy_method.{n}" for n in ["flexion_stiffness", "bridge_deceleration", "bridge_contact_moment",
                                               "bridge_bending_stress", "bridge_strain_energy", "bridge_strain_ratio"]),
             "max_energy_residual", "yield_utilisation", "load_cases.utilisation",
             *(f"{former}_time" for former in list(FORMER)[:5])]


def test_the_native_sweep_has_the_cli_sweep_s_columns_and_the_fmu_s_lacks_only_its_missing_outputs(
        cli_rows, native_rows, cluster_rows):
    """Issue 41: `beam_impact.sweep` (the native engine, the default) has the columns of
    `beam-impact sweep --out` for the same grid, names and order (63 for one varied field: the
    peak times of tutorial step 6 among them); the FMU engine's are the CLI's less those the FMU
    has no output for (`beam_impact.dask_sweep.FMU_LACKS`, what the docs say it lacks), in the
    same order."""
    assert list(native_rows.columns) == list(cli_rows.columns)
    assert len(cli_rows.columns) == 63 + 2  # three varied fields here
    assert {f"peak_time.{p.removeprefix('peak.')}" for p in PEAKS} <= set(native_rows.columns)
    assert list(beam_impact.dask_sweep.FMU_LACKS) == FMU_LACKS
    assert set(FMU_LACKS) <= set(cli_rows.columns)
    assert list(cluster_rows.columns) == [c for c in cli_rows.columns if c not in FMU_LACKS]


# The one rule (issue 31): each engine's sweep, the FMU's and the solver's own, equals the CLI's.
@pytest.mark.parametrize("engine_rows", ["cluster_rows", "native_rows"])
def test_local_cluster_sweep_equals_the_cli_sweep(cli_rows, engine_rows, request):
    """Every column an engine gives (the native engine all of the CLI's) holds the CLI's values:
    numbers to 1e-9 relative (the check figures 1e-9 absolute), the CLI's empty cells as NaN, the
    verdicts equal; the former names duplicate their named columns."""
    py, cli = request.getfixturevalue(engine_rows), cli_rows
    varied = ["drop_height", "damping_ratio", "contact_position"]
    assert list(py.columns[:3]) == varied and {*PEAKS, *METHOD, *CHECKS, *VERDICTS, *FORMER} <= set(py.columns)
    for former, name in FORMER.items():
        assert former in cli.columns and name in cli.columns, former
        assert py[former].equals(py[name]) and cli[former].equals(cli[name]), former
    assert len(py) == len(cli) == 8
    for column in varied:
        assert py[column].tolist() == cli[column].tolist(), column
    ok = py["error"] == ""
    assert ok.tolist() == (cli["error"] == "").tolist() == [True, False] * 4
    worst = 0.0
    for column in py.columns:
        if column in varied or column in ("wall_time", "error"):
            continue
        if column in BOOLEANS:
            got = py.loc[ok, column].tolist()
            want = [str(v).lower() == "true" for v in cli.loc[ok, column]]
            assert got == want, f"{column}: {engine_rows} {got} vs CLI {want}"
            continue
        got, want = py.loc[ok, column].to_numpy(float), cli.loc[ok, column].to_numpy(float)
        assert (np.isnan(got) == np.isnan(want)).all(), f"{column}: {engine_rows} {got} vs CLI {want} (empty cells)"
        got, want = got[~np.isnan(want)], want[~np.isnan(want)]
        if column in FIGURES:
            # The FMU's sensitivity figure is its real twin's finite difference (drop height x (1 +
            # 1e-9): a floor of ~1e-7 from the twin's own nanosecond step choices), the CLI's the
            # printed run's tangent (issue 43): both round-off-level here, held to 1e-4 absolute,
            # a hundredth of the 1 % tolerance they are judged against (the verdicts, compared
            # above, agree). Every other figure, and the native engine's, to 1e-9.
            sensitivity = "sensitivity" in column and engine_rows == "cluster_rows"
            tolerance = 1e-4 if sensitivity else 1e-9
            assert np.abs(got - want).max(initial=0) <= tolerance, f"{column}: {engine_rows} {got} vs CLI {want}"
            continue
        rel = np.abs(got - want) / np.maximum(np.abs(want), 1e-300)
        worst = max(worst, rel.max(initial=0))
        assert rel.max(initial=0) <= 1e-9, f"{column}: {engine_rows} {got} vs CLI {want}"
    for column in CHECKS:  # the twin ran (check_sensitivity=True): every figure is there
        assert np.all(np.isfinite(py.loc[ok, column].to_numpy(float))), column
    # A failed row's results are NaN, as the CLI's cells are empty.
    results = [c for c in py.columns if c not in (*varied, "wall_time", "error")]
    assert py.loc[~ok, results].isna().all().all()
    print(f"{engine_rows} vs CLI: {len(py.columns)} columns, largest relative difference {worst:.3e} "
          f"over {ok.sum()} scenarios")


@pytest.mark.parametrize("engine_rows", ["cluster_rows", "native_rows"])
def test_a_failing_scenario_is_a_row_with_the_fmu_message(cli_rows, engine_rows, request):
    rows = request.getfixturevalue(engine_rows)
    failed = rows[rows["error"] != ""]
    assert (failed["contact_position"] == 40).all() and len(failed) == 4
    for message, cli_message in zip(failed["error"], cli_rows.loc[failed.index, "error"]):
        assert "contact_position must be on the upper beam" in message, message
        assert "contact_position must be on the upper beam" in cli_message, cli_message
    assert failed[PEAKS].isna().all().all()


def test_the_local_scheduler_gives_the_cluster_numbers(cluster_rows, native_rows, native_cluster_rows):
    local = beam_impact.sweep(parse_vary(VARY), fmu=fmu_path(), progress=False, check_sensitivity=True)
    # Every column but the rows' wall times, which are each run's own.
    pd.testing.assert_frame_equal(local.drop(columns="wall_time"), cluster_rows.drop(columns="wall_time"),
                                  check_exact=True)
    # The native engine: the same on a cluster's worker processes as on the local threads.
    pd.testing.assert_frame_equal(native_cluster_rows.drop(columns="wall_time"), native_rows.drop(columns="wall_time"),
                                  check_exact=True)
    for rows in (local, cluster_rows, native_rows, native_cluster_rows):
        assert (rows["wall_time"] > 0).all() and np.isfinite(rows["wall_time"]).all()


def test_spec_syntax_gives_the_cli_grid(tmp_path):
    vary = ["drop_height=0.1:2:7", "lower.elements=4:8:9", "step_free=auto,2e-5", "stress_recovery=mean,right"]
    grid = parse_vary(vary)
    assert grid["lower.elements"] == [4.0, 5.0, 6.0, 7.0, 8.0]
    assert parse_vary(["drop_height=0.2:1:3"])["drop_height"] == [0.2, 0.6, 1.0]
    points = beam_impact.expand(grid)
    assert len(points) == 7 * 5 * 2 * 2
    assert points[0] == {"drop_height": 0.1, "lower.elements": 4.0, "step_free": 0.0, "stress_recovery": 0.0}
    assert points[1]["stress_recovery"] == 2.0 and points[2]["step_free"] == 2e-5  # the last varies fastest
    out = tmp_path / "grid.csv"
    args = [binary(), "sweep", "--set", "duration=0.001", "--out", str(out)]
    for v in vary:
        args += ["--vary", v]
    subprocess.run(args, check=True, capture_output=True)
    cli = pd.read_csv(out, keep_default_na=False, dtype=str)
    from beam_impact.grid import display

    for k, point in enumerate(points):
        row = cli.iloc[k]
        for name, value in point.items():
            shown = display(name, value)
            assert (float(row[name]) if isinstance(shown, float) else row[name]) == (
                shown if isinstance(shown, float) else str(shown)), (k, name, row[name], shown)
    with pytest.raises(ValueError, match="upper.lenght"):
        beam_impact.sweep({"upper.lenght": [1.0]}, fmu=fmu_path())
    with pytest.raises(ValueError, match="upper.lenght"):
        beam_impact.sweep({"upper.lenght": [1.0]})
    with pytest.raises(ValueError, match="start:stop:count"):
        parse_vary(["drop_height=1:2"])


@pytest.mark.parametrize("spec, message", [
    # The CLI's parser and messages (issue 27: parse_vary is `beam-impact sweep --vary`'s).
    ("drop_height=0.1:0.5:18446744073709551615", r"more than a sweep runs \(1000000 scenarios\)"),
    ("drop_height=0.1:0.5:18446744073709551616", "from 1 to 1000000"),
    ("drop_height=0.1:0.5:100000000", r"more than a sweep runs \(1000000 scenarios\)"),
    ("lower.elements=inf", "whole number"),
    ("method=fast", "converged or paper"),
])
def test_hostile_grids_are_refused_before_any_value_is_built(spec, message):
    with pytest.raises(ValueError, match=message):
        beam_impact.expand(parse_vary([spec]))


def test_linspace_counts_are_bounded_as_the_cli_s():
    """Issue 40 (part 5) item 8: `linspace(0, 1, 10**9)` had no count limit (it built a billion values:
    4.7 GB). Its count is now bounded as the CLI's `--vary start:stop:count` is (from 1 to
    MAX_SCENARIOS, the very limit of the CLI's parser), refused at once in one line naming the limit
    and the value; within it, linspace gives the CLI's values."""
    from beam_impact.grid import MAX_SCENARIOS

    started = time.perf_counter()
    for count, shown in [(MAX_SCENARIOS + 1, "1000001"), (10**9, "1000000000"), (0, "0"), (-3, "-3"),
                         (2**80, "1208925819614629174706176"), (2.5, "2.5"), (True, "True"), ("10", "'10'")]:
        with pytest.raises(ValueError) as refused:
            beam_impact.linspace(0.0, 1.0, count)
        text = str(refused.value)
        assert f"from 1 to {MAX_SCENARIOS}" in text and text.endswith(f"got {shown}") and "\n" not in text, text
    assert time.perf_counter() - started < 5, "refused before any value is built"
    # The bound is the CLI's own: its parser takes MAX_SCENARIOS values and refuses one more.
    (values,) = parse_vary([f"drop_height=0:1:{MAX_SCENARIOS}"]).values()
    assert len(values) == MAX_SCENARIOS
    with pytest.raises(ValueError, match=f"more than a sweep runs \\({MAX_SCENARIOS} scenarios\\)"):
        parse_vary([f"drop_height=0:1:{MAX_SCENARIOS + 1}"])
    assert beam_impact.linspace(0.1, 0.5, 7) == beam_impact.parse_spec("drop_height", "0.1:0.5:7")
    assert beam_impact.linspace(0.1, 0.5, np.int64(1)) == [0.1]


def test_linspace_endpoints_are_finite_and_never_overflow():
    """Issue 40's re-test: `linspace(1e308, -1e308, 3)` gave [1e308, -inf, -1e308] and NaN or inf
    endpoints were taken. Now they are refused in one line, as the CLI's `--vary` refuses them, and
    a span that overflows still gives the CLI's points (1e308 / 2 - 1e308 / 2 = 0 exactly)."""
    for start, stop, shown in [(float("nan"), 1.0, "nan"), (0.0, float("inf"), "inf"), (-math.inf, 0.0, "-inf"),
                               (True, 1.0, "True"), ("0", 1.0, "'0'"), (10**400, 1.0, "1" + "0" * 99)]:
        with pytest.raises(ValueError) as refused:
            beam_impact.linspace(start, stop, 3)
        text = str(refused.value)
        assert "must be finite numbers" in text and shown in text and "\n" not in text, text
    assert beam_impact.linspace(1e308, -1e308, 3) == [1e308, 0.0, -1e308]
    assert beam_impact.linspace(1e308, -1e308, 3) == beam_impact.parse_spec("upper.tip_force", "1e308:-1e308:3")
    with pytest.raises(ValueError, match="must be finite numbers"):
        parse_vary(["drop_height=nan:1:3"])


def test_simulate_refuses_runs_it_cannot_finish():
    """Issue 16 item 8: `simulate(fmu, {"duration": 1e6})` ran for hours and `histories=True` on a
    long run ended in a SimulationError with an empty message. Now the stop time is bounded by the
    FMU's limit and the communication points by 1e7, each refused at once with a message."""
    with pytest.raises(beam_impact.SimulationError, match="at most 1e6 s"):
        beam_impact.simulate(fmu_path(), {"duration": 1e7})
    with pytest.raises(beam_impact.SimulationError, match="communication points"):
        beam_impact.simulate(fmu_path(), {"duration": 1000.0}, histories=True, output_interval=1e-5)
    # The reproduction itself: within the FMU's time limit, but 4.2e10 internal steps (the CLI
    # refuses it: at most 1e8): refused by the crate's own check before the FMU is loaded.
    started = time.perf_counter()
    with pytest.raises(beam_impact.SimulationError, match=r"at most 100000000 steps .* max_steps=N"):
        beam_impact.simulate(fmu_path(), {"duration": 1e6})
    assert time.perf_counter() - started < 60, "refused at once, not after stepping"
    # The limit is the CLI's --max-steps: a 0.01 s run needs 424 steps of 2.36e-5 s.
    with pytest.raises(beam_impact.SimulationError, match="this run needs 424 steps"):
        beam_impact.simulate(fmu_path(), {"duration": 0.01}, max_steps=100)
    assert beam_impact.simulate(fmu_path(), {"duration": 0.01}, max_steps=424)["trusted"] in (True, False)


def test_python_sweep_outputs_go_through_the_guard(tmp_path):
    """`python -m beam_impact sweep --out` wrote through a symbolic link and hung on a FIFO (an
    attack pass): both are refused before any run, the link's target untouched."""
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    link = tmp_path / "link.csv"
    link.symlink_to(victim)
    fifo = tmp_path / "fifo.csv"
    os.mkfifo(fifo)
    for out in [link, fifo]:
        done = subprocess.run([sys.executable, "-m", "beam_impact", "sweep", "--fmu", fmu_path(), "--vary",
                               "drop_height=0.5", "--out", str(out)], capture_output=True, text=True, timeout=120)
        assert done.returncode == 2 and ("symbolic link" in done.stderr or "FIFO" in done.stderr), done.stderr
    assert victim.read_text() == "keep me"


def test_a_grid_over_the_limit_is_refused_before_its_product():
    grid = {"drop_height": [0.1] * 1000, "damping_ratio": list(range(1001))}
    with pytest.raises(ValueError, match="more than 1000000 scenarios"):
        beam_impact.expand(grid)
    assert parse_vary(["method=paper,converged", "lower.elements=auto,7"]) == {
        "method": [1.0, 0.0], "lower.elements": [0.0, 7.0]}


@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_simulate_peaks_histories_and_log(version, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    peaks = beam_impact.simulate(fmu_path(version), {"drop_height": 0.8, "duration": 0.5})
    assert set(peaks) == set(PEAKS + ENVELOPE + METHOD + CHECKS + VERDICTS) | set(FORMER)
    assert math.isnan(peaks["sensitivity_spread"]), "the twin runs only when asked"
    # The stress envelope: the bridge has no shear area by default (the FMU's 0, the CLI's empty
    # cell: NaN); the arrestor's worst bending stress is at its clamp (0 m, a position, not NaN).
    assert math.isnan(peaks["peak.upper.shear_stress"]) and math.isnan(peaks["peak_position.upper.shear_stress"])
    assert peaks["peak_position.lower.bending_stress"] == 0 and peaks["peak.lower.bending_stress"] > 0
    assert 0 <= peaks["discretisation_error"] < 1 and isinstance(peaks["trusted"], bool)
    assert list(tmp_path.iterdir()) == [], "logging is off unless asked"
    log_path = tmp_path / "run.mcap"
    again, histories = beam_impact.simulate(fmu_path(version), {"drop_height": 0.8, "duration": 0.5},
                                            log_path=str(log_path), histories=True)
    del again["sensitivity_spread"], peaks["sensitivity_spread"]  # NaN (not checked) is not == NaN
    assert again == peaks, "the communication interval does not change the peaks or the checks"
    assert histories["time"].iloc[-1] == pytest.approx(0.5)
    assert len(histories) == 501
    assert histories["peak.lower.tip_deflection"].iloc[-1] == peaks["lower_tip_deflection"]
    log = beam_impact.load_log(str(log_path))
    assert log.complete and log.problem == ""
    assert log.answer is None, "the FMU's log stores no answer.json"
    frame = log.dataframe()
    assert frame["time_ns"].iloc[-1] == 500_000_000
    assert frame["peaks.lower_tip_deflection"].iloc[-1] == peaks["lower_tip_deflection"]
    with pytest.raises(beam_impact.SimulationError, match="drop_height must be >= 0 m, got -1"):
        beam_impact.simulate(fmu_path(version), {"drop_height": -1})


def test_load_log_reads_a_killed_run(tmp_path):
    """A log cut short (the file a killed writer leaves: no summary, no footer, maybe half a
    chunk) loads up to its last complete chunk, flagged incomplete."""
    path = tmp_path / "full.mcap"
    subprocess.run([binary(), "run", "--set", "duration=0.3", "--mcap", str(path)], check=True, capture_output=True)
    full = beam_impact.load_log(str(path))
    assert full.complete
    # The run's answer with its checks is stored with it (`run --json`'s quality and design).
    assert full.answer["quality"]["trusted"] is True and full.answer["design"]["pass"] is True
    assert [run["role"] for run in full.answer["discretisation"]["runs"]][:3] == ["printed", "check", "coarse"]
    data = path.read_bytes()
    cut = tmp_path / "killed.mcap"
    cut.write_bytes(data[: len(data) * 6 // 10])
    killed = beam_impact.load_log(str(cut))
    assert not killed.complete and killed.problem, killed.problem
    n = len(killed.steps["step"])
    assert 0 < n < len(full.steps["step"])
    for name, values in killed.steps.items():
        assert np.array_equal(values, full.steps[name][:n]), name
    # The old import path keeps working (tests/python/load_log.py re-exports the package's loader).
    sys.path.insert(0, str(Path(__file__).parent))
    from load_log import load_log as old_load_log

    assert old_load_log is beam_impact.load_log


def test_load_log_raises_one_error_type_for_any_bad_file(tmp_path):
    """Issue 16 item 3: `load_log` raised protobuf DecodeError, KeyError, TypeError, numpy
    ValueError on mutated logs, hung on a FIFO, and `python -m beam_impact log /etc/hostname`
    printed a traceback. Every bad file now raises `beam_impact.LogError` (a ValueError) with one
    line; a sample of mutated logs (bytes overwritten at random places, seeded) either loads or
    raises LogError. Not covered yet: the memory and time bounds of crafted compressed logs (the
    Rust reader's, for the native extension that issue 16 asks for)."""
    import random

    path = tmp_path / "short.mcap"
    subprocess.run([binary(), "run", "--set", "duration=0.02", "--mcap", str(path)], check=True, capture_output=True)
    data = path.read_bytes()
    text = tmp_path / "hostname"
    text.write_text("a text file\n")
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for bad in [text, fifo, tmp_path, tmp_path / "missing.mcap"]:
        with pytest.raises(beam_impact.LogError) as e:
            beam_impact.load_log(str(bad))
        assert "\n" not in str(e.value) and str(bad) in str(e.value)
    assert issubclass(beam_impact.LogError, ValueError)
    out = subprocess.run([sys.executable, "-m", "beam_impact", "log", str(text)], capture_output=True, text=True)
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and "Traceback" not in out.stderr, out.stderr
    rng = random.Random(16)
    outcomes = {"loaded": 0, "LogError": 0}
    for k in range(150):
        mutant = bytearray(data)
        for _ in range(rng.randint(1, 8)):
            mutant[rng.randrange(len(mutant))] = rng.randrange(256)
        m = tmp_path / f"mutant{k}.mcap"
        m.write_bytes(bytes(mutant))
        try:
            beam_impact.load_log(str(m))
            outcomes["loaded"] += 1
        except beam_impact.LogError:
            outcomes["LogError"] += 1
        m.unlink()
    print(f"150 mutated logs: {outcomes}")
    assert sum(outcomes.values()) == 150


def test_python_m_beam_impact_sweep(tmp_path):
    out = tmp_path / "rows.csv"
    run = subprocess.run(
        [sys.executable, "-m", "beam_impact", "sweep", "--fmu", fmu_path("fmi3"), "--stop-time", "0.5",
         "--vary", "drop_height=0.5,-1", "--out", str(out)],
        capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "1 of 2 scenarios failed" in run.stderr
    rows = pd.read_csv(out, keep_default_na=False, na_values=[""])
    assert rows["drop_height"].tolist() == [0.5, -1.0]
    assert rows["lower_tip_deflection"].iloc[0] > 0.1 and math.isnan(rows["lower_tip_deflection"].iloc[1])
    assert "drop_height must be >= 0 m, got -1" in rows["error"].iloc[1]
    # Issue 29: each row keeps its wall time, the failed one too.
    assert (rows["wall_time"] > 0).all(), rows["wall_time"].tolist()
    bad = subprocess.run([sys.executable, "-m", "beam_impact", "sweep", "--fmu", fmu_path(), "--vary", "nonsense=1",
                          "--out", str(out)], capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "nonsense" in bad.stderr, bad.stderr


def test_python_m_beam_impact_sweep_runs_the_solver_without_an_fmu(tmp_path):
    """Without --fmu the rows are the solver's own, from --scenario: `beam-impact sweep FILE`'s numbers."""
    scenario = tmp_path / "light.toml"
    scenario.write_text("duration = 0.4\n[upper]\nmass = 9000.0\n")
    out, cli_out = tmp_path / "rows.csv", tmp_path / "cli.csv"
    vary = ["--vary", "drop_height=0.3,0.9", "--vary", "contact_position=13,40"]
    run = subprocess.run([sys.executable, "-m", "beam_impact", "sweep", "--scenario", str(scenario), *vary,
                          "--out", str(out)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0 and "4 scenarios" in run.stdout and "2 of 4 scenarios failed" in run.stderr, run.stderr
    subprocess.run([binary(), "sweep", str(scenario), *vary, "--out", str(cli_out)], check=True, capture_output=True)
    rows, cli = (pd.read_csv(f, keep_default_na=False, na_values=[""]) for f in (out, cli_out))
    ok = rows["error"].fillna("") == ""
    assert ok.tolist() == [True, False, True, False]
    for column in PEAKS + METHOD:
        got, want = rows.loc[ok, column].to_numpy(), cli.loc[ok, column].to_numpy()
        assert np.all(np.abs(got - want) <= 1e-9 * np.abs(want)), column  # the same code: the same bits
    both = subprocess.run([sys.executable, "-m", "beam_impact", "sweep", "--scenario", str(scenario), "--fmu",
                           fmu_path(), "--vary", "drop_height=1", "--out", str(out)], capture_output=True, text=True)
    assert both.returncode == 2 and "--scenario is for the solver itself" in both.stderr, both.stderr


def test_the_docs_local_cluster_script_runs_as_written(tmp_path):
    """Issue 19: a LocalCluster script without the `__main__` guard fails ("Nanny failed to
    start"); docs/python-reference.md shows the guard. Its snippet runs here as a script, as a user
    saves it."""
    page = (ROOT / "docs" / "python-reference.md").read_text()
    start = page.index('  if __name__ == "__main__":') - len("  from dask.distributed import Client, LocalCluster\n\n")
    block_start = page.rindex("```python\n", 0, start) + len("```python\n")
    block = page[block_start:page.index("```", block_start)]
    script = "\n".join(line[2:] for line in block.splitlines())  # the page indents it by two (a list item)
    assert "LocalCluster" in script and '__name__ == "__main__"' in script
    (tmp_path / "study.py").write_text(script.replace("target/fmu/fmi2/BeamImpact.fmu", fmu_path()))
    run = subprocess.run([sys.executable, "study.py"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    table = pd.read_csv(tmp_path / "sweep.csv")
    assert list(table["drop_height"]) == [0.3, 0.6, 0.9] and table["lower_clamp_bending_stress"].gt(0).all()


def test_the_local_sweep_shows_a_bar_with_the_time_left(monkeypatch, capsys):
    """Issue 29: `progress=True` draws a tqdm bar on standard error (here from the start: the
    2 s delay set to 0) with the scenarios done, the elapsed and the estimated time left."""
    import beam_impact.dask_sweep as dask_sweep

    monkeypatch.setattr(dask_sweep, "BAR_DELAY", 0.0)
    table = beam_impact.sweep({"drop_height": [0.3, 0.6], "duration": [0.05]}, fmu=fmu_path(), progress=True)
    bar = capsys.readouterr().err
    assert "sweep" in bar and "2/2" in bar and "<00:00" in bar, bar  # tqdm: [elapsed<left, rate]
    assert (table["error"] == "").all() and (table["wall_time"] > 0).all()


def test_fmu_path_without_an_fmu_names_both_places(tmp_path, monkeypatch):
    """No FMU in BEAM_IMPACT_FMU_DIR nor inside the package (an install from source): one line
    naming both places; and the FMU route of the sweep without fmu= says so too (without
    engine="fmu" the sweep runs the solver itself and needs no FMU)."""
    import beam_impact.fmu as fmu_module

    monkeypatch.setattr(fmu_module, "PACKED_FMUS", tmp_path / "package" / "fmus")
    monkeypatch.setenv("BEAM_IMPACT_FMU_DIR", str(tmp_path / "empty"))
    monkeypatch.delenv("BEAM_IMPACT_FMU", raising=False)
    with pytest.raises(FileNotFoundError) as e:
        beam_impact.fmu_path("fmi3")
    message = str(e.value)
    assert "\n" not in message
    assert str(tmp_path / "empty" / "fmi3" / "BeamImpact.fmu") in message
    assert str(tmp_path / "package" / "fmus" / "fmi3" / "BeamImpact.fmu") in message
    with pytest.raises(ValueError, match="no FMU: pass fmu=PATH"):
        beam_impact.sweep({"drop_height": [1.0]}, engine="fmu")


def test_fmu_path_takes_beam_impact_fmu_dir(monkeypatch):
    monkeypatch.setenv("BEAM_IMPACT_FMU_DIR", str(FMU_DIR))
    assert beam_impact.fmu_path() == str(FMU_DIR / "fmi2" / "BeamImpact.fmu")
    assert beam_impact.fmu_path("fmi3") == str(FMU_DIR / "fmi3" / "BeamImpact.fmu")


def test_examples_are_the_repository_s_scenarios_from_a_checkout():
    """Issue 41: `beam_impact.examples()` names every example scenario of the checkout (a wheel's
    own copy is checked in tests/python/test_wheel.py)."""
    found = beam_impact.examples()
    assert sorted(found) == sorted(p.name for p in (Path(__file__).resolve().parents[2] / "examples").glob("*.toml"))
    assert all(Path(p).is_file() for p in found.values())


def test_simulate_max_steps_is_enforced_inside_the_fmus_do_step():
    """Issue 40: `simulate(max_steps=)` was only a check before the FMU ran (doStep had a built-in
    1e8 alone); now it is also the FMU's `solver.max_steps`, enforced at every internal step of
    doStep. The paper method adds a step wherever it locates a contact change: a limit at the
    plan's own count passes the check before the run and is reached inside it, with the FMU's
    message naming the limit and the time reached."""
    from beam_impact import _native

    needed = _native.check_run({"method": 1.0}, 0.3, 10**9)
    with pytest.raises(beam_impact.SimulationError, match=rf"max_steps = {needed} internal steps reached at t = "):
        beam_impact.simulate(fmu_path(), {"method": 1, "duration": 0.3}, max_steps=needed)
    # A limit with room runs to the end.
    assert beam_impact.simulate(fmu_path(), {"method": 1, "duration": 0.3}, max_steps=2 * needed)["trusted"] in (
        True, False)
