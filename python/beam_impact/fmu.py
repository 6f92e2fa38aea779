"""One run of the beam-impact FMU through fmpy.

Parameters are the scenario's dotted names (`drop_height`, `upper.mass`, ...), with the values of
`beam_impact.grid.parse_value` ("auto" time steps, stress recovery names); `duration` is the stop
time (the FMU runs until its importer's stop time); `upper.tip_force` / `lower.tip_force` are the
FMU's inputs, held constant. Logging is off unless asked (`log.path` = "").

With one communication step over the whole run (the default here) the FMU takes the CLI's very
internal steps, so the peaks equal `beam-impact run`'s to round-off (docs/fmu.md, "Co-simulation grid").
"""

from __future__ import annotations

import atexit
import hashlib
import math
import os
import shutil
import tempfile
import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .grid import INTEGER_FIELDS, PEAKS, parse_value

#: FMU output -> its former name (the CLI's before one name per quantity; a duplicate key until
#: 0.2.0), for the five peaks.
PEAK_OUTPUTS = {
    "peak.lower.tip_deflection": "lower_tip_deflection",
    "peak.lower.clamp_bending_stress": "lower_clamp_bending_stress",
    "peak.lower.clamp_shear_stress": "lower_clamp_shear_stress",
    "peak.upper.contact_bending_stress": "upper_contact_bending_stress",
    "peak.contact.force": "contact_force",
}
assert tuple(PEAK_OUTPUTS.values()) == PEAKS

#: The stress envelope's outputs (issue 30): each beam's worst bending and shear stress along it
#: (Pa), where (m from its support) and its utilisation, in the CLI sweep's columns' order. The
#: FMU gives 0 where the beam has no such stress (or, for a utilisation, no allowable), where the
#: CLI's cell is empty: NaN here.
ENVELOPE_NAMES = ("upper.bending_stress", "upper.shear_stress", "lower.bending_stress", "lower.shear_stress")
ENVELOPE_OUTPUTS = (*(f"peak.{n}" for n in ENVELOPE_NAMES), *(f"peak_position.{n}" for n in ENVELOPE_NAMES),
                    *(f"utilisation.{n}" for n in ENVELOPE_NAMES))

#: FMU output -> its former name, for the checks and the design (Real; -1 is "not checked", NaN here).
CHECK_OUTPUTS = {
    "quality.discretisation_error": "discretisation_error",
    "quality.sensitivity_spread": "sensitivity_spread",
    "utilisation.lower.clamp_bending_stress": "utilisation.lower_clamp_bending_stress",
    "utilisation.lower.clamp_shear_stress": "utilisation.lower_clamp_shear_stress",
    "utilisation.upper.contact_bending_stress": "utilisation.upper_contact_bending_stress",
}
#: FMU Boolean output -> its former name.
VERDICT_OUTPUTS = {"design.pass": "design_pass", "quality.trusted": "trusted"}
#: The columns `simulate` adds after the peaks and the energy approach, in the CLI sweep's order.
CHECK_COLUMNS = (*CHECK_OUTPUTS, *VERDICT_OUTPUTS)
#: Every former name -> its name, in the order `simulate` repeats them after the named keys.
FORMER_NAMES = {former: name for name, former in {**PEAK_OUTPUTS, **CHECK_OUTPUTS, **VERDICT_OUTPUTS}.items()}
#: FMU-only Boolean parameters `simulate` accepts.
BOOLEAN_PARAMETERS = frozenset({"check_sensitivity"})
#: Largest whole number an FMU Integer parameter holds.
_INT_MAX = 2**31 - 1

#: fmi2Error / fmi3Error and above.
_ERROR = 3


#: Where a wheel keeps its packed FMUs, inside the installed package: fmus/fmi2/BeamImpact.fmu and
#: fmus/fmi3/BeamImpact.fmu (scripts/build-wheels.sh puts them there; `pip install ./python` has none).
PACKED_FMUS = Path(__file__).resolve().parent / "fmus"
#: The FMI versions `fmu_path` knows.
FMI_VERSIONS = ("fmi2", "fmi3")


def fmu_path(version: str = "fmi2") -> str:
    """The path of the beam-impact FMU for `version` ("fmi2" or "fmi3"), found in this order:

    1. `$BEAM_IMPACT_FMU_DIR/<version>/BeamImpact.fmu` when BEAM_IMPACT_FMU_DIR is set (the layout
       `beam-impact pack --out DIR` writes): a setting made on purpose beats the default, so a
       developer's freshly packed FMUs win over the ones a wheel carries;
    2. the FMU packed inside the installed package (`beam_impact/fmus/<version>/BeamImpact.fmu`),
       which every wheel built by scripts/build-wheels.sh carries.

    Raises ValueError for another version, and FileNotFoundError with one line naming the places
    looked at when neither holds the FMU (a package installed from source carries none: pack them
    with `beam-impact pack --out DIR` and set BEAM_IMPACT_FMU_DIR=DIR)."""
    if version not in FMI_VERSIONS:
        raise ValueError(f"fmu_path: version must be one of {', '.join(FMI_VERSIONS)}, got {version!r}")
    looked = []
    directory = os.environ.get("BEAM_IMPACT_FMU_DIR")
    if directory:
        path = Path(directory) / version / "BeamImpact.fmu"
        if path.is_file():
            return str(path)
        looked.append(f"{path} (BEAM_IMPACT_FMU_DIR)")
    packed = PACKED_FMUS / version / "BeamImpact.fmu"
    if packed.is_file():
        return str(packed)
    looked.append(f"{packed} (inside the package: wheels carry it, an install from source does not)")
    raise FileNotFoundError(f"no {version} FMU: looked at {'; '.join(looked)}; pack one with "
                            "`beam-impact pack --out DIR` and set BEAM_IMPACT_FMU_DIR=DIR")


class SimulationError(RuntimeError):
    """A run the FMU refused or could not finish; the message is the FMU's own (its logger's)."""


class ScenarioError(SimulationError, ValueError):
    """A scenario, field, value or limit refused before anything runs, in one line naming the field
    and the value, whatever the door (`run`, `simulate`, `sweep`): a ValueError, and a
    SimulationError as `simulate`'s refusals always were."""


@dataclass(frozen=True)
class FmuFile:
    """An FMU's bytes, the unit shipped to a cluster's workers (scattered once to each)."""

    name: str
    data: bytes = field(repr=False)
    sha256: str = ""

    @staticmethod
    def read(path: str | os.PathLike) -> "FmuFile":
        """The FMU at `path`: a regular file of at most 1 GiB (`beam_impact._native.MAX_FMU_BYTES`,
        checked by the native module before a byte is read: a FIFO or a device fails at once),
        else ValueError with one line."""
        from . import _native

        data = _native.read_fmu(_path_text(path))
        return FmuFile(Path(_path_text(path)).name, data, hashlib.sha256(data).hexdigest())


def _path_text(path: "str | os.PathLike") -> str:
    """A path as text for the native module (bytes paths decoded as the file system does)."""
    return os.fsdecode(os.fspath(path))


@dataclass
class _Extracted:
    directory: str
    model_description: Any
    names: set = field(default_factory=set)


_cache: dict[str, _Extracted] = {}
_lock = threading.Lock()
_scratch: list[str] = []


def _cleanup() -> None:
    for d in _scratch:
        shutil.rmtree(d, ignore_errors=True)


atexit.register(_cleanup)


def _extracted(fmu: "str | os.PathLike | FmuFile") -> _Extracted:
    """The FMU unzipped once per process (keyed by its content), with its model description."""
    from fmpy import extract, read_model_description

    from . import _native

    if isinstance(fmu, FmuFile):
        key, data, path = fmu.sha256 or hashlib.sha256(fmu.data).hexdigest(), fmu.data, None
    else:
        # Checked by the native module before anything reads it: a regular file of at most 1 GiB
        # (_native.MAX_FMU_BYTES; ValueError at once for a FIFO, a device, a folder or a larger file).
        path = _path_text(fmu)
        key, data = f"{os.path.abspath(path)}:{_native.fmu_key(path)}", None
    with _lock:
        hit = _cache.get(key)
        if hit is not None:
            return hit
        if data is None:
            data = _native.read_fmu(path)
        scratch = tempfile.mkdtemp(prefix="beam_impact-fmu-")
        _scratch.append(scratch)
        # fmpy reads this copy, never the user's path (which may have changed since the check).
        source = os.path.join(scratch, "model.fmu")
        _native.write_file(source, data, "the FMU's copy")
        directory = extract(source, unzipdir=os.path.join(scratch, "unzipped"))
        md = read_model_description(directory)
        entry = _Extracted(directory, md, {v.name for v in md.modelVariables})
        _cache[key] = entry
        return entry


def _start_values(parameters: dict[str, Any], names: set) -> tuple[dict[str, Any], float | None]:
    values: dict[str, Any] = {}
    duration = None
    for key, value in parameters.items():
        if key in BOOLEAN_PARAMETERS:
            if not isinstance(value, bool):
                raise ScenarioError(f"{key} takes True or False, got {value!r}")
            values[key] = value
            continue
        v = parse_value(key, value)
        if key == "duration":
            duration = v
            continue
        if key not in names:
            raise ScenarioError(f"unknown parameter `{key}`: the FMU has no variable of that name")
        if key in INTEGER_FIELDS:
            if not (v.is_integer() and 0 <= v <= _INT_MAX):
                raise ScenarioError(f"{key} must be a whole number >= 0 (0: auto where allowed), got {v:g}")
            v = int(v)
        values[key] = v
    return values, duration


class _Fmi2Messages:
    """FMI 2 logger messages, routed to their run by `componentEnvironment`.

    fmpy's varargs proxy (`fmpy.logging.addLoggerProxy`, which formats the FMU's printf-style
    message) keeps the Python logger in one process-wide pointer, so every instance in a process
    must share one logger that lives as long as the process (a logger freed after its run, with
    another run's pointer still on it, would crash the next message). This is that logger; each
    run passes its own key as `componentEnvironment`, which the FMU hands back untouched."""

    def __init__(self) -> None:
        from fmpy.fmi2 import fmi2CallbackLoggerTYPE

        self.lock = threading.Lock()
        self.runs: dict[int, list] = {}
        self.next_key = 1
        self.callback = fmi2CallbackLoggerTYPE(self._log)

    def _log(self, env, instance, status, category, message) -> None:
        with self.lock:
            messages = self.runs.get(int(env or 0))
        if messages is not None:
            messages.append((int(status), message.decode(errors="replace") if message else ""))
        else:  # another importer's instance in this process (e.g. a plain fmpy.simulate_fmu): print, as fmpy does
            from fmpy.fmi1 import printLogMessage

            printLogMessage(env, instance, status, category, message)

    def open(self) -> tuple[int, list]:
        with self.lock:
            key, self.next_key = self.next_key, self.next_key + 1
            self.runs[key] = []
            return key, self.runs[key]

    def close(self, key: int) -> None:
        with self.lock:
            self.runs.pop(key, None)


_fmi2_messages: _Fmi2Messages | None = None


def _fmi2_router() -> _Fmi2Messages:
    global _fmi2_messages
    with _lock:
        if _fmi2_messages is None:
            _fmi2_messages = _Fmi2Messages()
        return _fmi2_messages


#: Most communication points one `simulate` call takes (histories of 1e7 rows are ~2 GB).
MAX_POINTS = 10_000_000


def _communication_points(stop_time: float, interval: float) -> list[float]:
    """0, interval, 2 interval, ..., stop_time (the last one exactly), from the index, not a sum."""
    if not (interval > 0 and stop_time / interval <= MAX_POINTS):
        raise SimulationError(f"output_interval = {interval} s over {stop_time} s gives more than {MAX_POINTS} "
                              "communication points: raise output_interval")
    n = max(1, int(round(stop_time / interval)))
    return [k * interval for k in range(n)] + [stop_time]


def _run(entry: _Extracted, start: dict[str, Any], stop_time: float, interval: float, outputs: list[str],
         histories: bool) -> list[list[float]]:
    """Drives one co-simulation instance (FMI 2 or 3): start values, initialization, doStep over
    the communication points; returns the outputs at the end (or at every point, time first)."""
    md = entry.model_description
    variables = {v.name: v for v in md.modelVariables}
    fmi2 = md.fmiVersion.startswith("2")
    common = dict(guid=md.guid, unzipDirectory=entry.directory, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="beam_impact")
    messages: list[tuple[int, str]]
    if fmi2:
        from ctypes import byref, c_void_p

        from fmpy.fmi2 import FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE, \
            fmi2CallbackFunctions
        from fmpy import calloc, free
        from fmpy.logging import addLoggerProxy

        router = _fmi2_router()
        key, messages = router.open()
        callbacks = fmi2CallbackFunctions()
        callbacks.logger = router.callback
        callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        callbacks.componentEnvironment = c_void_p(key)
        addLoggerProxy(byref(callbacks))
        fmu = FMU2Slave(**common)
        setters = {"Real": fmu.setReal, "Integer": fmu.setInteger, "Boolean": fmu.setBoolean,
                   "String": fmu.setString}
        get, get_boolean = fmu.getReal, fmu.getBoolean
    else:
        from fmpy.fmi3 import FMU3Slave

        messages = []
        key = 0

        def log(env, status, category, message):
            messages.append((int(status), message.decode(errors="replace") if message else ""))

        fmu = FMU3Slave(**common)
        setters = {"Float64": fmu.setFloat64, "Int32": fmu.setInt32, "Int64": fmu.setInt64,
                   "Boolean": fmu.setBoolean, "String": fmu.setString}
        get, get_boolean = fmu.getFloat64, fmu.getBoolean
    instantiated = False
    try:
        if fmi2:
            fmu.instantiate(callbacks=callbacks)
        else:
            fmu.instantiate(logMessage=log)
        instantiated = True
        if fmi2:
            fmu.setupExperiment(startTime=0.0, stopTime=stop_time)
        for name, value in start.items():
            v = variables[name]
            setters[v.type]([v.valueReference], [value])
        if fmi2:
            fmu.enterInitializationMode()
        else:
            fmu.enterInitializationMode(startTime=0.0, stopTime=stop_time)
        fmu.exitInitializationMode()
        vrs = [variables[n].valueReference for n in outputs]
        points = _communication_points(stop_time, interval)
        rows = [[0.0, *get(vrs)]] if histories else []
        for t0, t1 in zip(points, points[1:]):
            fmu.doStep(currentCommunicationPoint=t0, communicationStepSize=t1 - t0)
            if histories:
                rows.append([t1, *get(vrs)])
        if not histories:
            rows = [[stop_time, *get(vrs)]]
        verdicts = get_boolean([variables[n].valueReference for n in VERDICT_OUTPUTS])
        fmu.terminate()
        return rows, [bool(v) for v in verdicts]
    except Exception as e:
        errors = [m for status, m in messages if status >= _ERROR]
        raise SimulationError("; ".join(errors) if errors else (str(e) or type(e).__name__)) from e
    finally:
        if instantiated:
            fmu.freeInstance()  # also unloads this instance's handle on the shared library
        else:
            fmu.freeLibrary()
        if fmi2:
            router.close(key)


def _check_steps(start: dict[str, Any], stop_time: float, max_steps: int | None) -> None:
    """The CLI's step limit, checked by the crate itself (beam_impact._native.check_run)."""
    from . import _native

    limit = _native.MAX_STEPS if max_steps is None else max_steps
    if not (isinstance(limit, int) and 0 < limit < 2**64):
        raise ScenarioError(f"max_steps must be a whole number > 0, got {max_steps!r}")
    values = {k: float(v) for k, v in start.items() if k not in BOOLEAN_PARAMETERS and isinstance(v, (int, float))}
    try:
        _native.check_run(values, float(stop_time), limit)
    except ValueError as e:
        message = " ".join(str(e).split()).replace("with --max-steps", "with simulate(..., max_steps=N)")
        raise ScenarioError(message[:600] + ("..." if len(message) > 600 else "")) from None


def simulate(
    fmu: "str | os.PathLike | FmuFile",
    parameters: dict[str, Any] | None = None,
    stop_time: float = 3.0,
    output_interval: float | None = None,
    log_path: str | None = None,
    histories: bool = False,
    max_steps: int | None = None,
):
    """Runs the FMU once: `parameters` by the scenario's dotted names, until `stop_time` s (or the
    `duration` parameter). Returns a dict keyed by the FMU's output names (one name per quantity, as
    the CLI's sweep columns): the peaks (`peak.lower.tip_deflection`, `peak.lower.clamp_bending_stress`,
    `peak.lower.clamp_shear_stress`, `peak.upper.contact_bending_stress`, `peak.contact.force`; SI
    units), the stress envelope (`peak.<beam>.<stress>` each beam's worst bending and shear stress
    along it, `peak_position.<...>` where, m, `utilisation.<...>`; NaN where the beam has none,
    the FMU's 0), the energy approach (`energy_method.<field>`), and the checks:
    `quality.discretisation_error`, `quality.sensitivity_spread` (fractions; NaN when not checked:
    the twin runs only with `"check_sensitivity": True`, which doubles the cost),
    `utilisation.<stress peak>` (converged peak / allowable), `design.pass` and `quality.trusted`;
    then the same values under their former names (`lower_clamp_bending_stress`, `trusted`, ...;
    `FORMER_NAMES`), kept until 0.2.0. With
    `histories=True`, returns (dict, DataFrame of every real output at each communication point,
    `output_interval` default 1e-3 s, time first); otherwise one communication step over the whole
    run. `log_path`: write the FMU's MCAP log there (default: no log). Raises SimulationError with
    the FMU's message when it refuses the parameters or the run fails, and, before the FMU is
    loaded, with the CLI's message when the run needs more than `max_steps` internal steps
    (default the CLI's 1e8, its `--max-steps`; the check builds the model's modes, stepping
    nothing); `max_steps` is also the FMU's `solver.max_steps` (at most 2^31 - 1), enforced at
    every internal step of doStep: a run whose steps shrink far below its plan's stops there with
    SimulationError naming the limit and the time reached.

    The FMU at a path is read only if it is a regular file of at most 1 GiB (held in memory whole;
    `beam_impact._native.MAX_FMU_BYTES`);
    otherwise, and for a `log_path` that the output guard of the CLI refuses (a NUL in it, a
    symbolic link, a folder, a FIFO, a socket or a device, or the FMU file itself, compared by
    device and inode), ValueError with one line, before the FMU is loaded.

    The instance is driven here through fmpy's FMU2Slave / FMU3Slave (not `simulate_fmu`), so that
    runs on several threads of one process keep their logger messages apart (see _Fmi2Messages)."""
    log_text = "" if log_path is None else _path_text(log_path)
    if log_text:
        from . import _native

        inputs = [] if isinstance(fmu, FmuFile) else [("the FMU", _path_text(fmu))]
        _native.check_output(log_text, "log_path", inputs)
    entry = _extracted(fmu)
    md = entry.model_description
    start, duration = _start_values(dict(parameters or {}), entry.names)
    if duration is not None:
        stop_time = duration
    if not 0 < stop_time <= 1e6:
        raise ScenarioError(f"stop time must be > 0 s and at most 1e6 s (the FMU's limit), got {stop_time}")
    _check_steps(start, stop_time, max_steps)
    if max_steps is not None and "solver.max_steps" in entry.names:
        # Enforced inside doStep too (issue 40): the FMU's Integer parameter, at most 2^31 - 1.
        start["solver.max_steps"] = min(max_steps, _INT_MAX)
    start["log.path"] = log_text
    if output_interval is None:
        output_interval = min(1e-3, stop_time) if histories else stop_time
    method = [v.name for v in md.modelVariables if v.name.startswith("energy_method.")]
    envelope = [name for name in ENVELOPE_OUTPUTS if name in entry.names]  # an FMU before issue 30 has none
    outputs = list(PEAK_OUTPUTS) + method + list(CHECK_OUTPUTS) + envelope
    if histories:
        real = ("Real", "Float64")
        outputs += [v.name for v in md.modelVariables if v.causality == "output" and v.type in real
                    and v.name not in outputs]
    rows, verdicts = _run(entry, start, stop_time, output_interval, outputs, histories)
    last = dict(zip(outputs, rows[-1][1:]))
    peaks: dict[str, Any] = {name: float(last[name]) for name in PEAK_OUTPUTS}
    # The FMU's 0 for a beam without the stress (or without an allowable): the CLI's empty cell.
    # A position of 0 m is a peak at the support: NaN only where the peak itself is.
    peaks.update({name: (math.nan if last[name] == 0 else float(last[name]))
                  for name in envelope if not name.startswith("peak_position.")})
    peaks.update({name: (math.nan if math.isnan(peaks[name.replace("peak_position.", "peak.", 1)])
                         else float(last[name])) for name in envelope if name.startswith("peak_position.")})
    peaks.update({name: float(last[name]) for name in method})
    peaks.update({name: (math.nan if last[name] < 0 else float(last[name])) for name in CHECK_OUTPUTS})
    peaks.update(dict(zip(VERDICT_OUTPUTS, verdicts)))
    peaks.update({former: peaks[name] for former, name in FORMER_NAMES.items()})
    if not histories:
        return peaks
    import pandas as pd

    return peaks, pd.DataFrame(rows, columns=["time", *outputs])
