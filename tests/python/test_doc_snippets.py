"""The Python snippets of the README and docs/*.md run as written (issue 31: every command a page
shows is run by the tests or marked as not run here).

Goal: every ```python block whose marker, on the line before its fence, is
`<!-- run by tests/python/test_doc_snippets.py -->` runs, unchanged, and succeeds. They run in
one working directory that holds what the pages assume a reader has: `target/fmu` (the packed
FMUs, BEAM_IMPACT_FMU_DIR), `paper.mcap` (a log of the paper scenario: here 50 ms of it, so the
snippet that prints every step stays short) and `steps.csv` (`beam-impact report paper.mcap --csv
steps.csv`). tests/docs.rs checks that every other command block is marked as run elsewhere or
not run here.

A failing snippet fails its test with the page, the line, the block and its output.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FMU_DIR = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", str(ROOT / "target" / "fmu")))
MARKER = "<!-- run by tests/python/test_doc_snippets.py -->"
TIMEOUT = 300  # s per snippet; together they take about 10 s on two cores


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return str(Path(path).resolve())


def marked_snippets() -> list[tuple[str, int, str]]:
    """(page, line of the fence, body) of every block marked for this file, README first."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    out = []
    for page in pages:
        lines = page.read_text().splitlines()
        for n, line in enumerate(lines):
            if line.strip() != MARKER:
                continue
            fence = lines[n + 1]
            assert fence.strip().startswith("```"), f"{page.name}:{n + 1}: the marker is not right before a fence"
            assert fence.strip() == "```python", f"{page.name}:{n + 2}: this file runs ```python blocks, not {fence!r}"
            indent = len(fence) - len(fence.lstrip())
            end = next(i for i in range(n + 2, len(lines)) if lines[i].strip().startswith("```"))
            body = "\n".join(line[indent:] for line in lines[n + 2:end])
            out.append((str(page.relative_to(ROOT)), n + 2, body))
    return out


SNIPPETS = marked_snippets()


def test_the_pages_mark_their_snippets_for_this_file():
    pages = {page for page, _, _ in SNIPPETS}
    assert {"README.md", "docs/fmu.md", "docs/logs.md", "docs/python-reference.md"} <= pages, pages
    assert len(SNIPPETS) >= 6, SNIPPETS


def make_inputs(work: Path, command: str, env: dict | None = None) -> None:
    """What the pages assume a reader has made with `beam-impact` (`command`), in `work`: a short
    paper log `paper.mcap` and its CSV `steps.csv` (tests/python/test_wheel.py makes them with the
    wheel's command)."""
    for args in (["run", "--set", "duration=0.05", "--mcap", "paper.mcap"],
                 ["report", "paper.mcap", "--csv", "steps.csv", "--out", "paper-figures"]):
        done = subprocess.run([command, *args], cwd=work, env=env, capture_output=True, text=True, timeout=TIMEOUT)
        assert done.returncode == 0, done.stderr


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    """The folder the snippets run in, with the FMUs, a short paper log and its CSV."""
    assert (FMU_DIR / "fmi2" / "BeamImpact.fmu").exists(), f"no FMU in {FMU_DIR}: run `beam-impact pack` or set BEAM_IMPACT_FMU_DIR"
    work = tmp_path_factory.mktemp("snippets")
    (work / "target").mkdir()
    (work / "target" / "fmu").symlink_to(FMU_DIR.resolve(), target_is_directory=True)
    make_inputs(work, binary())
    return work


@pytest.mark.parametrize("page,line,body", SNIPPETS, ids=[f"{p}:{n}" for p, n, _ in SNIPPETS])
def test_the_snippet_runs_as_written(work, page, line, body):
    # fmu_path(): the suite's FMUs, those of target/fmu.
    env = dict(os.environ, MPLBACKEND="Agg", BEAM_IMPACT_FMU_DIR=str(FMU_DIR.resolve()))
    done = subprocess.run([sys.executable, "-c", body], cwd=work, env=env, capture_output=True, text=True,
                          timeout=TIMEOUT)
    output = done.stdout + done.stderr
    if done.returncode != 0:
        pytest.fail(f"{page}:{line} failed with exit status {done.returncode}:\n{body}\n--- its output:\n{output[-3000:]}",
                    pytrace=False)
