"""Load a beam-impact MCAP log into numpy arrays (or a pandas DataFrame of the step channel).

    from beam_impact import load_log
    log = load_log("paper.mcap")
    log.steps["time"], log.steps["lower_tip_deflection"], ...   every scalar field of beam_impact.Step
    log.steps["energy.kinetic"], log.steps["peaks.contact_force"], ...   nested fields, dotted
    log.dataframe()         the same columns as a pandas.DataFrame, one row per internal step
    log.modal_coordinates   (messages x coordinates), float64; row k is step log.modal_steps[k]
    log.modal_steps, log.modal_times   the step and time (s) of each row
    log.nodal_shapes        (nodes x coordinates): nodal deflections w = nodal_shapes @ q
    log.lower_nodes, log.upper_nodes   node positions from clamp / hinge, m
    log.events              list of dicts (start, time, time_ns, step, relative_velocity)
    log.scenario_toml, log.metadata, log.log_times (every message's log_time, file order)
    log.complete            False for the log of a killed run (no summary and footer)
    log.problem, log.damaged   where the reading stopped, and whether at damaged bytes
    log.stopped_early       why the log ended before the run (its size cap), "" if it did not
    log.rollbacks           FMU states restored: the steps they superseded are left out, as `report` does
    log.upper_strain_at_peak_deflection   the FEM bridge strain energy at the largest arrestor deflection, J, as
                            the run printed it (`report`'s line), or None for a log written before logs held it
    log.answer              the run's verdict and checks as `beam-impact run` stored them (dict), or None
    log.motion_csv          the support-motion table the run used (the log's `motion.csv`), or None
    log.motion              that table as a pandas.DataFrame (`time`, then its columns), or None
    log.envelope            the stress envelope (issue 30): {"lower": {"bending": DataFrame, "shear": DataFrame},
                            "upper": {...}, "sampled_every", "source", "note"}, each DataFrame one row per
                            station (position m, max Pa, time s, allowable Pa, utilisation); None when absent
    log.stations            the stress stations: DataFrame (column, beam, stress, position, allowable, node)
    log.station_stresses    the signed stress at every station, every 1 ms of the rows: DataFrame (step, time,
                            then one column per station, `lower.bending.0`, ...; Pa), or None when not recorded
    log.fatigue             the run's fatigue (issue 44) as `report --fatigue` has it, with the keys of `run --json`'s
                            `fatigue` block (dict), or None (`log.fatigue_note` says why)

The file is read by the Rust reader of `beam-impact report` (the native module
`beam_impact._native`, built by `pip install ./python`), not by a second reader in Python: every
length in the file is checked before anything is allocated or decompressed, chunk CRCs are
checked, decompression is bounded by 64x the file and what is kept by 16x the file (+16 MiB), and
time is linear in the file, also for a log of many rollbacks. The log of a killed writer has every
complete chunk and no summary: it loads up to its last complete chunk, with `complete` False and
`problem` saying where it ends. Any file that is not a readable beam-impact log (a FIFO, a device,
a folder, an unknown log format, damaged records before any step) raises `LogError`, one line.
Step 0 is the initial state.

A run with moving supports replays from its log alone: the motion table it used is stored in the
log (the attachment `motion.csv`, its rows as the CLI read them), and `motion_csv` / `motion` come
from there, never from the motion file the scenario names (`motion.file`, which may be gone or
changed). A log written before logs carried the table has `motion_csv` None.

The stress envelope comes from the log's `envelope.json` (stored when the log was finished:
`envelope["source"] == "attachment"`); a log without it (a killed run) has it rebuilt from the
rows of `/beam/stations` (every 1 ms by default they carry the run's envelope so far: the last such
row's, raised by the stresses after it, single precision), as `beam-impact
report` rebuilds it (`"rebuilt"`, and `envelope["note"]` says why); a log written before logs carried the
envelope has `envelope` None, and `station_stresses` None.

Both log formats load. Format 2 (metadata `log_format` = 2) keeps the modal coordinates on
`/beam/modes` (every 1 ms, at contact changes, at the arrestor's peak deflection and at the last
step), leaves a step's `peaks` out when they equal the previous step's (carried forward here) and
leaves out `time` (= time_ns / 1e9, computed here). Format 1 had float32 coordinates in every step.
"""

from __future__ import annotations

import json
import os
import sys
from dataclasses import dataclass, field

import numpy as np

STEP_TOPIC = "/beam/step"
STATIONS_TOPIC = "/beam/stations"
CONTACT_TOPIC = "/beam/contact"
MODEL_TOPIC = "/beam/model"
MODES_TOPIC = "/beam/modes"
LOG_TOPIC = "/beam/log"

SCALARS = [
    "step",
    "time_ns",
    "time",
    "step_size",
    "contact",
    "lower_tip_deflection",
    "upper_contact_deflection",
    "upper_tip_deflection",
    "lower_clamp_bending_stress",
    "lower_clamp_shear_stress",
    "upper_contact_bending_stress",
    "contact_force",
    "contact_stress",
    "lower_clamp_reaction_force",
    "lower_clamp_reaction_moment",
    "upper_hinge_reaction_force",
    "lower_tip_velocity",
    "upper_tip_velocity",
    "lower_far_reaction_force",
    "lower_far_reaction_moment",
]
ENERGY = ["kinetic", "strain", "gravity_potential", "external_work", "damping_dissipation", "residual"]
PEAKS = [
    "lower_tip_deflection",
    "lower_clamp_bending_stress",
    "lower_clamp_shear_stress",
    "upper_contact_bending_stress",
    "contact_force",
]
INTEGER = {"step": np.uint64, "time_ns": np.uint64, "contact": np.bool_}
#: The stress stations' groups, in the order of the stresses' columns.
STATION_GROUPS = ["lower.bending", "lower.shear", "upper.bending", "upper.shear"]


@dataclass
class Log:
    steps: dict[str, np.ndarray]
    modal_coordinates: np.ndarray
    modal_steps: np.ndarray
    modal_times: np.ndarray
    nodal_shapes: np.ndarray
    lower_nodes: np.ndarray
    upper_nodes: np.ndarray
    events: list[dict]
    scenario_toml: str
    metadata: dict[str, str]
    log_times: np.ndarray
    counts: dict[str, int] = field(default_factory=dict)
    #: False when the file ends before its summary and footer (a killed run).
    complete: bool = True
    #: Why the reading stopped early ("" for a complete file): the record and its byte offset.
    problem: str = ""
    #: True when the reading stopped at bytes that are not a valid log (a bad CRC, a length
    #: beyond its record, a chunk that does not decompress, a message that does not decode),
    #: False for a complete file or one cut short (a killed writer).
    damaged: bool = False
    #: Why the recorder stopped before the run's end (the log's size cap), "" if it did not; the
    #: file is complete, the run went on unrecorded.
    stopped_early: str = ""
    #: FMU states restored during the run: the steps each superseded are left out.
    rollbacks: int = 0
    #: The FEM bridge strain energy at the largest arrestor deflection, J, as the run printed it
    #: (stored with that row's modal coordinates); None when the log does not hold it (written
    #: before it was stored, without /beam/modes, or rolled back past that row).
    upper_strain_at_peak_deflection: float | None = None
    #: The run's answer with its checks as `beam-impact run` stored it (`quality`, `design`,
    #: `discretisation`, as in `run --json`); None when the log holds none (an FMU's log, or
    #: one written before it was stored) or it does not parse.
    answer: dict | None = None
    #: The support-motion table the run used, as stored in the log (`motion.csv`: a header of
    #: `time` and the support-motion columns given, one line per row); None when the run's
    #: supports did not move, or the log was written before logs carried the table.
    motion_csv: str | None = None
    #: The native reader's envelope buffers (see `envelope`), None when the log holds none.
    envelope_raw: dict | None = None
    #: Where the envelope comes from: "attachment" (`envelope.json`), "rebuilt" (from the recorded
    #: stresses), or None (the log holds neither).
    envelope_source: str | None = None
    #: One line on where the envelope comes from (why it was rebuilt, or why there is none).
    envelope_note: str = ""
    #: The stress stations per group (`lower.bending`, ...: positions, allowable, nodes), None for
    #: a log written before them.
    station_layout: dict | None = None
    #: The step and time (s) of each recorded row of stresses, and the rows (steps x stations, Pa).
    station_steps: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.uint64))
    station_times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    station_values: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    #: The run's fatigue (issue 44), as `beam-impact report LOG --fatigue` has it and with the keys
    #: of `run --json`'s `fatigue` block: from the log's `fatigue.json` (every step of the printed
    #: run), else rebuilt from the `/beam/stations` rows (`source` says which, `note` why it is a
    #: lower bound); None when the log holds neither (then `fatigue_note` says why).
    fatigue: dict | None = None
    #: Why `fatigue` is None ("" otherwise).
    fatigue_note: str = ""

    @property
    def envelope(self):
        """The run's stress envelope (issue 30), as `beam-impact report` has it: a dict with, per
        beam (`lower`: the arrestor from its clamp, `upper`: the bridge from its hinge) and stress
        (`bending`, `shear`), a pandas.DataFrame of one row per station (`position` m, `max` the
        largest |stress| over the run Pa, `time` s when, `allowable` Pa (0: none given),
        `utilisation` max / allowable, NaN without an allowable); `sampled_every` (the envelope
        was evaluated every this many steps); `source` ("attachment" or "rebuilt") and `note`.
        None when the log holds neither the envelope nor stresses at its stations."""
        if self.envelope_raw is None:
            return None
        import pandas as pd

        out = {"sampled_every": int(self.envelope_raw["sampled_every"]), "source": self.envelope_source, "note": self.envelope_note}
        for beam in ("lower", "upper"):
            out[beam] = {}
            for stress in ("bending", "shear"):
                raw = self.envelope_raw[beam][stress]
                columns = {name: np.frombuffer(raw[name], dtype=np.float64) for name in ("position", "max", "time", "allowable")}
                allowable = columns["allowable"]
                with np.errstate(divide="ignore", invalid="ignore"):
                    columns["utilisation"] = np.where(allowable > 0, columns["max"] / np.where(allowable > 0, allowable, 1), np.nan)
                out[beam][stress] = pd.DataFrame(columns)
        return out

    @property
    def stations(self):
        """The stress stations as a pandas.DataFrame, one row per station in the order of
        `station_stresses`' columns: `column` (its name there), `beam` (lower, upper), `stress`
        (bending, shear), `position` (m from the clamp or the hinge), `allowable` (Pa, 0: none),
        `node` (0 at the support; two stations at one node are its two sides). None for a log
        written before logs carried them."""
        if self.station_layout is None:
            return None
        import pandas as pd

        rows = []
        for group in STATION_GROUPS:
            beam, stress = group.split(".")
            raw = self.station_layout[group]
            positions = np.frombuffer(raw["positions"], dtype=np.float64)
            allowable = np.frombuffer(raw["allowable"], dtype=np.float64)
            nodes = np.frombuffer(raw["nodes"], dtype=np.uint64)
            for k in range(len(positions)):
                rows.append((f"{group}.{k}", beam, stress, positions[k], allowable[k], int(nodes[k])))
        return pd.DataFrame(rows, columns=["column", "beam", "stress", "position", "allowable", "node"])

    @property
    def station_stresses(self):
        """The signed stress at every station (`/beam/stations`: the first row at or after every
        1 ms of simulated time, the rows where contact starts or ends and the last row; every
        recorded row of a log of every internal step), as a pandas.DataFrame: `step`, `time`
        (s), then one column per station (Pa; bending M / W sagging positive, shear Q / A_s; named
        as in `stations["column"]`). None when the log holds no such rows."""
        if self.station_layout is None or len(self.station_steps) == 0:
            return None
        import pandas as pd

        names = list(self.stations["column"])
        frame = pd.DataFrame(self.station_values, columns=names)
        frame.insert(0, "time", self.station_times)
        frame.insert(0, "step", self.station_steps)
        return frame

    @property
    def motion(self):
        """The support-motion table the run used (`motion_csv`) as a pandas.DataFrame, one row per
        row of the table: `time` (s, the motion file's time: the run's t = 0 is `motion.time_shift`)
        and the columns the table gave (`upper.hinge_heave`, `lower.clamp_rotation_velocity`, ...;
        m, m/s, m/s2, rad, rad/s, rad/s2); None when the log holds no table. Read by the CLI's
        motion-table parser (the native module); a table it refuses raises LogError."""
        if self.motion_csv is None:
            return None
        import pandas as pd

        from . import _native

        try:
            columns, data = _native.parse_motion(self.motion_csv)
        except ValueError as e:
            raise LogError(_one_line(f"the log's motion table (motion.csv) is refused: {e}", 600)) from None
        values = np.frombuffer(data, dtype=np.float64).reshape(-1, 1 + len(columns))
        return pd.DataFrame(values, columns=["time", *columns])

    def dataframe(self):
        """The step channel as a pandas.DataFrame, one row per internal step (step 0 first)."""
        import pandas as pd

        return pd.DataFrame(self.steps)


class LogError(ValueError):
    """A file that is not a readable beam-impact log: one line naming the file and why."""


def _one_line(text: object, limit: int = 200) -> str:
    t = " ".join(str(text).split())
    return t if len(t) <= limit else t[:limit] + "..."


def load_log(path: str) -> Log:
    """Reads the log at `path` (also the log of a killed run: every complete chunk) with the Rust
    reader. Every file that is not a readable beam-impact log raises `LogError` (a ValueError)
    with one line: a FIFO, a device or a folder is refused before it is read (it would block or
    never end), an unknown log format as `report` refuses it, a damaged file where nothing
    before the damage is a log."""
    from . import _native

    try:
        raw = _native.load_log(os.fspath(path))
    except ValueError as e:
        raise LogError(_one_line(e, 600)) from None
    except MemoryError:
        raise LogError(f"{_one_line(path)}: the log does not fit in memory") from None
    except (TypeError, OSError) as e:
        raise LogError(f"{_one_line(path)}: cannot read the log ({_one_line(e)})") from None
    return _from_native(raw)


def step_columns(buffers: dict) -> dict:
    """The step channel's columns as numpy arrays, from the native module's buffers (a log's
    steps, or a run's kept steps): one name per quantity, as `report --csv`: the FMU's names
    first (`lower.clamp_bending_stress`, `peak.contact.force`), then the former field-path names
    as duplicates (until 0.2.0)."""
    from . import _native

    steps = {}
    for name, data in buffers.items():
        dtype = INTEGER.get(name, np.float64)
        steps[name] = np.frombuffer(data, dtype=np.uint8 if dtype is np.bool_ else dtype).astype(dtype)
    renamed = dict(_native.STEP_RENAMES)
    fields = [*SCALARS, *(f"energy.{n}" for n in ENERGY), *(f"peaks.{n}" for n in PEAKS)]
    return {**{renamed.get(name, name): steps[name] for name in fields}, **{f: steps[f] for f in renamed}}


def _from_native(raw: dict) -> Log:
    """The Log of the native reader's buffers (native-endian, as numpy reads them)."""
    from . import _native

    steps = step_columns(raw["steps"])
    cols = raw["shape_cols"]
    modal_steps = np.frombuffer(raw["modal_steps"], dtype=np.uint64).copy()
    station_steps = np.frombuffer(raw["station_steps"], dtype=np.uint64).copy()
    layout = raw["station_layout"]
    width = 0 if layout is None else sum(len(layout[g]["positions"]) // 8 for g in STATION_GROUPS)
    return Log(
        steps=steps,
        modal_coordinates=np.frombuffer(raw["modal_coordinates"], dtype=np.float64).reshape(len(modal_steps), cols),
        modal_steps=modal_steps,
        modal_times=np.frombuffer(raw["modal_times_ns"], dtype=np.uint64) / 1e9,
        nodal_shapes=np.frombuffer(raw["nodal_shapes"], dtype=np.float64).reshape(raw["shape_rows"], cols),
        lower_nodes=np.frombuffer(raw["lower_nodes"], dtype=np.float64),
        upper_nodes=np.frombuffer(raw["upper_nodes"], dtype=np.float64),
        events=[
            {"start": start, "time": time_ns / 1e9, "time_ns": time_ns, "step": step, "relative_velocity": velocity}
            for start, time_ns, step, velocity in raw["events"]
        ],
        scenario_toml=raw["scenario_toml"],
        metadata=dict(raw["metadata"]),
        log_times=np.frombuffer(raw["log_times"], dtype=np.uint64),
        counts=dict(raw["counts"]),
        complete=raw["complete"],
        problem=raw["problem"],
        damaged=raw["damaged"],
        stopped_early=raw["stopped_early"],
        rollbacks=raw["rollbacks"],
        upper_strain_at_peak_deflection=raw.get("upper_strain_at_peak_deflection"),
        answer=_answer(raw["answer_json"]),
        motion_csv=raw["motion_csv"],
        envelope_raw=raw["envelope"],
        envelope_source=raw["envelope_source"],
        envelope_note=raw["envelope_note"],
        station_layout=None if layout is None else dict(layout),
        station_steps=station_steps,
        station_times=np.frombuffer(raw["station_times_ns"], dtype=np.uint64) / 1e9,
        station_values=np.frombuffer(raw["station_values"], dtype=np.float64).reshape(len(station_steps), width),
        fatigue=None if raw.get("fatigue_json") is None else json.loads(raw["fatigue_json"]),
        fatigue_note=raw.get("fatigue_note", ""),
    )


def _answer(text: str | None) -> dict | None:
    """The stored answer.json, parsed; None when absent or not a JSON object (a log is not trusted)."""
    import json

    if text is None:
        return None
    try:
        doc = json.loads(text)
    except ValueError:
        return None
    return doc if isinstance(doc, dict) else None


def main(argv: list[str]) -> int:
    """Prints a log's contents: `python -m beam_impact log FILE.mcap`."""
    if len(argv) != 2:
        print(__doc__)
        return 2
    try:
        log = load_log(argv[1])
    except LogError as e:
        print(f"beam_impact: {e}", file=sys.stderr)
        return 2
    s = log.steps
    if len(s["step"]) == 0:
        print(f"beam_impact: {argv[1]}: the log holds no step message", file=sys.stderr)
        return 2
    print(f"{argv[1]}: {len(s['step'])} step messages to t = {s['time'][-1]:.6f} s; messages {log.counts}")
    if not log.complete:
        print(f"incomplete log (a killed run?): {log.problem}")
    if log.motion_csv is not None:
        try:
            motion = log.motion
            print(f"support motion: {len(motion)} rows of {', '.join(motion.columns[1:])} (the log's motion.csv)")
        except LogError as e:
            print(f"support motion: {e}")
    peak = int(np.argmax(np.abs(s["lower_tip_deflection"])))
    print(f"largest arrestor end deflection {abs(s['lower_tip_deflection'][peak]):.4f} m at t = {s['time'][peak]:.5f} s")
    for name in ["lower_clamp_bending_stress", "lower_clamp_shear_stress", "upper_contact_bending_stress"]:
        k = int(np.argmax(np.abs(s[name])))
        print(f"largest |{name}| {abs(s[name][k]) / 1e6:.2f} MPa at t = {s['time'][k]:.5f} s")
    envelope = log.envelope
    if envelope is None:
        print(f"stress envelope: {log.envelope_note}")
    else:
        print(f"stress envelope ({envelope['source']}):")
        for beam, name in [("lower", "arrestor"), ("upper", "bridge")]:
            for stress in ["bending", "shear"]:
                frame = envelope[beam][stress]
                if len(frame):
                    k = int(np.argmax(frame["max"]))
                    print(
                        f"  {name} {stress}: {frame['max'][k] / 1e6:.2f} MPa at x = {frame['position'][k]:.3f} m, "
                        f"t = {frame['time'][k]:.5f} s"
                    )
    starts = [e["time"] for e in log.events if e["start"]]
    print(f"{len(log.events)} contact events, first contact at t = {starts[0] if starts else float('nan'):.6f} s")
    # The deflected shape at the largest deflection, from the modal coordinates of that row (its
    # step and time: a step's dense-output samples share its number; a log without that row's own
    # message: its step's last).
    rows = np.flatnonzero(log.modal_steps == s["step"][peak])
    own = rows[log.modal_times[rows] == s["time"][peak]]
    rows = own if own.size else rows
    if rows.size:
        w = log.nodal_shapes @ log.modal_coordinates[rows[-1]]
        print(f"bridge nodal deflections at the largest arrestor deflection, m: {np.array2string(w[len(log.lower_nodes):], precision=3)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
