"""Issue 44 item 2: load cases from Python. `beam_impact.run` returns the `load_cases` block of
`run --json` (the same Rust code), `design.pass` is every case's verdict, a bad case raises the
CLI's one-line ScenarioError before anything runs, and `load_log` replays the cases the run
stored in its log's `answer.json`.

Tolerances: none. Both sides are the same Rust numbers, compared for equality.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import beam_impact

ROOT = Path(__file__).resolve().parents[2]


def cases_text() -> str:
    return "duration = 0.6\n" + (ROOT / "examples" / "load-cases.toml").read_text()


def test_run_returns_the_cases_and_load_log_replays_them(tmp_path):
    log = tmp_path / "cases.mcap"
    result = beam_impact.run(cases_text(), log=log, check_sensitivity=False)
    cases = result["load_cases"]
    assert [c["name"] for c in cases["cases"]] == ["operating", "operating-factored", "emergency"]
    assert result["design"]["pass"] == cases["pass"]
    for quantity, governing in cases["governing"].items():
        largest = max(c["quantities"][quantity]["utilisation"] for c in cases["cases"] if quantity in c["quantities"])
        assert governing["utilisation"] == largest, quantity
    stored = beam_impact.load_log(log).answer
    assert stored["load_cases"] == cases
    assert stored["design"]["pass"] == cases["pass"]


def test_a_bad_case_is_a_one_line_scenario_error():
    text = "duration = 0.2\n[[load_cases]]\nname = \"a\"\nset = { no_such_field = 1 }\n"
    with pytest.raises(ValueError) as e:
        beam_impact.run(text)
    message = str(e.value)
    assert "load case \"a\"" in message and "no_such_field" in message, message
    assert "\n" not in message.strip()
