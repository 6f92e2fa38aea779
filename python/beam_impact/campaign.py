"""`beam_impact.campaign`: `beam-impact campaign` from Python (issue 43), on threads or a Dask
cluster.

The plan (which records, which instants, which sea states), every event's run and the statistics
are the crate's, the CLI's own code (the native module's `Campaign`); Python only moves the rows.
Each event is a loss of the gangway's support at an instant of a sea-state record; its row holds
the CLI's CSV columns in their order (`seed`, `instant`, the supports' motion at the instant, the
peaks as a sweep names them, utilisations, `design.pass`, `quality.trusted`, ...).

Where the events run:
- `client=None`: the crate's own pool of `jobs` threads (default: one per core), the GIL
  released, the rows in the plan's order, exactly the rows `beam-impact campaign --jobs N`
  writes (but `wall_time`), whatever the number of threads. A tqdm bar on standard error.
- a `dask.distributed.Client` (or a scheduler address): one task per event. The scenario file
  and its RAO file are read here and their texts scattered once to every worker, which builds
  the same campaign from them (once per process) and runs its events natively: workers need the
  `beam_impact` package but no shared file system. The plan and the statistics stay here.
Either way the same rows, to the bit: each event's run depends on its scenario only.

Ctrl-C stops the campaign and keeps the rows done: `CampaignInterrupted` (a KeyboardInterrupt)
carries the result of those rows as `.result` (threads: every row before the first not run, as
the CLI writes them; a cluster: every event finished).
"""

from __future__ import annotations

import hashlib
import json
import math
import numbers
import os
import sys
import threading
import uuid
from typing import Any, Iterable

#: Dask key prefix of the campaign's tasks.
TASK_PREFIX = "beam_impact-event"

#: Seconds before the bar shows: a campaign shorter than this prints none.
BAR_DELAY = 2.0


class CampaignInterrupted(KeyboardInterrupt):
    """Ctrl-C stopped a campaign: `.result` is the `CampaignResult` of the rows done."""

    def __init__(self, result: "CampaignResult"):
        super().__init__(f"interrupted: {len(result.rows)} of {result.planned} events run (the rows and "
                         f"statistics in .result are of them)")
        self.result = result


class CampaignResult:
    """A campaign's rows and statistics, as `beam-impact campaign` writes and prints them.

    - `rows`: pandas.DataFrame, one row per event run in the plan's order, the columns of the
      CLI's `--out` CSV in its order (an empty cell of the CLI is NaN; `error` is "" when fine)
    - `summary`: the CLI's `--json` document (dict): the settings and methods, per cell the
      overload probability with its Clopper-Pearson interval and per quantity the Gumbel fit of
      the records' maxima, the exceedance and the most probable maximum; the operability limits
    - `table`: the operability table (text), `text`: the summary the CLI prints (each cell's,
      then the table when the grid has more than one cell)
    - `units`: {column: unit}, `interrupted`: whether Ctrl-C stopped it, `planned`: events planned
    - `figures(folder)`: writes the operability figures (SVG and PNG per heading) as
      `--figures` does; returns their paths
    """

    def __init__(self, native, rows, outcomes, interrupted: bool, note: str):
        import pandas as pd

        self._native = native
        self._outcomes = outcomes
        self._note = note
        columns = native.columns()
        self.rows = pd.DataFrame(rows, columns=columns)
        self.units = dict(native.column_units())
        self.interrupted = interrupted
        self.planned = len(native)
        document, self.text, self.table = native.summarise(outcomes)
        self.summary = json.loads(document)

    def figures(self, folder: "str | os.PathLike") -> list[str]:
        """Writes the operability figures into `folder` (created if missing): one SVG and one PNG
        per heading, Hs against Tp with the limit line and each cell's probability."""
        return self._native.figures(self._outcomes, os.fspath(folder), self._note)

    def __repr__(self) -> str:
        return f"<CampaignResult: {len(self.rows)} of {self.planned} events>\n{self.text}"


def _texts(name: str, spec: Any) -> list[str]:
    """`set` / `vary` as the CLI's `--set` / `--vary` texts: a dict {field: value or values}
    (numbers written as the shortest decimal giving the same float, text as given: `1:3:5`), or
    texts already (`"sea.peak_period=6,8"`)."""
    if spec is None:
        return []
    if isinstance(spec, str):
        return [spec]
    if isinstance(spec, dict):
        out = []
        for field, value in spec.items():
            if isinstance(value, str):
                out.append(f"{field}={value}")
            elif isinstance(value, Iterable):
                out.append(f"{field}={','.join(_number(name, field, v) for v in value)}")
            else:
                out.append(f"{field}={_number(name, field, value)}")
        return out
    return [str(t) for t in spec]


def _number(name: str, field: str, value: Any) -> str:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        if isinstance(value, str):
            return value
        raise ValueError(f"{name}: {field} takes numbers, got {value!r}"[:300])
    return repr(float(value))


#: The campaigns a process built, by their key (a cluster's worker builds each once).
_BUILT: dict = {}
_BUILT_LOCK = threading.Lock()


def _native_campaign(spec: dict):
    """The native campaign of `spec` (built once per process and key)."""
    from . import _native

    with _BUILT_LOCK:
        built = _BUILT.get(spec["key"])
        if built is None:
            built = _native.Campaign(**spec["arguments"])
            _BUILT.clear()  # one campaign at a time is enough for a worker
            _BUILT[spec["key"]] = built
        return built


def _run_event(index: int, spec: dict):
    """A cluster's task: event `index` of the campaign of `spec`, run natively in the worker."""
    return _native_campaign(spec).run_event(index)


def _bar(total: int):
    from tqdm import tqdm

    return tqdm(total=total, unit="event", desc="campaign", file=sys.stderr, delay=BAR_DELAY, dynamic_ncols=True)


def campaign(
    scenario: Any,
    *,
    events: int = 1000,
    seeds: int | None = None,
    record_length: float = 10800.0,
    vary: Any = None,
    set: Any = None,  # noqa: A002 (the CLI's --set)
    target: float = 0.01,
    confidence: float = 0.95,
    exposure: float | None = None,
    on_estimate: bool = False,
    jobs: int | None = None,
    client: Any = None,
    max_events: int | None = None,
    max_steps: int | None = None,
    progress: bool | None = True,
    fatigue: bool = False,
    occurrence: "str | os.PathLike | None" = None,
) -> CampaignResult:
    """`beam-impact campaign SCENARIO --events N --seeds S ...`: `events` losses of the support
    at instants drawn across `seeds` records (default 20, or `events` if fewer) of `record_length` s
    of the scenario's sea state (it
    must have a `[sea]`), for each cell of the grid `vary` (sea states only:
    `sea.significant_wave_height`, `sea.peak_period`, `sea.heading`), each a converged run with
    its verdict; returns a `CampaignResult` (`rows`, `summary`, `table`, `text`, `figures(dir)`).

    `scenario`: a scenario file's path (its `[sea] raos` file beside it), or its TOML text (the
    RAO file then relative to the current folder). `vary`: {field: values or "SPEC"} or the CLI's
    `--vary` texts; `set`: {field: value} or `--set` texts, applied to the scenario first.
    `target`: the overload probability a cell must stay below (on the `confidence` interval's
    upper bound, or the estimate with `on_estimate=True`); `exposure`: the events the most
    probable maximum is of (default 1 / target). `jobs`: threads (default one per core); `client`:
    a `dask.distributed.Client` or a scheduler address, one task per event. `max_events`: the
    most runs allowed (default `_native.CAMPAIGN_MAX_EVENTS`, the CLI's). `progress`: a tqdm bar
    on standard error (None: when it is a terminal).

    `fatigue=True` (`--fatigue`): each event's fatigue (the rows' `fatigue.damage`, `fatigue.life`,
    `fatigue.beam`, `fatigue.position`), each cell's mean damage per event in `summary["fatigue"]`
    and the text; `occurrence` (`--occurrence`, with `fatigue=True`): the sea states' occurrence
    table, a CSV file (significant_wave_height, peak_period, [heading,] probability or hours), for
    the damage per event weighted over the cells, a year's at `fatigue.events_per_year` and the life
    (docs/operability.md).

    ValueError with the crate's one-line message for what the CLI refuses (a target outside
    [1e-15, 1), a scenario without `[sea]`, a varied field that is not the sea's, ...). Ctrl-C:
    `CampaignInterrupted`, whose `.result` holds the rows done.
    """
    from . import _native
    from .native_run import scenario_source

    if jobs is not None and client is not None:
        raise ValueError("give jobs= (threads here) or client= (a Dask cluster), not both")
    if progress is None:
        progress = sys.stderr.isatty()
    path, text = scenario_source(scenario)
    if path is None and text is None:
        raise ValueError("campaign: give a scenario (a file with a [sea] section, or its TOML text)")
    for what, count in (("events", events), ("seeds", seeds), ("max_events", max_events), ("max_steps", max_steps)):
        if count is not None and (isinstance(count, bool) or not isinstance(count, numbers.Integral)
                                  or not 0 <= count < 2**64):
            raise ValueError(f"{what} must be a whole number from 1 to 2**64 - 1, got {count!r}"[:300])
    if seeds is None and isinstance(events, numbers.Integral) and not isinstance(events, bool) and events >= 1:
        seeds = min(_native.CAMPAIGN_DEFAULT_SEEDS, int(events))
    elif seeds is None:
        seeds = _native.CAMPAIGN_DEFAULT_SEEDS
    name, toml, raos_path, raos_text = _native.campaign_sources(path, text)
    if occurrence is not None and not fatigue:
        raise ValueError("occurrence= weights the events' fatigue: give fatigue=True too")
    table = None
    if occurrence is not None:
        table = _native.occurrence_text(os.fspath(occurrence))
    arguments = dict(
        name=name, text=toml, raos_path=raos_path, raos_text=raos_text, set=_texts("set", set),
        vary=_texts("vary", vary), events=int(events), seeds=int(seeds), record_length=float(record_length),
        target=float(target), confidence=float(confidence),
        exposure=None if exposure is None else float(exposure), on_estimate=bool(on_estimate),
        max_events=_native.CAMPAIGN_MAX_EVENTS if max_events is None else int(max_events),
        max_steps=_native.MAX_STEPS if max_steps is None else int(max_steps),
        fatigue=bool(fatigue), occurrence=table,
    )
    native = _native.Campaign(**arguments)
    import warnings

    for note in native.notes():
        warnings.warn(note, RuntimeWarning, stacklevel=2)
    for cell_name, (_, refused) in zip(native.cell_names(), native.cells()):
        if refused is not None:
            warnings.warn(f"{cell_name}: refused, its events not run: {refused}", RuntimeWarning, stacklevel=2)
    planned = f"{events} events per cell over {seeds} records of {float(record_length):g} s"
    if client is None:
        if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
            raise ValueError(f"jobs must be a whole number of threads >= 1, got {jobs!r}"[:300])
        done, interrupted = _run_threads(native, jobs, progress)
    else:
        key = hashlib.sha256(json.dumps(arguments, sort_keys=True).encode()).hexdigest()
        done, interrupted = _run_cluster(client, native, {"key": key, "arguments": arguments}, progress)
    rows = [[*json.loads(head), *_cells(json.loads(results)).values()] for _, head, results, _ in done]
    rows = [[math.nan if v is None else v for v in row] for row in rows]
    outcomes = [(index, outcome) for index, _, _, outcome in done]
    if interrupted:
        note = f"interrupted: {len(rows)} of {len(native)} events run ({planned}); {name}"
    else:
        note = f"{planned}; {name}"
    result = CampaignResult(native, rows, outcomes, interrupted, note)
    if interrupted:
        raise CampaignInterrupted(result)
    return result


def _cells(results: dict) -> dict:
    """The results' cells, `error` kept as text."""
    return {k: ("" if v is None and k == "error" else v) for k, v in results.items()}


def _run_threads(native, jobs: int | None, progress: bool):
    if not progress:
        return native.run(jobs)
    with _bar(len(native)) as bar:
        def advance(n: int) -> None:
            bar.update(n - bar.n)

        out = native.run(jobs, advance)
        bar.update(len(out[0]) - bar.n)
        return out


def _run_cluster(client, native, spec: dict, progress: bool):
    own = isinstance(client, str)
    if own:
        from distributed import Client

        client = Client(client)
    try:
        n = len(native)
        # The texts go to every worker once; each task names the event only.
        shared = client.scatter(spec, broadcast=True, hash=False)
        token = uuid.uuid4().hex[:12]  # fresh keys: never another campaign's cached results
        keys = [f"{TASK_PREFIX}-{token}-{i}" for i in range(n)]
        futures = client.map(_run_event, range(n), spec=shared, key=keys, pure=False)
        from distributed import as_completed

        interrupted = False
        bar = _bar(n) if progress else None
        try:
            for _ in as_completed(futures):
                if bar is not None:
                    bar.update(1)
        except KeyboardInterrupt:
            interrupted = True
            client.cancel([f for f in futures if not f.done()])
        finally:
            if bar is not None:
                bar.close()
        done = []
        for future in futures:
            if future.status == "finished":
                done.append(future.result())
            elif not interrupted:
                future.result()  # a task that failed (a worker died): its error, here
        return done, interrupted
    finally:
        if own:
            client.close()
