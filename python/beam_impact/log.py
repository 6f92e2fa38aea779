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
    log.stopped_early       why the log ended before the run (its size cap), "" if it did not
    log.rollbacks           FMU states restored: the steps they superseded are left out, as `report` does

The file is read front to back with the `mcap` package's StreamReader (CRCs checked), not through
the summary at its end: the log of a killed writer has every complete chunk and no summary, and
loads up to its last complete chunk, with `complete` False and `problem` saying where it ends.
Every channel carries its protobuf schema (a FileDescriptorSet), so `mcap-protobuf-support`
decodes it without generated code. Step 0 is the initial state.

Both log formats load. Format 2 (metadata `log_format` = 2) keeps the modal coordinates on
`/beam/modes` (every 1 ms, at contact changes, at the arrestor's peak deflection and at the last
step), leaves a step's `peaks` out when they equal the previous step's (carried forward here) and
leaves out `time` (= time_ns / 1e9, computed here). Format 1 had float32 coordinates in every step.
"""

from __future__ import annotations

import bisect
import sys
from dataclasses import dataclass, field

import numpy as np

STEP_TOPIC = "/beam/step"
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
    #: Why the reading stopped early ("" for a complete file).
    problem: str = ""
    #: Why the recorder stopped before the run's end (the log's size cap), "" if it did not; the
    #: file is complete, the run went on unrecorded.
    stopped_early: str = ""
    #: FMU states restored during the run: the steps each superseded are left out.
    rollbacks: int = 0

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
    """Reads the log at `path` (also the log of a killed run: every complete chunk). Every file
    that is not a readable beam-impact log raises `LogError` (a ValueError) with one line: a
    FIFO, a device or a folder is refused before it is opened (it would block or never end), an
    unknown log format is refused as `report` refuses it, and any failure of the decoders is
    reported as the file's problem rather than as their own exception types."""
    import os
    import stat

    try:
        mode = os.stat(path).st_mode
    except OSError as e:
        raise LogError(f"{_one_line(path)}: cannot read the log ({_one_line(e.strerror or e)})") from None
    if not stat.S_ISREG(mode):
        raise LogError(f"{_one_line(path)}: not a regular file (a FIFO, a device or a folder is not a log)")
    try:
        log = _load_log(path)
    except LogError:
        raise
    except MemoryError:
        raise LogError(f"{_one_line(path)}: the log does not fit in memory") from None
    except Exception as e:  # the decoders' own types (protobuf, KeyError, ...): one type for callers
        raise LogError(f"{_one_line(path)}: not a readable beam-impact log ({type(e).__name__}: {_one_line(e)})") \
            from None
    fmt = log.metadata.get("log_format", "1")
    if fmt not in ("1", "2"):
        raise LogError(f"{_one_line(path)}: log format {_one_line(fmt, 20)!r} is not one this reader knows (1 or 2)")
    return log


def _load_log(path: str) -> Log:
    from mcap.records import Channel, DataEnd, Footer, Message, Metadata, Schema
    from mcap.stream_reader import StreamReader
    from mcap_protobuf.decoder import DecoderFactory

    columns: dict[str, list] = {name: [] for name in SCALARS}
    columns.update({f"energy.{n}": [] for n in ENERGY})
    columns.update({f"peaks.{n}": [] for n in PEAKS})
    coordinates: list = []
    modal_steps: list[int] = []
    modal_times: list[float] = []
    rollbacks = 0
    stopped_early = ""
    events: list[dict] = []
    log_times: list[int] = []
    counts: dict[str, int] = {}
    metadata: dict[str, str] = {}
    schemas: dict[int, Schema] = {}
    channels: dict[int, Channel] = {}
    decoders: dict[int, object] = {}
    factory = DecoderFactory()
    model = None
    complete, problem = False, ""
    with open(path, "rb") as f:
        records = iter(StreamReader(f, validate_crcs=True).records)
        while True:
            try:
                record = next(records)
            except StopIteration:
                break
            except Exception as e:  # the end of a killed run's file: keep every complete chunk
                complete, problem = False, f"{type(e).__name__}: {e}".strip()
                break
            if isinstance(record, Schema):
                schemas[record.id] = record
            elif isinstance(record, Channel):
                channels[record.id] = record
            elif isinstance(record, Metadata):
                if record.name == "scenario":
                    metadata = dict(record.metadata)
            elif isinstance(record, (DataEnd, Footer)):
                complete = True
            elif isinstance(record, Message):
                channel = channels[record.channel_id]
                decode = decoders.get(record.channel_id)
                if decode is None:
                    decode = factory.decoder_for(channel.message_encoding, schemas.get(channel.schema_id))
                    if decode is None:
                        raise LogError(f"{path}: channel {_one_line(channel.topic)} is not protobuf")
                    decoders[record.channel_id] = decode
                log_times.append(record.log_time)
                counts[channel.topic] = counts.get(channel.topic, 0) + 1
                proto = decode(record.data)
                if channel.topic == STEP_TOPIC:
                    if columns["step"] and proto.step <= columns["step"][-1]:
                        # A rollback (an FMU state restored): the steps from this one on are
                        # superseded, and so are the events and modal coordinates after it.
                        keep = bisect.bisect_left(columns["step"], proto.step)
                        for column in columns.values():
                            del column[keep:]
                        events[:] = [e for e in events if e["step"] <= proto.step]
                        # (Not sorted by step: a peak's coordinates follow later steps.)
                        rows = [k for k, step in enumerate(modal_steps) if step < proto.step]
                        coordinates[:] = [coordinates[k] for k in rows]
                        modal_times[:] = [modal_times[k] for k in rows]
                        modal_steps[:] = [modal_steps[k] for k in rows]
                        rollbacks += 1
                    for name in SCALARS:
                        columns[name].append(getattr(proto, name))
                    # Format 2 leaves out the time in seconds: it is time_ns / 1e9.
                    columns["time"][-1] = proto.time_ns / 1e9
                    for name in ENERGY:
                        columns[f"energy.{name}"].append(getattr(proto.energy, name))
                    # Format 2 leaves out peaks equal to the previous step's.
                    carried = not proto.HasField("peaks") and len(columns["peaks.contact_force"]) > 0
                    for name in PEAKS:
                        column = columns[f"peaks.{name}"]
                        column.append(column[-1] if carried else getattr(proto.peaks, name))
                    if len(proto.modal_coordinates) > 0:  # format 1
                        coordinates.append(np.asarray(proto.modal_coordinates, dtype=np.float64))
                        modal_steps.append(proto.step)
                        modal_times.append(proto.time_ns / 1e9)
                elif channel.topic == MODES_TOPIC:
                    coordinates.append(np.asarray(proto.coordinates, dtype=np.float64))
                    modal_steps.append(proto.step)
                    modal_times.append(proto.time_ns / 1e9)
                elif channel.topic == CONTACT_TOPIC:
                    events.append(
                        {
                            "start": proto.start,
                            "time": proto.time,
                            "time_ns": proto.time_ns,
                            "step": proto.step,
                            "relative_velocity": proto.relative_velocity,
                        }
                    )
                elif channel.topic == MODEL_TOPIC:
                    model = proto
                elif channel.topic == LOG_TOPIC and "reached its size cap" in proto.message:
                    stopped_early = proto.message
    if not complete and not problem:
        problem = "the file ends before its summary and footer (the writer never finished)"
    if model is None:
        raise LogError(f"{path}: no {MODEL_TOPIC} message" + (f" ({_one_line(problem)})" if problem else ""))
    steps = {name: np.asarray(values, dtype=INTEGER.get(name, np.float64)) for name, values in columns.items()}
    shapes = np.asarray(model.nodal_shapes, dtype=np.float64).reshape(model.shape_rows, model.shape_cols)
    return Log(
        steps=steps,
        modal_coordinates=np.asarray(coordinates, dtype=np.float64).reshape(len(coordinates), model.shape_cols),
        modal_steps=np.asarray(modal_steps, dtype=np.uint64),
        modal_times=np.asarray(modal_times, dtype=np.float64),
        nodal_shapes=shapes,
        lower_nodes=np.asarray(model.lower_nodes),
        upper_nodes=np.asarray(model.upper_nodes),
        events=events,
        scenario_toml=model.scenario_toml,
        metadata=metadata,
        log_times=np.asarray(log_times, dtype=np.uint64),
        counts=counts,
        complete=complete,
        problem=problem,
        stopped_early=stopped_early,
        rollbacks=rollbacks,
    )


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
    peak = int(np.argmax(np.abs(s["lower_tip_deflection"])))
    print(f"largest arrestor end deflection {abs(s['lower_tip_deflection'][peak]):.4f} m at t = {s['time'][peak]:.5f} s")
    for name in ["lower_clamp_bending_stress", "lower_clamp_shear_stress", "upper_contact_bending_stress"]:
        k = int(np.argmax(np.abs(s[name])))
        print(f"largest |{name}| {abs(s[name][k]) / 1e6:.2f} MPa at t = {s['time'][k]:.5f} s")
    starts = [e["time"] for e in log.events if e["start"]]
    print(f"{len(log.events)} contact events, first contact at t = {starts[0] if starts else float('nan'):.6f} s")
    # The deflected shape at the largest deflection, from the modal coordinates of that step.
    rows = np.flatnonzero(log.modal_steps == s["step"][peak])
    if rows.size:
        w = log.nodal_shapes @ log.modal_coordinates[rows[-1]]
        print(f"bridge nodal deflections at the largest arrestor deflection, m: {np.array2string(w[len(log.lower_nodes):], precision=3)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
