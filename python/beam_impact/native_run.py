"""`beam_impact.run`: one scenario through the Rust solver itself (the native module), no FMU.

The run is `beam-impact run`'s, the same code: the scenario read as the CLI reads it, the answer
with its checks (the printed run, the next coarser rungs, the reproducibility twin), the design
check, the MCAP log with `answer.json` attached when asked; the result holds the very keys of
`beam-impact run --json`. While the solver runs the GIL is released (other Python threads run,
a sweep's threads solve in parallel), and Ctrl-C stops it between two steps with
KeyboardInterrupt.

Fields are the scenario's dotted names (`beam-impact scenario` lists them). Python keywords hold
no dots, so a dot is written as a double underscore (`lower__damping_ratio=0.02`), or the names
go in a dict (`fields={"lower.damping_ratio": 0.02}`); both may be given (a name twice is refused).
"""

from __future__ import annotations

import errno
import json
import math
import os
import warnings as _warnings
from typing import Any



class RunResult(dict):
    """The `beam-impact run --json` document of one run (the same keys: `scenario`,
    `scenario_as_given`, `summary`, `quality`, `design`, `discretisation`, `impact`,
    `merged_contact_windows`, `units`, `wall_time_s`, `dynamic_amplification`), with shortcuts:

    - `peaks`, `peak_times`: `summary.peaks` / `summary.peak_times` by the FMU's names, one per
      quantity (the document also holds the former names until 0.2.0); SI
    - `converged_peaks`: `summary.converged_peaks`, the same way
    - `quality`, `trusted`, `reasons`: the checks, the verdict and why not trusted (lines)
    - `design`: the design check (`pass`, `utilisation`)
    - `series`: the steps as a pandas.DataFrame (`run(..., series=True)`; the columns of
      `load_log(...).dataframe()`), else None
    - `log_path`: the log written (None without `log=`), `warnings`: the lines the CLI prints as
      warnings (`results not trusted: ...` per reason, motion rows, a log cut short), each also
      given to Python's `warnings.warn` (RuntimeWarning)
    """

    series: Any = None
    log_path: str | None = None
    warnings: tuple = ()

    @staticmethod
    def _one_name_each(values: dict) -> dict:
        """The FMU's dotted names only: the document keeps each former name (`contact_force`)
        beside its dotted one until 0.2.0, a shortcut gives one name per quantity (issue 41)."""
        return {k: v for k, v in values.items() if "." in k}

    @property
    def peaks(self) -> dict:
        return self._one_name_each(self["summary"]["peaks"])

    @property
    def peak_times(self) -> dict:
        return self._one_name_each(self["summary"]["peak_times"])

    @property
    def converged_peaks(self) -> dict:
        return self._one_name_each(self["summary"]["converged_peaks"])

    @property
    def quality(self) -> dict:
        return self["quality"]

    @property
    def trusted(self) -> bool:
        return bool(self["quality"]["trusted"])

    @property
    def reasons(self) -> list:
        return list(self["quality"]["reasons"])

    @property
    def design(self) -> dict:
        return self["design"]

    #: The converged peaks a short repr shows: (key, label, scale, unit).
    SHOWN = (("lower.tip_deflection", "w_a", 1.0, "m"), ("lower.clamp_bending_stress", "sigma_a", 1e-6, "MPa"),
             ("lower.clamp_shear_stress", "tau_a", 1e-6, "MPa"),
             ("upper.contact_bending_stress", "sigma_b", 1e-6, "MPa"), ("contact.force", "F_c", 1e-3, "kN"))

    def _shown(self) -> list:
        peaks = self.get("summary", {}).get("converged_peaks", {})
        return [(label, peaks[key] * scale, unit) for key, label, scale, unit in self.SHOWN
                if isinstance(peaks.get(key), (int, float))]

    def __repr__(self) -> str:
        """One line (the whole document is the dict's, `dict(result)`): the verdicts and the five
        converged peaks. Echoing a result in a notebook printed 34 KB."""
        verdict = "trusted" if self.get("quality", {}).get("trusted") else "NOT TRUSTED"
        design = "PASS" if self.get("design", {}).get("pass") else "FAIL"
        peaks = ", ".join(f"{label} {value:.4g} {unit}" for label, value, unit in self._shown())
        return f"<RunResult {verdict}, design {design}: {peaks}; {len(self)} keys>"

    def _repr_html_(self) -> str:
        """A notebook's view: the verdicts and the converged peaks as a small table."""
        from html import escape

        rows = "".join(f"<tr><td>{escape(label)}</td><td>{value:.6g}</td><td>{escape(unit)}</td></tr>"
                       for label, value, unit in self._shown())
        verdict = "trusted" if self.get("quality", {}).get("trusted") else "NOT TRUSTED"
        design = "PASS" if self.get("design", {}).get("pass") else "FAIL"
        reasons = "".join(f"<li>{escape(r)}</li>" for r in self.get("quality", {}).get("reasons", []))
        return (f"<div><b>RunResult</b>: {verdict}, design {design}"
                f"<table><tr><th>converged peak</th><th>value</th><th>unit</th></tr>{rows}</table>"
                + (f"<ul>{reasons}</ul>" if reasons else "") + "</div>")


def field_pairs(fields: dict | None, keywords: dict) -> list:
    """(dotted name, value) pairs of a `fields` dict and `name__part=value` keywords; ValueError
    for a name given twice or a value that is neither a number nor text."""
    pairs: dict[str, Any] = dict(fields or {})
    for key, value in keywords.items():
        name = key.replace("__", ".")
        if name in pairs:
            raise ValueError(f"{name} is given twice (as a field and as the keyword {key})")
        pairs[name] = value
    out = []
    for name, value in pairs.items():
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise ValueError(f"{name} takes a number or text, got {value!r}")
        out.append((str(name), float(value) if isinstance(value, (int, float)) else value))
    return out


def scenario_source(scenario: Any) -> tuple:
    """(path, text) of `scenario`: a path (os.PathLike, or text with neither a line break nor `=`),
    else TOML text; (None, None) for None."""
    if scenario is None:
        return None, None
    if isinstance(scenario, (bytes, os.PathLike)):
        return os.fsdecode(os.fspath(scenario)), None
    if isinstance(scenario, str):
        if "\n" in scenario or "=" in scenario or not scenario.strip():
            return None, scenario
        return scenario, None
    raise ValueError(f"scenario takes a file path or TOML text, got {type(scenario).__name__}")


#: Largest `series_every`: the native module takes it as a 64-bit unsigned count.
MAX_SERIES_EVERY = 2**64 - 1


def series_every_of(value: Any) -> int:
    """`series_every` as a whole number from 1 to MAX_SERIES_EVERY; ValueError in one line naming
    it, its bounds and the value otherwise (2**80 raised OverflowError in the native module)."""
    try:
        every = None if isinstance(value, bool) else int(value)
    except (TypeError, ValueError, OverflowError):  # "x", None, inf, nan
        every = None
    if every is None or not 1 <= every <= MAX_SERIES_EVERY:
        shown = f"a whole number of {value.bit_length()} bits" if isinstance(value, int) and value.bit_length() > 128 \
            else repr(value)[:100]
        raise ValueError(f"series_every must be a whole number from 1 to {MAX_SERIES_EVERY} (2**64 - 1), got {shown}")
    return every


def run(scenario: Any = None, *, fields: dict | None = None, log: "str | os.PathLike | None" = None,
        log_sample_interval: float = 1e-4, log_channels: "str | None" = None, series: bool = False,
        series_every: int = 1, max_steps: int | None = None, check_sensitivity: bool = True,
        **field_keywords: Any) -> RunResult:
    """Runs one scenario as `beam-impact run` does and returns its `RunResult` (the `run --json`
    document).

    `scenario`: None (the paper's scenario and method, what a bare `beam-impact run` runs; with
    fields, the defaults, as `beam-impact run --set`), a scenario file's path (`pathlib.Path`, or
    text without a line break or `=`), or the TOML text itself (a motion file it names is read
    relative to the current folder). `fields` / keywords: the dotted fields to change, as `--set`
    (numbers, or text read by the CLI's parser: `"auto"`, `"mean"`, `"converged"`).
    `log`: write the MCAP log there, through the CLI's output guard (default: none).
    `log_sample_interval`: the log's dense output, s (`run --log-sample-interval`): the exact
    state every this much simulated time and wherever a peak is reached, so that the log's
    largest values are the printed peaks; 0: every internal step instead; 1e-6 to 1 s.
    `log_channels`: its topics, as `beam-impact run --log-channels` (default all): a comma list of
    model, step, contact, log (always written), modes, scene, stations, or a list of those names;
    `"step"` writes the smallest log that `load_log` reads (docs/logs.md says what each adds).
    `series`: keep every `series_every`-th step (and the last) and return them as
    `result.series`, a pandas.DataFrame (a converged run takes 1e5 to 1e6 steps of about 250
    bytes each). `max_steps`: refuse a run needing more internal steps (default the CLI's 1e8).
    `check_sensitivity`: run the reproducibility twin (as the CLI does; False halves the stepping
    of the checks and leaves `sensitivity_spread` null).

    ScenarioError (a ValueError) with the CLI's one-line message for a scenario, field, value, path
    or step count it refuses, before anything runs; FileNotFoundError for a scenario file that does
    not exist; KeyboardInterrupt on Ctrl-C (the run stops between steps; its
    log then ends at that step, without the answer: `load_log(...).answer` is None);
    SimulationError when the run fails."""
    from . import _native
    from .fmu import ScenarioError, SimulationError

    path, text = scenario_source(scenario)
    if path is not None and not os.path.lexists(path):
        # repr: a path's control characters (a terminal's escape sequences) shown, not sent.
        raise FileNotFoundError(errno.ENOENT, f"cannot read scenario {os.fsdecode(path)!r}: no such file", path)
    pairs = field_pairs(fields, field_keywords)
    limit = _native.MAX_STEPS if max_steps is None else max_steps
    if isinstance(limit, bool) or not isinstance(limit, int) or not 0 < limit < 2**64:
        raise ScenarioError(f"max_steps must be a whole number > 0, got {max_steps!r}")
    every = series_every_of(series_every)
    if isinstance(log_sample_interval, bool) or not isinstance(log_sample_interval, (int, float)) \
            or not math.isfinite(log_sample_interval):
        raise ScenarioError(f"log_sample_interval must be a number of seconds, got {log_sample_interval!r}")
    log_text = None if log is None else os.fsdecode(os.fspath(log))
    if log_channels is not None and not isinstance(log_channels, str):
        if not isinstance(log_channels, (list, tuple)) or not all(isinstance(c, str) for c in log_channels):
            raise ScenarioError(f"log_channels must be a comma list or a list of topic names, got {log_channels!r:.100}")
        log_channels = ",".join(log_channels)
    try:
        doc, steps, warnings, log_path = _native.run(
            scenario=path, scenario_text=text, fields=pairs, log=log_text, series_every=every if series else 0,
            max_steps=limit, sensitivity=bool(check_sensitivity), observed_order=True,
            log_sample_interval=float(log_sample_interval), log_channels=log_channels)
    except ValueError as e:
        # The crate's line names the CLI's option; here it is this function's keyword.
        raise ScenarioError(str(e).replace("with --max-steps", "with run(..., max_steps=N)")) from None
    except RuntimeError as e:
        raise SimulationError(str(e)) from None
    result = RunResult(json.loads(doc))
    result.warnings = list(warnings)
    # What the CLI prints as a warning: motion rows, a log cut short, each reason a run is not
    # trusted ("results not trusted: ...").
    for line in result.warnings:
        _warnings.warn(line, RuntimeWarning, stacklevel=2)
    result.log_path = log_path
    if steps is not None:
        import pandas as pd

        from .log import step_columns

        result.series = pd.DataFrame(step_columns(steps))
    return result
