"""The packed library loads on old Linux hosts (issue 8, item 7).

Goal: the shared library inside each packed FMU needs no glibc symbol newer than GLIBC_2.17
(manylinux2014: RHEL 7/8, Ubuntu 20.04, Debian 11 load it), read from `objdump -T` (every dynamic
symbol with its version, weak ones included), and the FMU still runs in fmpy.

`beam-impact pack` builds such a library when cargo-zigbuild is on PATH; tests/run_all.sh installs
the pinned cargo-zigbuild and ziglang and sets BEAM_IMPACT_REQUIRE_GLIBC_2_17=1, so there the check
must pass. Elsewhere an FMU packed from the host build (`--no-zigbuild`, or no cargo-zigbuild)
is skipped with the version it needs.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import zipfile
from pathlib import Path

import fmpy
import pytest

ROOT = Path(__file__).resolve().parents[2]
FMU_DIR = Path(os.environ.get("BEAM_IMPACT_FMU_DIR", str(ROOT / "target" / "fmu")))
BINARIES = {"fmi2": "binaries/linux64/BeamImpact.so", "fmi3": "binaries/x86_64-linux/BeamImpact.so"}
HIGHEST = (2, 17)
REQUIRED = os.environ.get("BEAM_IMPACT_REQUIRE_GLIBC_2_17") == "1"


def glibc_versions(library: Path) -> set[tuple[int, ...]]:
    """Every GLIBC_x.y[.z] version the library's dynamic symbols refer to."""
    objdump = shutil.which("objdump")
    assert objdump, "objdump not found (binutils, installed with gcc)"
    table = subprocess.run([objdump, "-T", str(library)], check=True, capture_output=True, text=True).stdout
    return {tuple(int(x) for x in v.split(".")) for v in re.findall(r"\bGLIBC_(\d+(?:\.\d+)+)\b", table)}


@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_packed_library_needs_at_most_glibc_2_17(version, tmp_path):
    fmu = FMU_DIR / version / "BeamImpact.fmu"
    assert fmu.exists(), f"{fmu} not found: run `beam-impact pack` or set BEAM_IMPACT_FMU_DIR"
    with zipfile.ZipFile(fmu) as archive:
        library = Path(archive.extract(BINARIES[version], tmp_path))
    versions = glibc_versions(library)
    assert versions, "no GLIBC symbol versions found: not a glibc-linked library?"
    highest = max(versions)
    name = "GLIBC_" + ".".join(map(str, highest))
    if highest > HIGHEST and not REQUIRED:
        pytest.skip(f"{fmu} was packed from the host build ({name}): pack with cargo-zigbuild on PATH for glibc 2.17")
    assert highest <= HIGHEST, f"{fmu}: the library needs {name}, newer than GLIBC_2.17"


def test_the_ssps_vessel_library_needs_at_most_glibc_2_17(tmp_path):
    """GangwayOnVessel.ssp's vessel-motion library (`pack --ssp` compiles it with the same zig for
    glibc 2.17, or with the host's cc without zig) holds to the same bound."""
    ssp = FMU_DIR / "GangwayOnVessel.ssp"
    assert ssp.exists(), f"{ssp} not found: run `beam-impact pack --ssp` or set BEAM_IMPACT_FMU_DIR"
    with zipfile.ZipFile(ssp) as archive:
        fmu = Path(archive.extract("resources/VesselMotion.fmu", tmp_path))
    with zipfile.ZipFile(fmu) as archive:
        library = Path(archive.extract("binaries/linux64/VesselMotion.so", tmp_path))
    versions = glibc_versions(library)
    assert versions, "no GLIBC symbol versions found: not a glibc-linked library?"
    name = "GLIBC_" + ".".join(map(str, max(versions)))
    if max(versions) > HIGHEST and not REQUIRED:
        pytest.skip(f"{ssp}'s vessel library was built with the host's cc ({name}): pack with cargo-zigbuild on PATH")
    assert max(versions) <= HIGHEST, f"{ssp}: the vessel library needs {name}, newer than GLIBC_2.17"


@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_packed_fmu_runs(version, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = fmpy.simulate_fmu(
        str(FMU_DIR / version / "BeamImpact.fmu"),
        stop_time=0.5,
        output_interval=1e-3,
        start_values={"log.path": ""},
        output=["peak.lower.tip_deflection"],
    )
    # The first impact's arrestor deflection, 0.657 m in the paper run (README), reached by 0.5 s.
    assert abs(result["peak.lower.tip_deflection"][-1] - 0.657) < 0.01


def fmi_functions() -> set[str]:
    """Every `extern "C" fn fmi2*/fmi3*` of the source (what scripts/cross-build.sh exports too)."""
    names = set()
    for source in (ROOT / "src" / "fmi").glob("*.rs"):
        names.update(re.findall(r'extern "C" fn (fmi[23]\w+)', source.read_text()))
    return names


@pytest.mark.parametrize("version", ["fmi2", "fmi3"])
def test_packed_library_exports_the_fmi_functions_only(version, tmp_path):
    """Issue 18: each binary exports the FMI functions and nothing else of ours (rustc's version
    script for a cdylib on Linux), and needs only the C runtime's libraries."""
    fmu = FMU_DIR / version / "BeamImpact.fmu"
    with zipfile.ZipFile(fmu) as archive:
        library = Path(archive.extract(BINARIES[version], tmp_path))
    objdump = shutil.which("objdump")
    assert objdump, "objdump not found (binutils, installed with gcc)"
    table = subprocess.run([objdump, "-T", str(library)], check=True, capture_output=True, text=True).stdout
    defined = {
        line.split()[-1] for line in table.splitlines() if re.match(r"^[0-9a-f]{16} g", line) and "*UND*" not in line
    }
    expected = fmi_functions()
    assert len(expected) > 100, "the FMI functions were not found in src/fmi"
    assert defined == expected, f"extra: {sorted(defined - expected)[:5]}, missing: {sorted(expected - defined)[:5]}"
    headers = subprocess.run([objdump, "-p", str(library)], check=True, capture_output=True, text=True).stdout
    needed = set(re.findall(r"NEEDED\s+(\S+)", headers))
    system = {"libc.so.6", "libm.so.6", "libgcc_s.so.1", "libpthread.so.0", "libdl.so.2", "librt.so.1", "ld-linux-x86-64.so.2"}
    assert needed <= system, f"links more than the C runtime: {sorted(needed - system)}"
