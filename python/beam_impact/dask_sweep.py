"""`beam_impact.sweep`: a grid of runs as Dask tasks, one row per scenario.

Each task runs one scenario of the grid and returns its row: by default through the Rust solver
itself (the native module, `beam_impact.run`'s code as one row of `beam-impact sweep`, made by
the CLI's own row code: its columns, names and order; no FMU, the GIL released while it solves,
Ctrl-C stopping the runs between steps); with `engine="fmu"` through the FMU
(`beam_impact.simulate`, logging off, one communication step over the whole run), whose table
has the CLI's columns the FMU gives (`FMU_LACKS`: those it has no output for).
A scenario refused, or whose run fails, returns its row with the message in `error`, and the
sweep goes on. What follows says how the FMU route runs; the native one runs the same way
without the FMU file (nothing to scatter: the workers need the `beam_impact` package only).

Where the tasks run:
- `client=None`: Dask's local threaded scheduler, one thread per core, with a tqdm bar (the
  estimated time left); the FMU is read from its path and unzipped once. The threads run
  in parallel: the whole run is one `fmi2DoStep` / `fmi3DoStep`, a ctypes call that releases the
  GIL; the FMU keeps no global state, and each run gets its own instance of the shared unzipped
  copy (fmpy's `simulate_fmu` is unsafe across threads when it unzips and deletes an FMU per
  call, which this never asks it to do). No `if __name__ == "__main__"` guard is needed.
- a `dask.distributed.Client` (of a `LocalCluster`, or `Client("tcp://host:8786")`), or a
  scheduler address: the FMU file's bytes are read here and scattered once to every worker, which
  unzips them once per process (keyed by their SHA-256), so workers need the `beam_impact`
  package but no shared file system; a tqdm bar follows the tasks as they finish. Workers must
  run Linux x86-64 (the FMU's binaries are `linux64` / `x86_64-linux`).
One task per scenario, so the bar advances per finished scenario, and each row keeps its wall time
(`wall_time`, s: the FMU run, from instantiation to the end).

What the rows share: nothing, unlike `beam-impact sweep`, whose rows of one geometry (the same
beams, contact and mesh; a different drop height, impact speed or damping) take the modes of
their rungs from one cache (issue 29). Each row here is its own FMU instance, and an FMU instance
computes its own modes: the FMU keeps no state between instances (nothing of one instance can
reach another, in this process or any other), and distributed workers are separate processes.
The setup repeated per row is about 4 % of a converged row's time (measured on the CLI); for a
sweep where that matters, run `beam-impact sweep`.
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
import uuid
from typing import Any, Iterable

from .fmu import CHECK_COLUMNS, ENVELOPE_OUTPUTS, FORMER_NAMES, PEAK_OUTPUTS, FmuFile, _extracted, _path_text, fmu_path, \
    simulate
from .grid import display, expand

#: Dask key prefix of the sweep's tasks (the progress bar's label).
TASK_PREFIX = "beam_impact-scenario"


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


def run_row(point: dict[str, float], fmu: "str | FmuFile", stop_time: float = 3.0,
            check_sensitivity: bool = False, fatigue: bool = False) -> dict[str, Any]:
    """One scenario's row: the varied values as the CLI shows them, the peaks, the energy
    approach and the checks (FMU names, then the former ones), `wall_time` (s) and `error` (""
    when fine)."""
    row: dict[str, Any] = {k: display(k, v) for k, v in point.items()}
    started = time.perf_counter()
    try:
        row.update(simulate(fmu, {**point, "check_sensitivity": check_sensitivity}, stop_time=stop_time))
        row["error"] = ""
    except Exception as e:  # a refused scenario or a failed run is a row, not an aborted sweep
        row["error"] = _one_line(e) or type(e).__name__
    row["wall_time"] = time.perf_counter() - started
    return row


def run_row_native(point: dict[str, float], scenario: Any = None, stop_time: float | None = 3.0,
                   check_sensitivity: bool = False, fatigue: bool = False) -> dict[str, Any]:
    """`run_row` through the Rust solver itself: the row `beam-impact sweep` writes for the grid
    point, made by the CLI's own code (the native module's `sweep_row`: the run of a sweep's row,
    the coarsest rung left out, no FMU; the row's cells as the CLI's JSON rows hold them, its
    columns and their order), with the CLI's message in `error` for a refused scenario. Empty
    cells (a failed row's results, a check not run) are NaN. The base scenario is `scenario` (a
    path or TOML text; None: the defaults, the FMU's), the run `stop_time` s long unless the grid
    varies `duration` (None: the scenario's). `fatigue`: the row of `beam-impact sweep --fatigue`
    (its fatigue columns)."""
    from . import _native
    from .native_run import scenario_source

    started = time.perf_counter()
    try:
        path, text = scenario_source(scenario)
        cells = json.loads(_native.sweep_row([(k, float(v)) for k, v in point.items()], scenario=path,
                                             scenario_text=text, duration=stop_time,
                                             sensitivity=check_sensitivity, fatigue=fatigue))
    except Exception as e:  # a scenario of the wrong type: still a row, not an aborted sweep
        return {**{k: display(k, v) for k, v in point.items()}, "error": _one_line(e) or type(e).__name__,
                "wall_time": time.perf_counter() - started}
    return {k: (math.nan if v is None and k != "error" else v) for k, v in cells.items()}


def fmu_columns(fields: Iterable[str], method: Iterable[str]) -> list[str]:
    """The FMU engine's columns: those of `beam-impact sweep` (`sweep_columns`' order) that the
    FMU gives (its outputs `simulate` reads: `FMU_COLUMNS` and the FMU's `energy_method.<field>`),
    after the varied `fields`."""
    from . import _native

    given = {*FMU_COLUMNS, *method, *FORMER_NAMES}
    return [*fields, *(c for c in _native.sweep_columns([]) if c in given)]


#: What a row of the FMU engine holds besides the varied fields and the energy approach.
FMU_COLUMNS = (*PEAK_OUTPUTS, *ENVELOPE_OUTPUTS, *CHECK_COLUMNS, "wall_time", "error")

#: The columns of `beam-impact sweep` (and of the native engine) that the FMU engine's table
#: lacks, in the CLI's order: the FMU has no output for them (tests/python/test_package.py holds
#: this list to the two engines' tables).
FMU_LACKS = (
    *(f"peak_time.{name.removeprefix('peak.')}" for name in PEAK_OUTPUTS),
    "energy_method.flexion_stiffness", "energy_method.bridge_deceleration", "energy_method.bridge_contact_moment",
    "energy_method.bridge_bending_stress", "energy_method.bridge_strain_energy", "energy_method.bridge_strain_ratio",
    "max_energy_residual", "yield_utilisation", "load_cases.utilisation",
    *(f"{former}_time" for former in PEAK_OUTPUTS.values()),
)


def _fmu_path(fmu: "str | os.PathLike | None") -> str:
    """`fmu` as given, else BEAM_IMPACT_FMU, else `beam_impact.fmu_path()` (BEAM_IMPACT_FMU_DIR,
    then the FMI 2 FMU a wheel carries)."""
    path = fmu if fmu is not None else os.environ.get("BEAM_IMPACT_FMU")
    if path is None:
        try:
            return fmu_path("fmi2")
        except FileNotFoundError as e:
            raise ValueError(f"no FMU: pass fmu=PATH (or set BEAM_IMPACT_FMU); {e}") from None
    path = _path_text(path)
    if not os.path.lexists(path):
        raise FileNotFoundError(f"{path}: no such FMU (build it with `beam-impact pack`)")
    return path


def _columns(fields: Iterable[str], path: str) -> list[str]:
    # The FMU read through the native module's checks (a regular file of at most 1 GiB), unzipped
    # once; fmpy never opens the user's path.
    md = _extracted(path).model_description
    names = {v.name for v in md.modelVariables}
    for f in fields:
        if f != "duration" and f not in names:
            raise ValueError(f"unknown parameter `{f}`: the FMU has no variable of that name")
    method = [v.name for v in md.modelVariables if v.name.startswith("energy_method.")]
    return fmu_columns(fields, method)


def sweep(
    grid: dict[str, Iterable[Any]],
    client: Any = None,
    fmu: "str | os.PathLike | None" = None,
    stop_time: float | None = None,
    progress: bool | None = None,
    num_workers: int | None = None,
    check_sensitivity: bool = False,
    engine: str | None = None,
    scenario: Any = None,
    fatigue: bool = False,
):
    """Runs every scenario of `grid` ({field: values}, the product in dict order with the last
    field fastest, as `beam-impact sweep --vary`) and returns a pandas.DataFrame, one row per
    scenario in grid order.

    Columns: by default (the native engine) those of `beam-impact sweep --out` for the same grid,
    the same names in the same order (`docs/cli.md` lists them with their units): the varied
    fields, the peaks `peak.<quantity>` (SI) and when each was reached `peak_time.<quantity>` (s),
    each beam's worst stress along it `peak.<beam>.<stress>` with `peak_position.<...>` (m) and
    `utilisation.<...>`, the energy approach `energy_method.<field>`, `max_energy_residual`, the
    checks `quality.discretisation_error`, `quality.sensitivity_spread` (NaN unless
    `check_sensitivity=True`, which runs each scenario's twin as the CLI's sweep does, at twice the
    stepping cost), `yield_utilisation`, `utilisation.<stress peak>`, `design.pass`,
    `quality.trusted`, `wall_time` (the row's run, s) and `error` ("" when fine; the results are
    NaN then, as the CLI's cells are empty); then the former names of the peaks, their times and
    the checks (`lower_clamp_bending_stress`, `contact_force_time`, `trusted`, ...), duplicates
    until 0.2.0. An empty cell of the CLI is NaN.

    `engine`: "native" (the default without `fmu`) runs each scenario through the Rust solver
    itself (the CLI sweep's row of `beam_impact.run`'s code; no FMU needed; the GIL is released,
    so threads solve in parallel); "fmu" (the default when `fmu` is given) through the FMU at
    `fmu` (or `$BEAM_IMPACT_FMU`) with fmpy. The FMU engine's table has the CLI's columns that the
    FMU gives as outputs, in the same order, and lacks the others (`FMU_LACKS`): the peak times
    `peak_time.<quantity>` (and their former names `<quantity>_time`), six of the eleven
    `energy_method.<field>` (`flexion_stiffness` and the bridge's five), `max_energy_residual`,
    `yield_utilisation` and `load_cases.utilisation` (the FMU judges no load cases). In the columns both have, the two engines give the same numbers (to
    round-off: tests/python/test_package.py holds both to the CLI's sweep at 1e-9). `scenario`
    (native engine only): the base scenario, a file path or TOML text as `beam_impact.run` takes
    it (default: the defaults, the FMU's, as `beam-impact sweep` without a file). `fatigue=True`
    (native engine only, `sweep --fatigue`): each row's fatigue on the scenario's `[fatigue]` curve,
    the columns `fatigue.damage` (Miner's sum of one impact at the worst station), `fatigue.life`
    (years at `fatigue.events_per_year`, NaN without it), `fatigue.beam` and `fatigue.position`
    after `load_cases.utilisation` (about 1.6 times a row's work; docs/fatigue-run.md).
    `client`: None for the local threaded scheduler (`num_workers` threads, default one per core),
    a `dask.distributed.Client`, or a scheduler address ("tcp://host:8786").
    `stop_time`: simulated s per run (a varied `duration` overrides it; default: the scenario's
    `duration` on the native engine, 3 s, the defaults' too, on the FMU). `progress`: show a tqdm
    bar with the estimated time left on standard error, from 2 s into the sweep (default: when
    standard error is a terminal). Ctrl-C stops the local sweep's runs between steps
    (KeyboardInterrupt). Rows share no work (see the module's documentation). The FMU is read only
    if it is a regular file of at most 1 GiB (ValueError at once otherwise: a FIFO, a device, a
    folder)."""
    import pandas as pd

    if engine is None:
        engine = "native" if fmu is None else "fmu"
    if engine not in ("native", "fmu"):
        raise ValueError(f"engine must be \"native\" or \"fmu\", got {engine!r}")
    if engine == "native" and fmu is not None:
        raise ValueError("fmu= is for engine=\"fmu\"; the native engine runs the solver itself")
    if engine == "fmu" and scenario is not None:
        raise ValueError("scenario= is for the native engine; the FMU starts from its own parameters")
    if engine == "fmu" and fatigue:
        raise ValueError("fatigue=True is for the native engine; the FMU keeps no stress history")
    points = expand(grid)
    if engine == "fmu":
        stop_time = 3.0 if stop_time is None else stop_time
        path = _fmu_path(fmu)
        columns = _columns(list(grid), path)
        task, target = run_row, path
    else:
        from . import _native

        # The CLI's columns for this grid (an unknown field refused with the CLI's message).
        columns = list(_native.sweep_columns([str(f) for f in grid], fatigue=bool(fatigue)))
        task, target = run_row_native, scenario
    if client is None:
        rows = _run_local(task, points, target, stop_time, progress, num_workers, check_sensitivity, bool(fatigue))
    else:
        own = isinstance(client, str)
        if own:
            from distributed import Client

            client = Client(client)
        try:
            if engine == "fmu":
                target = client.scatter(FmuFile.read(target), broadcast=True)
            rows = _run_distributed(client, task, points, target, stop_time, progress, check_sensitivity,
                                    bool(fatigue))
        finally:
            if own:
                client.close()
    return pd.DataFrame(rows, columns=columns)


#: Seconds before the bar shows: a sweep shorter than this prints none.
BAR_DELAY = 2.0


def _bar(total: int):
    """The sweep's tqdm bar on standard error: scenarios done, elapsed and estimated time left."""
    from tqdm import tqdm

    return tqdm(total=total, unit="scenario", desc="sweep", file=sys.stderr, delay=BAR_DELAY, dynamic_ncols=True)


def _run_local(task, points, target, stop_time, progress, num_workers, check_sensitivity,
               fatigue=False) -> list[dict]:
    import dask
    from dask.callbacks import Callback

    if progress is None:
        progress = sys.stderr.isatty()

    class _Advance(Callback):
        """Advances the bar by one per finished scenario task."""

        def __init__(self, bar):
            super().__init__()
            self.bar = bar

        def _posttask(self, key, result, dsk, state, worker_id):
            if str(key).startswith(TASK_PREFIX):
                self.bar.update(1)

    tasks = [dask.delayed(task, pure=False)(p, target, stop_time, check_sensitivity, fatigue,
                                            dask_key_name=f"{TASK_PREFIX}-{i}")
             for i, p in enumerate(points)]
    try:
        if not progress:
            return list(dask.compute(*tasks, scheduler="threads", num_workers=num_workers))
        with _bar(len(tasks)) as bar, _Advance(bar):
            return list(dask.compute(*tasks, scheduler="threads", num_workers=num_workers))
    except KeyboardInterrupt:
        # Ctrl-C reaches the main thread only: the runs on the pool's threads stop at their next
        # step (native engine); an FMU's doStep runs to its end.
        from . import _native

        _native.cancel_running()
        raise


def _run_distributed(client, task, points, target, stop_time, progress, check_sensitivity,
                     fatigue=False) -> list[dict]:
    if progress is None:
        progress = sys.stderr.isatty()
    token = uuid.uuid4().hex[:12]  # fresh keys: never another sweep's cached results
    keys = [f"{TASK_PREFIX}-{token}-{i}" for i in range(len(points))]
    # The FMU (a scattered future) or the base scenario, the same for every task: a keyword, not
    # an iterable mapped over.
    shared = {"fmu": target} if task is run_row else {"scenario": target}
    futures = client.map(task, points, **shared, stop_time=stop_time, check_sensitivity=check_sensitivity,
                         fatigue=fatigue, key=keys, pure=False)
    if progress:
        from distributed import as_completed

        with _bar(len(futures)) as bar:
            for _ in as_completed(futures):
                bar.update(1)
    rows = []
    for point, future in zip(points, futures):
        try:
            rows.append(future.result())
        except Exception as e:  # the worker died (a crash inside the FMU): still a row
            rows.append({**{k: display(k, v) for k, v in point.items()}, "error": f"task failed: {_one_line(e)}"})
    return rows
