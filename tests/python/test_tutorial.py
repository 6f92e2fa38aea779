"""docs/tutorial.md runs as written (issue 19).

Goal: every ```sh and ```python block of the tutorial runs, in order, in one fresh working
directory, and succeeds; what the tutorial states about the results holds (one CSV row per drop
height, the figure written, the worst case the one it goes on with, the FMU giving the CLI's
peaks, the log and its figures written). The ```sh setup block (build, pack, pip install) is what
the suite's environment has already done, so it is not run: `beam-impact` is BEAM_IMPACT_BIN
(a symbolic link on PATH), `target/fmu` is BEAM_IMPACT_FMU_DIR (exported to the blocks, as the set-up
does), `python` is this interpreter,
and `examples/` and `docs/` are copies of the repository's. Output blocks (```text) are not
compared: the numbers in them are abbreviated and may move with the physics.

A failing block fails the test with the block's text and its output.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[2]
TUTORIAL = ROOT / "docs" / "tutorial.md"
FMU_DIR = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", str(ROOT / "target" / "fmu")))
FENCE = re.compile(r"^```([^\n`]*)\n(.*?)^```[ \t]*$", re.MULTILINE | re.DOTALL)
TIMEOUT = 120  # s per block; the whole tutorial takes about 15 s on two cores


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return str(Path(path).resolve())


def blocks(text: str) -> list[tuple[str, str]]:
    """(info string, body) of every fenced block, in order."""
    return [(m.group(1).strip(), m.group(2)) for m in FENCE.finditer(text)]


def runnable(text: str) -> list[tuple[str, str]]:
    """The blocks the test runs: ```sh and ```python, not ```sh setup."""
    return [(info, body) for info, body in blocks(text) if info in ("sh", "python")]


@pytest.fixture(scope="module")
def tutorial(tmp_path_factory):
    """Runs the tutorial's blocks in order in a fresh directory; returns (directory, [(info, body, output)])."""
    assert (FMU_DIR / "fmi2" / "BeamImpact.fmu").exists(), f"no FMU in {FMU_DIR}: run `beam-impact pack` or set BEAM_IMPACT_FMU_DIR"
    work = tmp_path_factory.mktemp("tutorial")
    shutil.copytree(ROOT / "examples", work / "examples")
    shutil.copytree(ROOT / "docs", work / "docs")
    (work / "target").mkdir()
    (work / "target" / "fmu").symlink_to(FMU_DIR.resolve(), target_is_directory=True)
    bin_dir = tmp_path_factory.mktemp("bin")
    (bin_dir / "beam-impact").symlink_to(binary())
    (bin_dir / "python").symlink_to(sys.executable)
    (bin_dir / "python3").symlink_to(sys.executable)
    env = dict(os.environ, PATH=os.pathsep.join([str(bin_dir), os.environ.get("PATH", "")]), MPLBACKEND="Agg",
               BEAM_IMPACT_FMU_DIR=str(FMU_DIR.resolve()))  # the set-up's export: beam_impact.fmu_path() finds them
    ran = []
    for n, (info, body) in enumerate(runnable(TUTORIAL.read_text()), 1):
        if info == "sh":
            args = ["bash", "-euo", "pipefail", "-c", body]
        else:
            args = [sys.executable, "-c", body]
        try:
            done = subprocess.run(args, cwd=work, env=env, capture_output=True, text=True, timeout=TIMEOUT)
            output, code = done.stdout + done.stderr, done.returncode
        except subprocess.TimeoutExpired as e:
            output, code = f"{e.stdout or ''}{e.stderr or ''}\n(timed out after {TIMEOUT} s)", "timeout"
        if code != 0:
            pytest.fail(f"tutorial block {n} (```{info}) failed with exit status {code}:\n{body}\n--- its output:\n{output}",
                        pytrace=False)
        ran.append((info, body, output))
    return work, ran


def test_the_tutorial_has_its_blocks():
    text = TUTORIAL.read_text()
    every = blocks(text)
    # The set-up comes first and is the only block the test does not run.
    assert every[0][0] == "sh setup", every[0]
    assert [info for info, _ in every if info not in ("sh", "python", "text")] == ["sh setup"]
    run = runnable(text)
    assert sum(info == "sh" for info, _ in run) >= 6
    assert sum(info == "python" for info, _ in run) >= 2
    commands = "\n".join(body for info, body in run if info == "sh")
    for sub in ["scenario", "run", "sweep", "verify", "report"]:
        assert re.search(rf"^beam-impact {sub}\b", commands, re.MULTILINE), sub
    assert "fmpy.simulate_fmu" in text


def test_every_block_runs(tutorial):
    _, ran = tutorial
    assert len(ran) == len(runnable(TUTORIAL.read_text()))


def test_the_sweep_has_one_row_per_drop_height(tutorial):
    work, _ = tutorial
    rows = pd.read_csv(work / "sweep.csv")
    assert rows["drop_height"].tolist() == pytest.approx(np.linspace(0.1, 2.0, 5).tolist(), rel=1e-12)
    assert rows["error"].isna().all(), rows["error"].tolist()
    as_json = json.loads((work / "sweep.json").read_text())
    assert [r["drop_height"] for r in as_json] == rows["drop_height"].tolist()
    # What the tutorial says of it: every run trusted, the small drops pass, the 2 m drop fails.
    assert rows["quality.trusted"].all()
    assert rows["design.pass"].iloc[0] and not rows["design.pass"].iloc[-1]
    units = {c["name"]: c["unit"] for c in json.loads((work / "sweep.units.json").read_text())["columns"]}
    assert units["peak.lower.clamp_bending_stress"] == "Pa" and units["drop_height"] == "m"


def test_the_figure_is_written(tutorial):
    work, _ = tutorial
    figure = work / "sweep-stresses.png"
    assert figure.exists()
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert figure.stat().st_size > 10_000


def test_the_worst_case_is_the_one_the_tutorial_goes_on_with(tutorial):
    work, ran = tutorial
    rows = pd.read_csv(work / "sweep.csv")
    utilisation = ["utilisation.lower.clamp_bending_stress", "utilisation.lower.clamp_shear_stress",
                   "utilisation.upper.contact_bending_stress"]
    worst = rows.loc[rows[utilisation].max(axis=1).idxmax(), "drop_height"]
    plotted = [out for info, body, out in ran if info == "python" and "sweep-stresses.png" in body]
    assert plotted and f"worst case: drop_height = {worst:g} m" in plotted[0], plotted
    commands = "\n".join(body for info, body, _ in ran if info == "sh")
    for sub in ["verify", "run"]:
        lines = [line for line in commands.splitlines() if line.startswith(f"beam-impact {sub} ") and "drop_height=" in line]
        assert lines, sub
        for line in lines:
            assert float(re.search(r"drop_height=([0-9.]+)", line).group(1)) == worst, line


def test_verify_and_the_log_leave_their_files(tutorial):
    work, ran = tutorial
    verdicts = json.loads((work / "verify.json").read_text())
    assert all(p["converged"] for p in verdicts["peaks"].values()), verdicts["peaks"]
    assert (work / "worst.mcap").stat().st_size > 0
    assert (work / "worst-figures" / "fig7-bending-stress.png").exists()
    report = [out for info, body, out in ran if info == "sh" and body.startswith("beam-impact report")]
    assert report and "status: complete" in report[0]


def test_the_fmu_gives_the_cli_peaks(tutorial):
    _, ran = tutorial
    fmu = [out for info, body, out in ran if info == "python" and "fmpy.simulate_fmu" in body]
    assert fmu
    pairs = re.findall(r"FMU\s+(\S+)\s+CLI\s+(\S+)", fmu[0])
    assert len(pairs) >= 3, fmu[0]
    for got, want in pairs:
        assert float(got) == pytest.approx(float(want), rel=1e-6), fmu[0]


def test_the_readme_sweep_figure_script_draws_a_cli_sweep(tmp_path):
    """docs/plot_sweep.py (the figure of docs/cli.md) reads the CLI sweep's columns as they are named
    now: a 2 x 2 grid of short runs, drawn to a PNG."""
    rows = tmp_path / "sweep.csv"
    subprocess.run([binary(), "sweep", "--vary", "drop_height=0.3,0.6", "--vary", "damping_ratio=0.02,0.04",
                    "--set", "duration=0.4", "--out", str(rows)], check=True, capture_output=True, timeout=TIMEOUT)
    figure = tmp_path / "sweep.png"
    run = subprocess.run([sys.executable, str(ROOT / "docs" / "plot_sweep.py"), str(rows), str(figure)],
                         capture_output=True, text=True, timeout=TIMEOUT)
    assert run.returncode == 0, run.stderr
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
