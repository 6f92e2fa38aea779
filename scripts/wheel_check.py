#!/usr/bin/env python3
"""Checks one wheel of scripts/build-wheels.sh, as the FMU's binaries are checked (issue 31, item 2),
and prints one line saying what it holds; exits 1 with one line per problem otherwise.

    wheel_check.py WHEEL linux|windows|macos FMU_PLATFORMS(linux|all)

- the name's tags (`beam_impact-V-cp39-abi3-PLATFORM.whl`) and the WHEEL file's `Tag:` lines agree,
  and are the platform's: manylinux_2_17_x86_64.manylinux2014_x86_64, win_amd64, or
  macosx_*_x86_64.macosx_*_arm64.macosx_*_universal2; `Root-Is-Purelib: false`;
- RECORD lists every file with its SHA-256 and size, and they match;
- the packed FMUs are there (beam_impact/fmus/fmi2/ and fmi3/BeamImpact.fmu), each holding the
  binaries of FMU_PLATFORMS and no others;
- the native module: Linux `_native.abi3.so` (objdump -T / -p: GLIBC_2.17 at most, no libpython,
  PyInit__native exported); Windows `_native.pyd` (scripts/pe_info.py: x86-64, exports
  PyInit__native and nothing else, imports python3.dll, the stable ABI's, and system DLLs only);
  macOS `_native.abi3.so` (scripts/macho_info.py: an x86_64 and an arm64 slice, each exporting
  _PyInit__native, linking system libraries only and no libpython, the arm64 slice's code
  signature verified).

Standard library only, besides objdump for the Linux module.
"""

from __future__ import annotations

import base64
import csv
import hashlib
import io
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import macho_info  # noqa: E402
import pe_info  # noqa: E402

#: The platform tags of each wheel (the part of the name after `cp39-abi3-`, split at the dots, in
#: any order): one component matching each pattern, and no other.
PLATFORM_TAGS = {
    "linux": [r"manylinux_2_17_x86_64", r"manylinux2014_x86_64"],
    "windows": [r"win_amd64"],
    "macos": [r"macosx_\d+_\d+_x86_64", r"macosx_\d+_\d+_arm64", r"macosx_\d+_\d+_universal2"],
}
#: The native module's file inside the wheel.
MODULE = {"linux": "beam_impact/_native.abi3.so", "windows": "beam_impact/_native.pyd",
          "macos": "beam_impact/_native.abi3.so"}
#: The binaries each FMU holds, per packed platform set (as scripts/cross-check.sh expects them).
FMU_BINARIES = {
    "fmi2": {"linux": ["binaries/linux64/BeamImpact.so"],
             "windows": ["binaries/win64/BeamImpact.dll"],
             "darwin": ["binaries/darwin64/BeamImpact.dylib"]},
    "fmi3": {"linux": ["binaries/x86_64-linux/BeamImpact.so"],
             "windows": ["binaries/x86_64-windows/BeamImpact.dll"],
             "darwin": ["binaries/x86_64-darwin/BeamImpact.dylib", "binaries/aarch64-darwin/BeamImpact.dylib"]},
}
#: Windows system DLLs a Rust module may import (scripts/cross-build.sh's list), besides python3.dll.
SYSTEM_DLL = re.compile(r"^(kernel32|ntdll|ws2_32|userenv|bcryptprimitives|advapi32|bcrypt|api-ms-win-[a-z0-9-]+"
                        r"|ucrtbase|msvcrt)\.dll$")
#: macOS system libraries a Rust module may link (scripts/cross-build.sh's list).
SYSTEM_DYLIB = re.compile(r"^(/usr/lib/(libSystem\.B|libiconv\.2|libcharset\.1|libresolv\.9)\.dylib"
                          r"|/System/Library/Frameworks/(CoreFoundation|Security)\.framework/Versions/A/"
                          r"(CoreFoundation|Security))$")


def record_problems(archive: zipfile.ZipFile) -> list[str]:
    """RECORD's hashes and sizes against the files, and every file listed."""
    names = archive.namelist()
    record = [n for n in names if n.endswith(".dist-info/RECORD")]
    if len(record) != 1:
        return [f"{len(record)} RECORD files"]
    problems, listed = [], set()
    for row in csv.reader(io.StringIO(archive.read(record[0]).decode())):
        if not row:
            continue
        name, digest, size = row
        listed.add(name)
        if name == record[0]:
            continue
        if name not in names:
            problems.append(f"RECORD lists {name}, which the wheel lacks")
            continue
        data = archive.read(name)
        want = "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        if digest != want or int(size) != len(data):
            problems.append(f"RECORD's hash or size of {name} does not match the file")
    unlisted = sorted(set(n for n in names if not n.endswith("/")) - listed)
    if unlisted:
        problems.append(f"RECORD lists not {unlisted}")
    return problems


def fmu_problems(archive: zipfile.ZipFile, fmu_platforms: str) -> list[str]:
    packed = ["linux"] if fmu_platforms == "linux" else ["linux", "windows", "darwin"]
    problems = []
    for fmi, by_platform in FMU_BINARIES.items():
        name = f"beam_impact/fmus/{fmi}/BeamImpact.fmu"
        if name not in archive.namelist():
            problems.append(f"no {name}")
            continue
        with zipfile.ZipFile(io.BytesIO(archive.read(name))) as fmu:
            have = {n for n in fmu.namelist() if n.startswith("binaries/") and not n.endswith("/")}
            if "modelDescription.xml" not in fmu.namelist():
                problems.append(f"{name} has no modelDescription.xml")
        want = {b for p in packed for b in by_platform[p]}
        if have != want:
            problems.append(f"{name} holds the binaries {sorted(have)}, not {sorted(want)}")
    return problems


def linux_module(path: Path) -> tuple[list[str], str]:
    objdump = shutil.which("objdump")
    if objdump is None:
        return ["objdump not found (binutils)"], ""
    symbols = subprocess.run([objdump, "-T", str(path)], check=True, capture_output=True, text=True).stdout
    headers = subprocess.run([objdump, "-p", str(path)], check=True, capture_output=True, text=True).stdout
    problems = []
    versions = {tuple(int(x) for x in v.split(".")) for v in re.findall(r"\bGLIBC_(\d+(?:\.\d+)+)\b", symbols)}
    highest = max(versions) if versions else None
    if highest is None or highest > (2, 17):
        problems.append(f"the module needs GLIBC_{'.'.join(map(str, highest or ()))}, not 2.17 at most")
    needed = re.findall(r"^\s*NEEDED\s+(\S+)", headers, re.MULTILINE)
    if any("python" in n for n in needed):
        problems.append(f"the module links libpython ({needed}): abi3 modules take Python's symbols from the process")
    if not re.search(r"\sPyInit__native$", symbols, re.MULTILINE):
        problems.append("the module does not export PyInit__native")
    glibc = "GLIBC_" + ".".join(map(str, highest or ()))
    return problems, f"needs {glibc} at most; links {' '.join(needed)}; exports PyInit__native"


def windows_module(path: Path) -> tuple[list[str], str]:
    machine, exports, imports = pe_info.read_pe(path.read_bytes())
    problems = []
    if machine != 0x8664:
        problems.append(f"the module's machine is {machine:#x}, not x86-64 (0x8664)")
    if exports != ["PyInit__native"]:
        problems.append(f"the module exports {len(exports)} names ({' '.join(exports[:4])} ...), not PyInit__native alone")
    lower = [i.lower() for i in imports]
    if "python3.dll" not in lower:
        problems.append(f"the module imports no python3.dll (the stable ABI's): {lower}")
    other = [i for i in lower if i != "python3.dll" and not SYSTEM_DLL.match(i)]
    if other:
        problems.append(f"the module imports non-system DLLs {other} (abi3 wants python3.dll only)")
    return problems, f"exports {' '.join(exports)}; imports {' '.join(lower)}"


def macos_module(path: Path) -> tuple[list[str], str]:
    facts: dict[str, dict[str, list[str]]] = {}
    slices = []
    for line in macho_info.info(str(path)):
        key, _, rest = line.partition(" ")
        if key == "slice":
            slices.append(rest.split()[0])
        elif key != "file":
            sub, _, value = rest.partition(" ")
            facts.setdefault(key, {}).setdefault(sub, []).append(value)
    problems = []
    if slices != ["x86_64", "arm64"]:
        problems.append(f"the module's slices are {slices}, not x86_64 and arm64 (universal2)")
    summary = []
    for arch in slices:
        f = facts.get(arch, {})
        dylibs = [d.split(" (")[0] for d in f.get("dylib", [])]
        bad = [d for d in dylibs if not SYSTEM_DYLIB.match(d)]
        if bad:
            problems.append(f"the {arch} slice links non-system libraries {bad} (abi3 takes Python's symbols from the process)")
        if "_PyInit__native" not in f.get("export", []):
            problems.append(f"the {arch} slice does not export _PyInit__native")
        signature = (f.get("signature") or ["none"])[0]
        if arch == "arm64" and not signature.startswith("ok"):
            problems.append(f"the arm64 slice's code signature does not verify ({signature}): macOS on arm64 refuses it")
        minos = (f.get("minos") or ["?"])[0].split()[0]
        summary.append(f"{arch}: {(f.get('filetype') or ['?'])[0]}, macOS >= {minos}, "
                       f"{len(f.get('export', []))} exports incl. _PyInit__native, links {' '.join(sorted(set(dylibs)))}, "
                       f"signature {signature.split(' (')[0]}")
    return problems, "; ".join(summary)


def main() -> int:
    if len(sys.argv) != 4 or sys.argv[2] not in PLATFORM_TAGS or sys.argv[3] not in ("linux", "all"):
        print("usage: wheel_check.py WHEEL linux|windows|macos linux|all", file=sys.stderr)
        return 2
    wheel, platform, fmu_platforms = Path(sys.argv[1]), sys.argv[2], sys.argv[3]
    problems = []
    m = re.fullmatch(r"beam_impact-([^-]+)-cp39-abi3-(.+)\.whl", wheel.name)
    components = m.group(2).split(".") if m else []
    patterns = PLATFORM_TAGS[platform]
    if len(components) != len(patterns) or not all(sum(bool(re.fullmatch(p, c)) for c in components) == 1
                                                   for p in patterns):
        problems.append(f"the name {wheel.name} is not beam_impact-V-cp39-abi3-{'.'.join(patterns)}.whl "
                        "(its platform tags in any order)")
    name_tags = {f"cp39-abi3-{c}" for c in components}
    with zipfile.ZipFile(wheel) as archive, tempfile.TemporaryDirectory() as scratch:
        names = archive.namelist()
        metadata = [n for n in names if n.endswith(".dist-info/WHEEL")]
        text = archive.read(metadata[0]).decode() if len(metadata) == 1 else ""
        tags = set(re.findall(r"^Tag: (\S+)$", text, re.MULTILINE))
        if not tags or tags != name_tags:
            problems.append(f"WHEEL's tags {sorted(tags)} are not the name's {sorted(name_tags)}")
        if "Root-Is-Purelib: false" not in text:
            problems.append("WHEEL does not say Root-Is-Purelib: false")
        problems += record_problems(archive)
        problems += fmu_problems(archive, fmu_platforms)
        modules = [n for n in names if re.fullmatch(r"beam_impact/_native\..*", n)]
        if modules != [MODULE[platform]]:
            problems.append(f"the native module is {modules}, not [{MODULE[platform]}]")
            summary = ""
        else:
            module = Path(archive.extract(modules[0], scratch))
            check = {"linux": linux_module, "windows": windows_module, "macos": macos_module}[platform]
            found, summary = check(module)
            problems += found
    for p in problems:
        print(f"wheel_check: {wheel.name}: {p}", file=sys.stderr)
    if problems:
        return 1
    print(f"wheel_check: {wheel.name} ({wheel.stat().st_size // 1024} KiB): tags {' '.join(sorted(tags))} "
          f"(name and WHEEL); RECORD matches; FMUs fmi2 and fmi3 with {fmu_platforms} binaries; "
          f"{MODULE[platform]}: {summary}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
