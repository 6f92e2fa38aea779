"""VesselMotion in an irregular sea (issue 42): the vessel FMU's `sea.*` parameters and its RAO
table `resources/raos.csv` give the record of docs/sea-states.md, the one `beam-impact sea` writes.

The FMU is the one `beam-impact pack --ssp` packs into GangwayOnVessel.ssp (tests/run_all.sh packs
it into target/fmu), with the example vessel's RAO table (examples/vessel-sea-raos.csv) as its
resource; `sea.significant_wave_height` above 0 switches it from the regular wave (its default,
0: tests/python/test_vessel.py) to the irregular sea. Checks (each can fail):

- Its ten outputs (the elevation at the motion reference point and the nine support motions) at
  the communication points equal `beam-impact sea`'s columns at the same record times, for
  examples/vessel-sea.toml's sea and for a sea that exercises the rest of the spec (an other
  seed, Pierson-Moskowitz, fewer components over a given range, a heading between the file's and
  on its mirrored side, deck points off the centreline with the arrestor athwartships so that
  roll enters, a time shift). Tolerance 1e-12 of each column's largest |value|: the same
  operations in C (glibc's libm) and Rust (the libm crate), whose sin, cos, exp and pow differ by
  at most an ulp; summed over 1000 components that is a few 1e-15 of the largest term. Measured
  1.4e-14 over 60 s (the record's time read at t_n + h in the FMU, n h in the CLI, adds w h 1e-16).
  A component drawn out of order, a bin off by one, an RAO interpolated in amplitude and phase
  rather than in its complex value or a mirrored heading with the wrong signs would move the
  columns by percents.
- `pack --ssp --scenario` with a [sea] naming a VERES .re1 (the MSS supply vessel's, when it lies
  beside the repository): the SSD's bindings and the table written as our CSV give the same
  columns as `beam-impact sea` reading the .re1 (6.6e-15 measured).
- One regular-wave case equal to today's vessel FMU: a one-component sea over constant RAOs is a
  regular wave; the irregular and the regular branch give the same nine outputs to 1e-12.
- A hostile RAO resource (NaN, a missing column, a file over the size limit, a folder) fails
  fmi2ExitInitializationMode with one line naming it; the FMU never crashes. So does a sea.*
  parameter out of its range (the ranges of the [sea] fields; a components' range holding less than
  95 % of the variance with the number beam-impact gives).

About 10 s (three `beam-impact sea` records, one `pack --ssp`, six FMU runs of 12 000 steps at most).
"""

from __future__ import annotations

import math
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import vessel_master as vm

ROOT = Path(__file__).resolve().parents[2]
SSP = vm.FMU_DIR / "GangwayOnVessel.ssp"
EXAMPLE = ROOT / "examples" / "vessel-sea.toml"
RAOS = ROOT / "examples" / "vessel-sea-raos.csv"
COLUMNS = {"wave.elevation": "wave_elevation", **{m: m for m in vm.MOTION}}
RTOL = 1e-12  # see the module docstring
DT = 0.005  # the record's default sample interval: `beam-impact sea`'s grid


def binary() -> str:
    path = os.environ.get("BEAM_IMPACT_BIN", str(ROOT / "target" / "release" / "beam-impact"))
    assert Path(path).exists(), f"{path} not found: build with `cargo build --release` or set BEAM_IMPACT_BIN"
    return path


@pytest.fixture(scope="module")
def vessel_fmu(tmp_path_factory) -> Path:
    """The VesselMotion FMU inside GangwayOnVessel.ssp."""
    if not SSP.exists():
        pytest.fail(f"{SSP} not found: run `beam-impact pack --ssp --out {SSP.parent}` (tests/run_all.sh does)")
    out = tmp_path_factory.mktemp("vessel-sea")
    with zipfile.ZipFile(SSP) as z:
        z.extract("resources/VesselMotion.fmu", out)
    fmu = out / "resources" / "VesselMotion.fmu"
    with zipfile.ZipFile(fmu) as z:
        assert z.read("resources/raos.csv") == RAOS.read_bytes(), "the example vessel's RAO table"
    return fmu


def with_raos(fmu: Path, out: Path, data: bytes | None, folder: bool = False) -> Path:
    """A copy of the FMU whose resources/raos.csv is `data` (or a folder)."""
    with zipfile.ZipFile(fmu) as zin, zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zout:
        for info in zin.infolist():
            if info.filename != "resources/raos.csv":
                zout.writestr(info, zin.read(info.filename))
        if folder:
            zout.writestr("resources/raos.csv/", b"")
        elif data is not None:
            zout.writestr("resources/raos.csv", data)
    return out


def sea_record(tmp_path: Path, scenario: Path, duration: float) -> pd.DataFrame:
    out = tmp_path / "sea.csv"
    done = subprocess.run([binary(), "sea", str(scenario), "--duration", str(duration), "--out", str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return pd.read_csv(out, dtype=float, engine="python")  # the python engine parses floats to the bit


def simulate(fmu: Path, work: Path, parameters: dict, steps: int, step: float = DT):
    """VesselMotion alone over `steps` communication steps; its outputs at every t_n and its
    messages. Raises on an error status (fmpy)."""
    vm.listen()
    vessel = vm.Slave(fmu, work.name, work / "unzip")
    vessel.fmu.setupExperiment(startTime=0.0)
    vessel.fmu.enterInitializationMode()
    vessel.set_values(parameters)
    vessel.fmu.exitInitializationMode()
    names = list(COLUMNS) + ["vessel.heave", "vessel.pitch"]
    rows = []
    for n in range(steps + 1):
        rows.append(vessel.get(*names))
        if n < steps:
            vessel.do_step(n * step, step)
    messages = vessel.messages
    vessel.close()
    return {k: np.array(v) for k, v in zip(names, np.array(rows).T)}, messages


def assert_columns_equal(got: dict, record: pd.DataFrame, first_row: int = 0) -> float:
    worst = 0.0
    for output, column in COLUMNS.items():
        want = record[column].to_numpy()[first_row:first_row + len(got[output])]
        scale = np.abs(want).max()
        assert scale > 0, column
        error = np.abs(got[output] - want).max() / scale
        worst = max(worst, error)
        assert error <= RTOL, (output, error)
    return worst


def test_the_example_sea_equals_beam_impact_sea(vessel_fmu, tmp_path):
    """examples/vessel-sea.toml's sea: the FMU's defaults are the example's but Hs (0: regular)."""
    record = sea_record(tmp_path, EXAMPLE, 60.0)
    got, messages = simulate(vessel_fmu, tmp_path / "example", {"sea.significant_wave_height": 2.5}, len(record) - 1)
    assert not messages, messages
    worst = assert_columns_equal(got, record)
    print(f"largest difference: {worst:.2e} of the column's largest value")
    # The record moves the supports: the clamp 15 m forward heaves by tens of cm.
    assert np.abs(got["lower.clamp_heave"]).max() > 0.3


OTHER_SEA = {
    "significant_wave_height": 1.8, "peak_period": 9.5, "spectrum": "pierson-moskowitz", "heading": 200.0,
    "seed": 424242, "components": 300, "frequency_min": 0.35, "frequency_max": 2.6, "time_shift": 0.0,
    "hinge_point": [-12.0, 4.0, 8.0], "clamp_point": [14.0, -3.0, 8.0], "arrestor_direction": 100.0,
}


def test_an_other_sea_equals_beam_impact_sea(vessel_fmu, tmp_path):
    """Every sea.* parameter away from the example's; heading 200 deg lies between 195 and 210 deg,
    the mirrored columns of 165 and 150 deg (the file gives 0 to 180), the deck points off the centreline and
    the arrestor nearly athwartships make roll move the supports; a time shift of 10 s."""
    s = OTHER_SEA
    shutil.copy(RAOS, tmp_path / "raos.csv")
    lines = ["duration = 3.0", "", "[sea]", 'raos = "raos.csv"']
    for k, v in s.items():
        lines.append(f"{k} = {v!r}" if not isinstance(v, str) else f'{k} = "{v}"')
    (tmp_path / "sea.toml").write_text("\n".join(lines).replace("'", '"') + "\n")
    record = sea_record(tmp_path, tmp_path / "sea.toml", 40.0)
    shift_rows = 2000  # 10 s
    parameters = {
        "sea.significant_wave_height": s["significant_wave_height"], "sea.peak_period": s["peak_period"],
        "sea.spectrum": 1.0, "sea.heading": s["heading"], "sea.seed": float(s["seed"]),
        "sea.components": float(s["components"]), "sea.frequency_min": s["frequency_min"],
        "sea.frequency_max": s["frequency_max"], "sea.time_shift": shift_rows * DT,
        "hinge.x": s["hinge_point"][0], "hinge.y": s["hinge_point"][1], "clamp.x": s["clamp_point"][0],
        "clamp.y": s["clamp_point"][1], "sea.arrestor_direction": s["arrestor_direction"],
    }
    got, messages = simulate(vessel_fmu, tmp_path / "other", parameters, len(record) - 1 - shift_rows)
    assert not messages, messages
    worst = assert_columns_equal(got, record, first_row=shift_rows)
    print(f"largest difference: {worst:.2e} of the column's largest value")
    # Roll matters here: the same sea with the deck points on the centreline moves the clamp's
    # rotation by more than the tolerance by far.
    centre, _ = simulate(vessel_fmu, tmp_path / "centre", dict(parameters, **{"hinge.y": 0.0, "clamp.y": 0.0}), 200)
    assert np.abs(centre["lower.clamp_heave"] - got["lower.clamp_heave"][:201]).max() > 1e-3


def rao_row(w: float, heave: tuple[float, float], pitch: tuple[float, float]) -> str:
    return f"{w!r},180.0,0,0,0,0,{heave[0]!r},{heave[1]!r},0,0,{pitch[0]!r},{pitch[1]!r},0,0"


def test_a_one_component_sea_is_todays_regular_wave(vessel_fmu, tmp_path):
    """One regular-wave case equal to today's vessel FMU (issue 42, item 4): one component of
    frequency w, amplitude a and phase phi over RAOs constant in frequency (heave |H_z| at eps_z,
    pitch |H_theta| k at eps_theta with k = w^2 / g) is the regular wave of period 2 pi / w,
    amplitude a and phase phi with those RAOs. The component is drawn here from the spec
    (scripts/vessel_raos/reference_record.py, splitmix64), the regular wave's parameters set from
    it. Tolerance 1e-12 of each output's amplitude: the two branches round differently (cos(psi +
    eps) against Re(a e^(i phi) H e^(i w t)), omega = 2 pi / (2 pi / w)), by a few ulp."""
    sys.path.insert(0, str(ROOT / "scripts" / "vessel_raos"))
    import reference_record as ref

    hs, tp, seed, lo, hi, g = 2.0, 8.0, 99, 0.3, 3.0, 9.81
    (w,), (a,), (phi,), _ = ref.components(hs, tp, "pierson-moskowitz", None, 1, lo, hi, seed)
    heave, pitch = (0.9, -0.3), (0.8, -1.9)  # today's defaults: |H|, eps (rad); pitch per unit slope
    k = w * w / g
    table = ["frequency,heading,surge,surge_phase,sway,sway_phase,heave,heave_phase,roll,roll_phase,pitch,"
             "pitch_phase,yaw,yaw_phase"]
    for f in (lo, hi):
        table.append(rao_row(f, (heave[0], math.degrees(heave[1])),
                             (math.degrees(pitch[0] * k), math.degrees(pitch[1]))))
    fmu = with_raos(vessel_fmu, tmp_path / "regular.fmu", ("\n".join(table) + "\n").encode())
    steps = 2000
    irregular, messages = simulate(fmu, tmp_path / "irregular", {
        "sea.significant_wave_height": hs, "sea.peak_period": tp, "sea.spectrum": 1.0, "sea.seed": float(seed),
        "sea.components": 1.0, "sea.frequency_min": lo, "sea.frequency_max": hi}, steps)
    assert not messages, messages
    regular, messages = simulate(fmu, tmp_path / "regular", {
        "wave.amplitude": a, "wave.period": 2 * math.pi / w, "wave.phase": phi, "gravity": g,
        "heave.rao": heave[0], "heave.phase": heave[1], "pitch.rao": pitch[0], "pitch.phase": pitch[1]}, steps)
    assert not messages, messages
    for name in list(COLUMNS) + ["vessel.heave", "vessel.pitch"]:
        scale = np.abs(regular[name]).max()
        assert scale > 0, name
        assert np.abs(irregular[name] - regular[name]).max() <= RTOL * scale, name


HOSTILE = {
    "nan": (b"frequency,heading,surge,surge_phase,sway,sway_phase,heave,heave_phase,roll,roll_phase,pitch,"
            b"pitch_phase,yaw,yaw_phase\n0.5,180,0,0,0,0,NaN,0,0,0,0,0,0,0\n", "`heave` is not a number"),
    "no_header": (b"0.5,180,0,0,0,0,1,0,0,0,0,0,0,0\n", "is not an RAO CSV header"),
    "huge": (b"#" * (33 << 20), "larger than"),
    "empty": (b"", "no header line"),
    "one_frequency": (b"frequency,heading,surge,surge_phase,sway,sway_phase,heave,heave_phase,roll,roll_phase,"
                      b"pitch,pitch_phase,yaw,yaw_phase\n0.5,180,0,0,0,0,1,0,0,0,0,0,0,0\n", "at least 2"),
}


@pytest.mark.parametrize("case", [*HOSTILE, "folder", "missing"])
def test_a_hostile_rao_resource_is_one_line_and_no_crash(vessel_fmu, tmp_path, case):
    data, expected = HOSTILE.get(case, (None, {"folder": "cannot read raos.csv", "missing": "cannot open raos.csv"}
                                        .get(case)))
    fmu = with_raos(vessel_fmu, tmp_path / f"{case}.fmu", data, folder=case == "folder")
    vm.listen()
    vessel = vm.Slave(fmu, case, tmp_path / "unzip")
    vessel.fmu.setupExperiment(startTime=0.0)
    vessel.fmu.enterInitializationMode()
    vessel.set_values({"sea.significant_wave_height": 2.5})
    with pytest.raises(Exception, match="status 3"):
        vessel.fmu.exitInitializationMode()
    errors = [m for status, _, m in vessel.messages if status == 3]
    assert len(errors) == 1 and "\n" not in errors[0] and expected in errors[0], vessel.messages
    vessel.fmu.freeInstance()


def supply_path() -> Path:
    """The MSS supply vessel's .re1 as tests/sea_raos.rs finds it: BEAM_IMPACT_SUPPLY_RE1, else
    shared/data/... beside the checkout or any folder above it (a clone elsewhere, as CI's), else
    /work/shared/data/...; the first that exists."""
    if os.environ.get("BEAM_IMPACT_SUPPLY_RE1"):
        return Path(os.environ["BEAM_IMPACT_SUPPLY_RE1"])
    tail = Path("shared") / "data" / "mss-supply-vessel" / "supply.re1"
    candidates = [folder / tail for folder in ROOT.parents] + [Path("/work") / tail]
    return next((c for c in candidates if c.is_file()), candidates[0])


SUPPLY = supply_path()


def host_library() -> Path:
    exe = Path(binary())
    for candidate in (exe.with_name("libbeam_impact.so"), exe.with_name("deps") / "libbeam_impact.so"):
        if candidate.is_file():
            return candidate
    pytest.skip(f"no libbeam_impact.so beside {exe} to pack with")


@pytest.mark.skipif(not SUPPLY.exists(), reason=f"{SUPPLY} (the MSS supply vessel's VERES RAOs) is not beside the repository")
def test_a_veres_sea_packed_with_its_scenario_equals_beam_impact_sea(tmp_path):
    """`pack --ssp --scenario` with a [sea] naming a VERES .re1 (the MSS supply vessel's, read where
    it lies, copied beside the scenario only for this test): the SSD binds the sea, the vessel FMU's
    resources/raos.csv is the table written as our CSV (src/model/sea/raos_write.rs), and the FMU with
    the SSD's bindings gives `beam-impact sea`'s columns on that scenario (which reads the .re1
    itself) to the same 1e-12: the CSV's amplitudes and phases in shortest round-trip form give back
    each complex RAO to a few ulp. Heading 150 deg, between VERES's headings, on its mirrored side."""
    shutil.copy(SUPPLY, tmp_path / "supply.re1")
    (tmp_path / "supply.toml").write_text(
        'duration = 3.0\n\n[sea]\nsignificant_wave_height = 2.0\npeak_period = 9.0\nheading = 150.0\nseed = 5\n'
        'raos = "supply.re1"\nhinge_point = [-8.0, 2.0, 6.0]\nclamp_point = [12.0, 1.0, 6.0]\narrestor_direction = 160.0\n')
    out = tmp_path / "fmu"
    done = subprocess.run([binary(), "pack", "--ssp", "--no-zigbuild", "--library", str(host_library()), "--scenario",
                           str(tmp_path / "supply.toml"), "--out", str(out)], capture_output=True, text=True, timeout=300,
                          env={**os.environ, "PATH": "/usr/local/bin:/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr
    ssp = out / "GangwayOnVessel.ssp"
    with zipfile.ZipFile(ssp) as z:
        z.extract("resources/VesselMotion.fmu", tmp_path)
    fmu = tmp_path / "resources" / "VesselMotion.fmu"
    with zipfile.ZipFile(fmu) as z:
        assert z.read("resources/raos.csv").startswith(b"# The RAOs of ")
    sys.path.insert(0, str(Path(__file__).parent))
    import test_ssp

    bound = test_ssp.bindings(ssp)["vessel"]
    assert bound["sea.significant_wave_height"] == 2.0 and bound["sea.heading"] == 150.0 and bound["clamp.y"] == 1.0
    record = sea_record(tmp_path, tmp_path / "supply.toml", 30.0)
    got, messages = simulate(fmu, tmp_path / "supply", bound, len(record) - 1)
    assert not messages, messages
    worst = assert_columns_equal(got, record)
    print(f"largest difference: {worst:.2e} of the column's largest value")


BAD_SEA = [
    ({"sea.significant_wave_height": 30.0}, "sea.significant_wave_height (m) must be in (0, 20]"),
    ({"sea.significant_wave_height": -1.0}, "sea.significant_wave_height (m) must be in (0, 20]"),
    ({"sea.peak_period": 1.0}, "sea.peak_period (s) must be in [2, 30], got 1"),
    ({"sea.peak_period": 3.0}, "steeper than a sea can be"),
    ({"sea.spectrum": 2.0}, "sea.spectrum must be 0 (JONSWAP) or 1 (Pierson-Moskowitz), got 2"),
    ({"sea.spectrum": 1.0, "sea.peak_enhancement": 3.3}, "sea.peak_enhancement must be 0 with sea.spectrum = 1"),
    ({"sea.heading": 400.0}, "sea.heading (deg) must be in [0, 360], got 400"),
    ({"sea.seed": 1e30}, "sea.seed must be a whole number from 0 to 2^53"),
    ({"sea.seed": 0.5}, "sea.seed must be a whole number from 0 to 2^53"),
    ({"sea.components": 0.0}, "sea.components must be a whole number from 1 to 100000, got 0"),
    ({"sea.components": 1e12}, "sea.components must be a whole number from 1 to 100000"),
    ({"sea.frequency_min": 0.05}, "not within the RAO file's frequencies, 0.1 to 3 rad/s"),
    # 1.5 to 3 rad/s: the message beam-impact gives for this [sea] too
    ({"sea.frequency_min": 1.5}, "range 1.5 to 3 rad/s holds 8.4 % of the spectrum's variance, less than 95 %"),
    ({"clamp.y": 600.0}, "must be within 500 m of the motion reference point"),
    ({"hinge.on_vessel": False, "clamp.on_vessel": False}, "no support is on the vessel"),
]


@pytest.mark.parametrize("parameters,expected", BAD_SEA, ids=[str(i) for i in range(len(BAD_SEA))])
def test_a_bad_sea_parameter_is_one_line(vessel_fmu, tmp_path, parameters, expected):
    vm.listen()
    vessel = vm.Slave(vessel_fmu, "bad", tmp_path / "unzip")
    vessel.fmu.setupExperiment(startTime=0.0)
    vessel.fmu.enterInitializationMode()
    vessel.set_values({"sea.significant_wave_height": 2.5, **parameters})
    with pytest.raises(Exception, match="status 3"):
        vessel.fmu.exitInitializationMode()
    errors = [m for status, _, m in vessel.messages if status == 3]
    assert len(errors) == 1 and "\n" not in errors[0] and expected in errors[0], vessel.messages
    vessel.fmu.freeInstance()
