"""The Python package's files under the CLI's rules (issue 27, items 3 and 8, and the replay of a
run with moving supports from its log alone).

Before: `simulate(fmu, log_path=fmu)` wrote the log over the FMU; `python -m beam_impact sweep
--out <the FMU>` replaced it; `--out X --json X` kept one of the two silently;
`log_path="results.csv\\0.mcap"` overwrote results.csv (cut at the NUL); `simulate('/dev/zero')`
read until the interpreter was killed and a FIFO as the FMU blocked forever; `parse_vary` took
`1_0` and Arabic-Indic digits that `beam-impact sweep --vary` refuses; a log of a run with moving
supports held no motion table for Python.

Goal: every file the package writes goes through the native module's guard (the library's
`record::output`: no NUL, symbolic link, folder, FIFO, socket or device other than /dev/null,
never an input or another output of the call by device and inode, written beside and renamed),
refused before the FMU is loaded or any scenario runs, the earlier file untouched; an FMU is
opened only if it is a regular file of at most 1 GiB, refused within seconds otherwise (run in a
child process with a timeout, so a hang fails the test instead of stalling it); `parse_vary` is
the CLI's parser, so both accept and refuse the same strings with the same message; `load_log`
of a vessel run's log gives the motion table of `examples/vessel-motion.csv`, bit for bit, with
the motion file gone.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

import beam_impact

ROOT = Path(__file__).resolve().parents[2]
FMU_DIR = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", str(ROOT / "target" / "fmu")))
#: Seconds a refusal may take (it takes milliseconds; a hang or a read of /dev/zero takes forever).
PROMPT = 60


def fmu_path(version: str = "fmi2") -> Path:
    path = FMU_DIR / version / "BeamImpact.fmu"
    assert path.exists(), f"{path} not found: run `beam-impact pack` or set BEAM_IMPACT_FMU_DIR"
    return path


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


@pytest.fixture
def fmu_copy(tmp_path) -> Path:
    """A copy of the FMU that a test may lose."""
    copy = tmp_path / "BeamImpact.fmu"
    shutil.copyfile(fmu_path(), copy)
    return copy


def python_sweep(*args, cwd=None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "beam_impact", "sweep", "--vary", "drop_height=0.5",
                           "--stop-time", "0.01", *map(str, args)], capture_output=True, text=True, timeout=300,
                          cwd=cwd)


def in_child(code: str) -> subprocess.CompletedProcess:
    """`code` in a fresh interpreter, killed (a test failure) if it runs longer than PROMPT s."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=PROMPT)


# ------------------------------------------------------------------------------------------------
# simulate's log_path


def test_log_path_naming_the_fmu_is_refused_before_the_fmu_is_loaded(fmu_copy, tmp_path, monkeypatch):
    before = fmu_copy.read_bytes()
    monkeypatch.chdir(tmp_path)
    hard_link = tmp_path / "run.mcap"
    os.link(fmu_copy, hard_link)
    # By device and inode, not by name: the path itself, another spelling, a hard link.
    for log_path in [fmu_copy, "./BeamImpact.fmu", hard_link]:
        with pytest.raises(ValueError, match=r"the FMU and log_path name the same file"):
            beam_impact.simulate(str(fmu_copy), {"duration": 0.01}, log_path=str(log_path))
    assert fmu_copy.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["BeamImpact.fmu", "run.mcap"], "no partial file left"


def test_a_nul_in_log_path_is_refused_not_cut(tmp_path):
    results = tmp_path / "results.csv"
    results.write_text("a,b\n1,2\n")
    with pytest.raises(ValueError, match=r"log_path .*results\.csv\\u\{0\}\.mcap: a path holding a NUL character"):
        beam_impact.simulate(str(fmu_path()), {"duration": 0.01}, log_path=f"{results}\0.mcap")
    assert results.read_text() == "a,b\n1,2\n"
    assert [p.name for p in tmp_path.iterdir()] == ["results.csv"]


def test_a_link_folder_fifo_or_device_as_log_path_is_refused(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    link = tmp_path / "link.mcap"
    link.symlink_to(victim)
    fifo = tmp_path / "fifo.mcap"
    os.mkfifo(fifo)
    cases = {link: "symbolic link", fifo: "FIFO", tmp_path: "folder", "/dev/null": "device", "/dev/zero": "device"}
    started = time.monotonic()
    for log_path, kind in cases.items():
        with pytest.raises(ValueError, match=f"cannot create log_path .*{kind}"):
            beam_impact.simulate(str(fmu_path()), {"duration": 0.01}, log_path=str(log_path))
    assert time.monotonic() - started < PROMPT
    assert victim.read_text() == "keep me"


# ------------------------------------------------------------------------------------------------
# python -m beam_impact sweep --out / --json


def test_sweep_out_naming_the_fmu_is_refused(fmu_copy):
    before = fmu_copy.read_bytes()
    for option in ["--out", "--json"]:
        others = ["--out", fmu_copy.parent / "rows.csv"] if option == "--json" else []
        done = python_sweep("--fmu", fmu_copy, *others, option, fmu_copy)
        assert done.returncode == 2, done
        assert f"--fmu and {option} name the same file" in done.stderr, done.stderr
        assert "sweep:" not in done.stdout, "refused before any scenario ran"
    assert fmu_copy.read_bytes() == before


def test_sweep_out_and_json_naming_one_file_are_refused(tmp_path):
    (tmp_path / "kept.csv").write_text("earlier rows\n")
    for out, other in [("rows.csv", "rows.csv"), ("rows.csv", "./rows.csv"), ("kept.csv", "kept.csv")]:
        done = python_sweep("--fmu", fmu_path(), "--out", out, "--json", other, cwd=tmp_path)
        assert done.returncode == 2 and "--out and --json name the same file" in done.stderr, done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kept.csv"]
    assert (tmp_path / "kept.csv").read_text() == "earlier rows\n"


def test_sweep_outputs_are_written_beside_and_renamed_never_through_a_link(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    link = tmp_path / "link.csv"
    link.symlink_to(victim)
    done = python_sweep("--fmu", fmu_path(), "--out", link)
    assert done.returncode == 2 and "cannot create --out" in done.stderr and "symbolic link" in done.stderr, done
    done = python_sweep("--fmu", fmu_path(), "--out", tmp_path / "rows.csv", "--json", link)
    assert done.returncode == 2 and "cannot create --json" in done.stderr and "symbolic link" in done.stderr, done
    assert victim.read_text() == "keep me" and link.is_symlink()
    # Written: the earlier file replaced whole, no NAME.partial left, /dev/null taken as the CLI takes it.
    (tmp_path / "rows.csv").write_text("earlier rows\n")
    done = python_sweep("--fmu", fmu_path(), "--out", tmp_path / "rows.csv", "--json", tmp_path / "rows.json")
    assert done.returncode == 0, done.stderr
    rows = pd.read_csv(tmp_path / "rows.csv")
    assert rows["drop_height"].tolist() == [0.5] and rows["error"].isna().all()
    assert json.loads((tmp_path / "rows.json").read_text())[0]["drop_height"] == 0.5
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.csv", "rows.csv", "rows.json", "victim.txt"]
    assert python_sweep("--fmu", fmu_path(), "--out", os.devnull).returncode == 0


# ------------------------------------------------------------------------------------------------
# The FMU: a regular file under 1 GiB, or refused at once


@pytest.mark.parametrize("call", [
    "beam_impact.simulate(PATH)",
    "beam_impact.FmuFile.read(PATH)",
    "beam_impact.sweep({'drop_height': [0.5]}, fmu=PATH)",
])
def test_an_fmu_that_is_not_a_regular_file_fails_at_once(call, tmp_path):
    fifo = tmp_path / "model.fmu"
    os.mkfifo(fifo)
    for path, message in [("/dev/zero", "device"), (fifo, "FIFO"), (tmp_path, "directory")]:
        started = time.monotonic()
        done = in_child(f"import beam_impact\nPATH = {str(path)!r}\n"
                        f"try:\n    {call}\nexcept ValueError as e:\n    print(e)\nelse:\n    print('accepted')")
        assert done.returncode == 0 and done.stdout.startswith(f"cannot read FMU {path}: "), done
        assert message in done.stdout and time.monotonic() - started < PROMPT


def test_an_fmu_over_1_gib_is_refused_before_it_is_read(tmp_path):
    sparse = tmp_path / "huge.fmu"
    with open(sparse, "wb") as f:
        f.truncate(beam_impact._native.MAX_FMU_BYTES + 1)  # sparse: costs no disk
    assert beam_impact._native.MAX_FMU_BYTES == 1 << 30
    done = in_child(f"import beam_impact\ntry:\n    beam_impact.simulate({str(sparse)!r})\n"
                    "except ValueError as e:\n    print(e)")
    assert "the FMU is 1073741825 bytes, larger than 1073741824 bytes (the limit)" in done.stdout, done


def test_python_sweep_with_a_fifo_as_the_fmu_exits_at_once(tmp_path):
    fifo = tmp_path / "model.fmu"
    os.mkfifo(fifo)
    done = subprocess.run([sys.executable, "-m", "beam_impact", "sweep", "--fmu", str(fifo), "--vary",
                           "drop_height=0.5", "--out", str(tmp_path / "rows.csv")], capture_output=True, text=True,
                          timeout=PROMPT)
    assert done.returncode == 2 and "FIFO" in done.stderr and done.stderr.count("\n") == 1, done.stderr


# ------------------------------------------------------------------------------------------------
# parse_vary is the CLI's parser

#: Strings the CLI refuses that Python's former parser accepted (Python's float()).
FORMERLY_ACCEPTED = [
    "drop_height=1_0",
    "damping_ratio=\u0660.\u0660\u0663",  # Arabic-Indic digits
    "drop_height=\uff11",  # a fullwidth digit
    "lower.elements=\u0663",
    "drop_height=\x1c1",  # a separator Python's strip() takes for white space, Rust's trim() does not
    "drop_height=1:2:1_0",
    "upper.lenght=1",  # an unknown field, refused by the CLI at once (Python's sweep refused it later)
]
#: Other strings, accepted or refused: both sides must agree.
OTHERS = [
    "drop_height=0.5", "drop_height=0.1:2:7", "drop_height= 1e-1 ", "drop_height=+.5", "drop_height=5.",
    "drop_height=1E2", "drop_height=inf", "drop_height=NaN", "drop_height=infinity", "drop_height=\u00a00.5",
    "step_free=auto,2e-5", "method=paper,converged", "lower.elements=4:8:9", "lower.elements=auto,7",
    "stress_recovery=mean,right", "motion.time_shift=0:8.25:12", "upper.tip_force=1e3", "duration=0.5",
    "drop_height=0x10", "drop_height=1,", "drop_height=", "drop_height=1:2", "drop_height=1:2:0",
    "drop_height=0.1:0.5:100000000", "=1", "drop_height", "method=fast", "step_free=Auto", "drop_height=1 000",
    "drop_height=1e", "lower.elements=inf", "drop_height=0.1:0.5:18446744073709551616",
]


def cli_verdict(texts: list[str], folder: Path) -> str | None:
    """None if `beam-impact sweep --vary ...` accepts `texts`, else its one-line message. An accepted
    grid stops at the same-file check of --out and --json, so nothing runs."""
    args = [binary(), "sweep", "--out", "same.csv", "--json", "same.csv"]
    for t in texts:
        args += ["--vary", t]
    done = subprocess.run(args, capture_output=True, text=True, timeout=PROMPT, cwd=folder)
    assert done.returncode == 2, done
    if "--out and --json name the same file" in done.stderr:
        return None
    return done.stderr.strip().removeprefix("beam-impact: ")


def python_verdict(texts: list[str]) -> str | None:
    try:
        beam_impact.parse_vary(texts)
    except ValueError as e:
        return str(e)
    return None


@pytest.mark.parametrize("texts", [[t] for t in FORMERLY_ACCEPTED + OTHERS]
                         + [["drop_height=1", "drop_height=2"], ["drop_height=1", " drop_height =2"]])
def test_parse_vary_accepts_exactly_what_the_cli_accepts(texts, tmp_path):
    cli = cli_verdict(texts, tmp_path)
    assert python_verdict(texts) == cli
    if texts[0] in FORMERLY_ACCEPTED:
        assert cli is not None, f"the CLI accepts {texts}"


def test_parse_spec_and_parse_value_read_numbers_as_the_cli():
    assert beam_impact.parse_spec("drop_height", "0.2:1:3") == [0.2, 0.6, 1.0]
    with pytest.raises(ValueError, match="drop_height takes a number in m, got `1_0`"):
        beam_impact.parse_spec("drop_height", "1_0")
    with pytest.raises(ValueError, match="takes a number"):
        beam_impact.expand({"damping_ratio": ["\u0660.\u0660\u0663"]})
    with pytest.raises(ValueError, match="takes a number"):
        beam_impact.simulate(str(fmu_path()), {"drop_height": "1_0"})
    assert beam_impact.expand({"lower.elements": ["auto", " 7 "]}) == [{"lower.elements": 0.0}, {"lower.elements": 7.0}]


# ------------------------------------------------------------------------------------------------
# load_log replays a run with moving supports from its log alone


def test_load_log_gives_the_motion_table_of_a_vessel_run_from_its_log_alone(tmp_path):
    for name in ["vessel.toml", "vessel-motion.csv"]:
        shutil.copyfile(ROOT / "examples" / name, tmp_path / name)
    done = subprocess.run([binary(), "run", "vessel.toml", "--mcap", "vessel.mcap"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    (tmp_path / "vessel-motion.csv").unlink()  # the log alone: the motion file is gone
    log = beam_impact.load_log(tmp_path / "vessel.mcap")
    assert isinstance(log.motion_csv, str) and log.motion_csv.startswith("time,upper.hinge_heave,")
    lines = [line for line in (ROOT / "examples" / "vessel-motion.csv").read_text().splitlines()
             if line and not line.startswith("#")]
    header, rows = lines[0].split(","), [[float(v) for v in line.split(",")] for line in lines[1:]]
    assert list(log.motion.columns) == header
    assert log.motion.shape == (1201, 10) == (len(rows), len(header))
    assert log.motion.to_numpy().tolist() == rows, "the rows, bit for bit"


def test_a_log_without_moving_supports_has_no_motion_table():
    log = beam_impact.load_log(ROOT / "tests" / "corpus" / "logs" / "real-2ms.mcap")
    assert log.motion_csv is None and log.motion is None


def test_a_motion_table_the_parser_refuses_raises_log_error():
    log = beam_impact.load_log(ROOT / "tests" / "corpus" / "logs" / "real-2ms.mcap")
    log.motion_csv = "time,upper.hinge_heave,upper.hinge_heave_velocity,upper.hinge_heave_acceleration\n0,\x1b[31m,0,0\n"
    with pytest.raises(beam_impact.LogError, match=r"motion table \(motion.csv\) is refused: .*\\u\{1b\}") as error:
        log.motion
    assert "\n" not in str(error.value) and "\x1b" not in str(error.value)
