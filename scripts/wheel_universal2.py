#!/usr/bin/env python3
"""Makes the macOS universal2 wheel out of an x86_64 and an arm64 wheel of the same package
(scripts/build-wheels.sh builds each slice as scripts/cross-build.sh builds the FMU's, in its own
cached target directory, which maturin's own universal2 target cannot reuse):

    wheel_universal2.py X86_64.whl ARM64.whl OUT_DIR

Every file of the two wheels must be the same bytes, except the native module (merged into one
fat Mach-O by scripts/macho_info.py --merge, x86_64 slice first), the software bill of materials
maturin writes per target (`*.dist-info/sboms/NAME.json`: the x86_64 one is kept under its name,
the arm64 one added as `NAME.arm64.json`), `WHEEL` (its `Tag:` lines become
the three tags maturin gives a universal2 wheel: macosx_A_x86_64, macosx_B_arm64 and
macosx_A_universal2, A and B the input wheels' versions) and `RECORD` (written anew). Prints the
new wheel's path; exits 1 with one line otherwise. Standard library only.
"""

from __future__ import annotations

import base64
import hashlib
import re
import sys
import tempfile
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import macho_info  # noqa: E402

MODULE = "beam_impact/_native.abi3.so"


def platform_tag(wheel: Path, arch: str) -> tuple[str, str, str]:
    """(distribution-version, python-abi, macosx_X_Y) of a wheel named ...-cp39-abi3-macosx_X_Y_ARCH.whl."""
    m = re.fullmatch(rf"(.+)-(cp\d+-abi3)-(macosx_\d+_\d+)_{arch}\.whl", wheel.name)
    if not m:
        sys.exit(f"wheel_universal2: {wheel.name} is not a cp3x-abi3 macosx_*_{arch} wheel")
    return m.group(1), m.group(2), m.group(3)


def digest(data: bytes) -> str:
    return "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()


def main() -> int:
    if len(sys.argv) != 4:
        print("usage: wheel_universal2.py X86_64.whl ARM64.whl OUT_DIR", file=sys.stderr)
        return 2
    x86, arm, out_dir = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
    name, abi, x86_version = platform_tag(x86, "x86_64")
    arm_name, arm_abi, arm_version = platform_tag(arm, "arm64")
    if (name, abi) != (arm_name, arm_abi):
        sys.exit(f"wheel_universal2: {x86.name} and {arm.name} are not the same package and ABI")
    tags = [f"{abi}-{x86_version}_x86_64", f"{abi}-{arm_version}_arm64", f"{abi}-{x86_version}_universal2"]
    out = out_dir / f"{name}-{abi}-{'.'.join(t.split('-', 2)[2] for t in tags)}.whl"
    with zipfile.ZipFile(x86) as a, zipfile.ZipFile(arm) as b, tempfile.TemporaryDirectory() as scratch:
        names = [n for n in a.namelist() if not n.endswith("/")]
        if sorted(names) != sorted(n for n in b.namelist() if not n.endswith("/")):
            sys.exit(f"wheel_universal2: {x86.name} and {arm.name} hold different files")
        special = {MODULE} | {n for n in names if re.fullmatch(r"[^/]+\.dist-info/(WHEEL|RECORD)", n)}
        if MODULE not in names or len(special) != 3:
            sys.exit(f"wheel_universal2: {x86.name} lacks {MODULE}, WHEEL or RECORD")
        sboms = {n for n in names if re.fullmatch(r"[^/]+\.dist-info/sboms/[^/]+\.json", n) and a.read(n) != b.read(n)}
        differ = [n for n in names if n not in special | sboms and a.read(n) != b.read(n)]
        if differ:
            sys.exit(f"wheel_universal2: the wheels' {differ} differ (only the native module may)")
        thin = [Path(scratch) / "x86_64.so", Path(scratch) / "arm64.so"]
        thin[0].write_bytes(a.read(MODULE))
        thin[1].write_bytes(b.read(MODULE))
        fat = Path(scratch) / "fat.so"
        macho_info.merge(str(fat), [str(p) for p in thin])
        record_name = next(n for n in names if n.endswith(".dist-info/RECORD"))
        wheel_name = next(n for n in names if n.endswith(".dist-info/WHEEL"))
        wheel_text = a.read(wheel_name).decode()
        if not re.search(r"^Tag: ", wheel_text, re.MULTILINE):
            sys.exit(f"wheel_universal2: {x86.name}'s WHEEL has no Tag line")
        kept = [line for line in wheel_text.splitlines() if not line.startswith("Tag: ")]
        wheel_text = "\n".join(kept + [f"Tag: {t}" for t in tags]) + "\n"
        out_dir.mkdir(parents=True, exist_ok=True)
        partial = out.with_suffix(".whl.part")
        record = []
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as w:
            for n in names:
                if n == record_name:
                    continue
                data = fat.read_bytes() if n == MODULE else wheel_text.encode() if n == wheel_name else a.read(n)
                info = zipfile.ZipInfo(n, date_time=a.getinfo(n).date_time)
                info.external_attr = a.getinfo(n).external_attr
                info.compress_type = zipfile.ZIP_DEFLATED
                w.writestr(info, data)
                record.append(f"{n},{digest(data)},{len(data)}")
            for n in sorted(sboms):
                data = b.read(n)
                extra = n[: -len(".json")] + ".arm64.json"
                info = zipfile.ZipInfo(extra, date_time=b.getinfo(n).date_time)
                info.external_attr = b.getinfo(n).external_attr
                info.compress_type = zipfile.ZIP_DEFLATED
                w.writestr(info, data)
                record.append(f"{extra},{digest(data)},{len(data)}")
            record.append(f"{record_name},,")
            info = zipfile.ZipInfo(record_name, date_time=a.getinfo(record_name).date_time)
            info.external_attr = a.getinfo(record_name).external_attr
            info.compress_type = zipfile.ZIP_DEFLATED
            w.writestr(info, "\n".join(record) + "\n")
        partial.replace(out)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
