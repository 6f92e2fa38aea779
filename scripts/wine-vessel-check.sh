#!/bin/sh
# Proves the vessel-motion FMU's win64 DLL in GangwayOnVessel.ssp works: loads it under wine64
# (scripts/cross-toolchain.sh --wine) with a small C importer built for Windows by zig
# (tests/wine/vessel_importer.c), and the same importer built for Linux against the SSP's Linux
# library; each sets the wave phase, steps to 3 s in 1 ms steps with made-up reactions as inputs
# and prints every Real output every 0.5 s. The two platforms' numbers must agree to 1e-12
# relative (allowing the C libraries' cos and sin, UCRT against glibc, to differ in the last bit;
# measured: all 119 values equal bit for bit).
#
# Usage: scripts/wine-vessel-check.sh [GangwayOnVessel.ssp]
#   default: target/fmu/GangwayOnVessel.ssp (beam-impact pack --ssp --platforms linux,windows)
set -eu

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CROSS=${BEAM_IMPACT_CROSS_DIR:-$ROOT/.cross}
SSP=${1:-$ROOT/target/fmu/GangwayOnVessel.ssp}
WORK=$ROOT/target/cross/wine-vessel
WINE=$CROSS/wine/root

fail() {
    echo "wine-vessel-check: $*" >&2
    exit 1
}
[ -x "$WINE/usr/lib/wine/wine64" ] || fail "no wine64 in $CROSS/wine: run scripts/cross-toolchain.sh --wine"
[ -f "$SSP" ] || fail "no $SSP: run beam-impact pack --ssp --platforms linux,windows"
command -v cc >/dev/null || fail "cc is missing (the Linux importer)"

rm -rf "$WORK"
mkdir -p "$WORK"
python3 - "$SSP" "$WORK" <<'PY' || fail "$SSP has no Windows and Linux vessel libraries (pack --ssp --platforms linux,windows)"
import io, sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as ssp:
    fmu = zipfile.ZipFile(io.BytesIO(ssp.read("resources/VesselMotion.fmu")))
for member, name in [("binaries/win64/VesselMotion.dll", "VesselMotion.dll"), ("binaries/linux64/VesselMotion.so", "VesselMotion.so")]:
    open(f"{sys.argv[2]}/{name}", "wb").write(fmu.read(member))
PY
ZIG="$CROSS/venv/bin/python -m ziglang"
$ZIG cc -target x86_64-windows-gnu -O2 -o "$WORK/vessel_importer.exe" "$ROOT/tests/wine/vessel_importer.c"
rm -f "$WORK"/*.lib "$WORK"/*.pdb
cc -O2 -o "$WORK/vessel_importer" "$ROOT/tests/wine/vessel_importer.c" -ldl

CACHE=${BEAM_IMPACT_CROSS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/beam-impact-cross}
export WINEPREFIX="$CACHE/wine-prefix-8.0" WINEDEBUG=-all WINEDLLPATH="$WINE/usr/x86_64-w64-mingw32/lib"
export WINEDLLOVERRIDES="mscoree,mshtml="
trap '"$WINE/usr/lib/wine/wineserver" -k 2>/dev/null || true' EXIT
[ -f "$WINEPREFIX/.ready" ] || fail "no wine prefix in $WINEPREFIX: run scripts/wine-check.sh once (it creates it)"
WIN_DIR="Z:$(echo "$WORK" | tr / '\\')"

cd "$WORK"
timeout 600 "$WINE/usr/lib/wine/wine64" vessel_importer.exe "$WIN_DIR\\VesselMotion.dll" >windows.txt 2>windows.err ||
    fail "the importer failed under wine: $(tail -3 windows.err | tr '\n' ' ')"
timeout 600 ./vessel_importer "$WORK/VesselMotion.so" >linux.txt 2>linux.err ||
    fail "the importer failed on Linux: $(tail -3 linux.err | tr '\n' ' ')"

python3 - windows.txt linux.txt <<'PY'
import sys
rows = [open(f).read().split("\n") for f in sys.argv[1:3]]
assert len(rows[0]) == len(rows[1]) > 100, "the two runs printed different numbers of values"
worst, same = 0.0, 0
for a, b in zip(*rows):
    if not a:
        continue
    ka, va = a.rsplit(" ", 1)
    kb, vb = b.rsplit(" ", 1)
    assert ka == kb, (a, b)
    x, y = float(va), float(vb)
    same += x == y
    worst = max(worst, abs(x - y) / max(abs(y), 1e-300) if y else abs(x))
print(f"wine-vessel-check: {len(rows[1]) - 1} values, {same} equal bit for bit, largest relative difference {worst:.1e}")
sys.exit(0 if worst <= 1e-12 else 1)
PY
