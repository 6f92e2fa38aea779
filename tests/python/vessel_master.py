"""The vessel example's co-simulation master, shared by tests/python/test_vessel.py and
docs/plot_vessel_phase.py (issue 17, item 4).

VesselMotion (fmu/vessel/vessel_motion.c, an FMI 2 co-simulation FMU built here with gcc
against fmu/vessel/fmi2_abi.h) gives the heave and pitch of a vessel in a regular wave,
projected onto BeamImpact's two supports; BeamImpact's support reactions go back to it as the deck
load. A fixed-step master (fmpy's low-level FMU2Slave, h = 1 ms by default) runs both; see
test_vessel.py's docstring for the order of the calls and why it has no algebraic loop.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
import time
import zipfile
from ctypes import byref
from dataclasses import dataclass, field
from pathlib import Path

import fmpy
import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    fmi2OK,
    fmi2True,
)
from fmpy.logging import addLoggerProxy

ROOT = Path(__file__).resolve().parents[2]
VESSEL = ROOT / "fmu" / "vessel"
FMU_DIR = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", str(ROOT / "target" / "fmu")))

STEP = 1e-3  # s, communication step
STOP = 3.0  # s, the scenario's full duration: the run starts at the impact

# The nine support motions, in BeamImpact's order; VesselMotion's outputs have the same names.
MOTION = [
    "upper.hinge_heave", "upper.hinge_heave_velocity", "upper.hinge_heave_acceleration",
    "lower.clamp_heave", "lower.clamp_heave_velocity", "lower.clamp_heave_acceleration",
    "lower.clamp_rotation", "lower.clamp_rotation_velocity", "lower.clamp_rotation_acceleration",
]
VESSEL_OUTPUTS = MOTION + ["wave.elevation", "vessel.heave", "vessel.pitch", "deck.force", "deck.pitch_moment",
                           "deck.heave_acceleration", "deck.pitch_acceleration"]
# BeamImpact -> VesselMotion: the support reactions (the support's force and moment on the beam).
REACTIONS = {"hinge_force": "upper.hinge_reaction_force", "clamp_force": "lower.clamp_reaction_force",
             "clamp_moment": "lower.clamp_reaction_moment"}
# BeamImpact's outputs recorded at every communication point (those its description has).
BEAM_OUTPUTS = list(REACTIONS.values()) + [
    "upper.tip_position", "lower.tip_position", "upper.tip_deflection", "lower.tip_deflection",
    "upper.contact_deflection", "contact.force", "lower.clamp_bending_stress", "lower.clamp_shear_stress",
    "upper.contact_bending_stress", "energy.residual", "energy.external_work", "energy.strain",
    "energy.kinetic", "energy.damping_dissipation",
]
SCENARIO = ["lower.length", "lower.mass", "lower.tip_mass", "upper.length", "contact_position", "contact.area", "contact.length",
            "contact.elastic_modulus", "upper.mass", "gravity", "drop_height", "lower.allowable_bending_stress",
            "lower.allowable_shear_stress", "upper.allowable_bending_stress"]
PEAKS = ["peak.lower.clamp_bending_stress", "peak.upper.contact_bending_stress", "peak.lower.clamp_shear_stress",
         "peak.contact.force"]


def beam_fmu(fmu_dir: Path = FMU_DIR) -> Path:
    path = Path(fmu_dir) / "fmi2" / "BeamImpact.fmu"
    if not path.exists():
        raise FileNotFoundError(f"{path} not found: run `beam-impact pack` or set BEAM_IMPACT_FMU_DIR")
    return path


def build_vessel_fmu(out_dir: Path, gcc: str | None = None) -> tuple[Path, str]:
    """Builds VesselMotion.fmu in out_dir with gcc (-Wall -Wextra): the C file and its FMI 2
    types (fmu/vessel/fmi2_abi.h), VesselMotion.xml as the modelDescription. Returns the FMU and
    gcc's stderr (empty when the file compiles clean); raises RuntimeError when gcc fails."""
    gcc = gcc or shutil.which("gcc")
    if gcc is None:
        raise RuntimeError("gcc not found: the vessel example builds its FMU from fmu/vessel/vessel_motion.c")
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    library = out_dir / "VesselMotion.so"
    compiled = subprocess.run(
        [gcc, "-shared", "-fPIC", "-O2", "-std=c99", "-Wall", "-Wextra", "-fvisibility=hidden",
         str(VESSEL / "vessel_motion.c"), "-o", str(library), "-lm"],
        capture_output=True, text=True,
    )
    if compiled.returncode != 0:
        raise RuntimeError(f"gcc failed:\n{compiled.stderr}")
    fmu = out_dir / "VesselMotion.fmu"
    with zipfile.ZipFile(fmu, "w", zipfile.ZIP_DEFLATED) as z:
        z.write(VESSEL / "VesselMotion.xml", "modelDescription.xml")
        z.write(library, "binaries/linux64/VesselMotion.so")
    return fmu, compiled.stderr


# Every message of every instance, (instanceName, status, category, message). fmpy's native proxy
# (addLoggerProxy) formats the printf-style message before it reaches Python, but it keeps ONE
# logger per process, the last registered, and swaps the struct's logger for itself. So every
# instance shares CALLBACKS (alive as long as the process), and `listen()` registers the recorder
# again before each run: anything else (tests/python/conftest.py restores a printing logger after
# every test) may have taken the slot since.
MESSAGES: list[tuple[str, int, str, str]] = []


def _record(env, instance, status, category, message):
    MESSAGES.append((instance.decode(), status, category.decode(), message.decode()))


_RECORD = fmi2CallbackLoggerTYPE(_record)
CALLBACKS = fmi2CallbackFunctions()
CALLBACKS.allocateMemory = fmi2CallbackAllocateMemoryTYPE(fmpy.calloc)
CALLBACKS.freeMemory = fmi2CallbackFreeMemoryTYPE(fmpy.free)


def listen() -> None:
    """Makes the recorder the process's FMI 2 logger (see MESSAGES)."""
    CALLBACKS.logger = _RECORD
    addLoggerProxy(byref(CALLBACKS))


class Slave:
    """One FMI 2 co-simulation instance through fmpy's low-level API; its log messages are those
    of MESSAGES with its instance name, and do_step returns fmi2DoStep's status."""

    def __init__(self, path: Path, name: str, unzip_dir: Path):
        self.name = name
        self.md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.type = {v.name: v.type for v in self.md.modelVariables}
        self.first_message = len(MESSAGES)
        self.fmu = FMU2Slave(guid=self.md.guid, modelIdentifier=self.md.coSimulation.modelIdentifier,
                             unzipDirectory=extract(str(path), str(unzip_dir)), instanceName=name)
        listen()
        self.fmu.instantiate(callbacks=CALLBACKS)

    @property
    def messages(self) -> list[tuple[int, str, str]]:
        return [(status, category, message) for instance, status, category, message in MESSAGES[self.first_message:]
                if instance == self.name]

    def has(self, name: str) -> bool:
        return name in self.vr

    def get(self, *names: str) -> list[float]:
        return self.fmu.getReal([self.vr[n] for n in names])

    def get_bool(self, name: str) -> bool:
        return bool(self.fmu.getBoolean([self.vr[name]])[0])

    def set(self, **values: float) -> None:
        self.set_values(values)

    def set_values(self, values: dict) -> None:
        """Sets parameters or inputs by name, each through the setter of its type."""
        by_type: dict[str, dict] = {}
        for name, value in values.items():
            by_type.setdefault(self.type[name], {})[name] = value
        for kind, group in by_type.items():
            setter = {"Real": self.fmu.setReal, "Boolean": self.fmu.setBoolean, "Integer": self.fmu.setInteger,
                      "String": self.fmu.setString}[kind]
            setter([self.vr[n] for n in group], list(group.values()))

    def do_step(self, t: float, h: float) -> int:
        """fmi2DoStep's status (fmpy raises on Discard and worse, returns OK and Warning)."""
        return self.fmu.fmi2DoStep(self.fmu.component, t, h, fmi2True)

    def close(self) -> None:
        self.fmu.terminate()
        self.fmu.freeInstance()


@dataclass
class Run:
    """One master run: per communication point t_n (n = 0..N) the vessel's and the beam's outputs
    (arrays by name), the values the master set on BeamImpact, the doStep statuses, the running
    peaks at the end, BeamImpact's scenario parameters, its verdict and the log messages."""

    time: np.ndarray
    vessel: dict[str, np.ndarray] = field(default_factory=dict)
    beam: dict[str, np.ndarray] = field(default_factory=dict)
    sent: dict[str, np.ndarray] = field(default_factory=dict)
    beam_statuses: list[int] = field(default_factory=list)
    vessel_statuses: list[int] = field(default_factory=list)
    peaks: dict[str, float] = field(default_factory=dict)
    scenario: dict[str, float] = field(default_factory=dict)
    trusted: bool | None = None
    parameters: dict[str, float] = field(default_factory=dict)
    beam_messages: list = field(default_factory=list)
    vessel_messages: list = field(default_factory=list)
    wall: float = 0.0


def run(beam_path: Path, work: Path, name: str, vessel_path: Path | None = None,
        vessel_parameters: dict | None = None, stop: float = STOP, step: float = STEP,
        positions_only: bool = False) -> Run:
    """The master loop. Without a vessel FMU BeamImpact's supports stay fixed (its motion inputs
    keep their default 0). positions_only sends the support positions with their rates left at 0
    (a master that does not know the rates): BeamImpact must warn."""
    work = Path(work).resolve()  # fmpy turns the unzip directory into a file URI: absolute
    steps = round(stop / step)
    vessel = None
    motion = [0.0] * len(MOTION)
    if vessel_path is not None:
        vessel = Slave(vessel_path, f"{name}-vessel", work / f"unzip-{name}-vessel")
        vessel.fmu.setupExperiment(startTime=0.0, stopTime=stop)
        vessel.fmu.enterInitializationMode()
        vessel.set_values(vessel_parameters or {})
        vessel.fmu.exitInitializationMode()
        motion = vessel.get(*MOTION)

    def sent(values: list[float]) -> list[float]:
        if not positions_only:
            return values
        return [v if k % 3 == 0 else 0.0 for k, v in enumerate(values)]

    beam = Slave(beam_path, name, work / f"unzip-{name}")
    beam.fmu.setupExperiment(startTime=0.0, stopTime=stop)
    beam.fmu.enterInitializationMode()
    beam.fmu.setString([beam.vr["log.path"]], [""])
    moving = vessel is not None and all(beam.has(n) for n in MOTION)
    if vessel is not None and not moving:
        raise RuntimeError(f"{beam_path} has no support-motion inputs ({', '.join(MOTION)})")
    if moving:
        # The motion at t = 0 in initialization mode: BeamImpact's initial state (the bridge's
        # fall, the arrestor's rest, the beams touching) is computed under it.
        beam.set_values(dict(zip(MOTION, sent(motion))))
    beam.fmu.exitInitializationMode()

    beam_names = [n for n in BEAM_OUTPUTS if beam.has(n)]
    rows_vessel, rows_beam, rows_sent = [], [], []
    result = Run(time=np.arange(steps + 1) * step)
    started = time.perf_counter()
    for n in range(steps + 1):
        t = n * step
        if vessel is not None:
            motion = sent(vessel.get(*MOTION))
            beam.set_values(dict(zip(MOTION, motion)))  # the motion from t_n on
            rows_sent.append(motion)
        outputs = beam.get(*beam_names)  # at t_n, after the inputs at t_n are set
        rows_beam.append(outputs)
        if vessel is not None:
            by_name = dict(zip(beam_names, outputs))
            vessel.set_values({k: by_name[v] for k, v in REACTIONS.items()})
            rows_vessel.append(vessel.get(*VESSEL_OUTPUTS))  # the motion and the deck load at t_n
        if n == steps:
            break
        if vessel is not None:
            result.vessel_statuses.append(vessel.do_step(t, step))
        result.beam_statuses.append(beam.do_step(t, step))
    result.wall = time.perf_counter() - started

    result.beam = {k: np.array(v) for k, v in zip(beam_names, np.array(rows_beam).T)}
    if vessel is not None:
        result.vessel = {k: np.array(v) for k, v in zip(VESSEL_OUTPUTS, np.array(rows_vessel).T)}
        result.sent = {k: np.array(v) for k, v in zip(MOTION, np.array(rows_sent).T)}
        result.parameters = dict(zip(
            [v.name for v in vessel.md.modelVariables if v.causality in ("parameter", "calculatedParameter")
             and v.type == "Real"],
            vessel.get(*[v.name for v in vessel.md.modelVariables
                         if v.causality in ("parameter", "calculatedParameter") and v.type == "Real"])))
    result.peaks = dict(zip(PEAKS, beam.get(*PEAKS)))
    result.scenario = dict(zip(SCENARIO, beam.get(*SCENARIO)))
    if beam.has("quality.trusted"):
        result.trusted = beam.get_bool("quality.trusted")
    result.beam_messages = beam.messages
    beam.close()
    if vessel is not None:
        result.vessel_messages = vessel.messages
        vessel.close()
    return result


def closing_speed(run: Run) -> float:
    """The speed at which the supports close the gap between the bridge's contact point and the
    arrestor's end at t = 0, m/s (positive: they add to the impact): -(h' - c' - L theta'), the
    rate of BeamImpact's support offset h - c - L theta with its sign turned."""
    s = run.sent
    length = run.scenario["lower.length"]
    return -(s["upper.hinge_heave_velocity"][0] - s["lower.clamp_heave_velocity"][0]
             - length * s["lower.clamp_rotation_velocity"][0])


def phase_sweep(beam_path: Path, vessel_path: Path, phases, work: Path | None = None,
                vessel_parameters: dict | None = None, stop: float = STOP) -> list[Run]:
    """One master run per wave phase at the impact (rad)."""
    with tempfile.TemporaryDirectory() as scratch:
        base = Path(work) if work is not None else Path(scratch)
        return [run(beam_path, base, f"phase{k}", vessel_path,
                    dict(vessel_parameters or {}, **{"wave.phase": float(phase)}), stop=stop)
                for k, phase in enumerate(phases)]
